#include "core/stepper.hpp"

#include <limits>

#include "core/format.hpp"

namespace contact2d {

double RunFacts::value(const std::string& name) const {
  for (const auto& [key, v] : values)
    if (key == name) return v;
  return std::numeric_limits<double>::quiet_NaN();
}

State initial_state(const Scene& scene) {
  State s = scene.initial;
  if (!shape_features(scene.shape).turns) {  // θ is no degree of freedom
    s.q.z() = 0.0;
    s.v.z() = 0.0;
  }
  return s;
}

ReferenceStepper::ReferenceStepper(const Scene& scene)
    : model_(make_model(scene)),
      placed_(model_.obstacles),
      integrator_(scene.sim.integrator),
      dt_(scene.sim.dt),
      ws_(model_) {
  reset(initial_state(scene));
}

bool ReferenceStepper::move_obstacle(int index, const Vec2& offset) {
  if (index < 0 || static_cast<size_t>(index) >= placed_.size()) return false;
  const Obstacle& placed = placed_[static_cast<size_t>(index)];
  if (!placed.moves) return false;
  Obstacle& o = model_.obstacles[static_cast<size_t>(index)];
  o.a = placed.a + offset;
  o.b = placed.b + offset;
  return true;
}

void ReferenceStepper::reset(const State& state) {
  state_ = state;
  find_contacts(model_, state_.q, ws_.contacts);
}

std::string ReferenceStepper::describe() const {
  return "ref " + std::string(integrator_name(integrator_));
}

RunFacts ReferenceStepper::facts(const Scene& /*scene*/) const {
  RunFacts facts;
  const FrictionStep f = friction_step(model_, integrator_, dt_);
  if (!f.beyond()) return facts;
  const double scale = f.limit / f.rate_dt;  // what Δt or α may be, as a fraction
  facts.warnings.push_back(
      "friction stiffer than the step: its rate at rest times dt, (mu g alpha (1 + m l^2/I)" +
      std::string(shape_features(model_.body.shape).resists_rolling && model_.contact.mu_roll > 0.0
                      ? " + mu_roll m g alpha R/I"
                      : "") +
      ") dt = " + format_number("%.3g", f.rate_dt) + ", exceeds " +
      std::string(integrator_title(integrator_)) + "'s limit " + format_number("%.4g", f.limit) +
      " on a damper: at rest the slip overshoots zero every step, a two-step cycle in place of "
      "static friction (a rolling body creeps); dt <= " +
      format_number("%.2g", dt_ * scale) +
      " s, contact.alpha <= " + format_number("%.2g", model_.contact.alpha * scale) +
      " s/m or --integrator implicit_euler holds it");
  return facts;
}

}  // namespace contact2d
