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
  // At the run's last state: where a body comes to rest (and a disc rolls),
  // on the contacts it rests on.
  const FrictionStep f = friction_step(model_, integrator_, dt_, ws_.contacts);
  if (!f.beyond()) return facts;
  // What Δt or α may be, as a fraction of theirs: below the cycle's onset.
  const double scale = f.onset * f.limit / f.rate_dt;
  const bool rolls =
      shape_features(model_.body.shape).resists_rolling && model_.contact.mu_roll > 0.0;
  facts.warnings.push_back(
      std::string(kFrictionStepWarning) +
      ": linearised at rest it is a damper whose rate times dt, (mu alpha Fn (1/m + r^2/I)" +
      (rolls ? std::string(" + mu_roll alpha Fn R/I") : std::string()) +
      ") dt = " + format_number("%.3g", f.rate_dt) + ", is past " +
      (f.onset < 1.0 ? format_number("%.0f", 100.0 * f.onset) + " % of " : std::string()) +
      std::string(integrator_title(integrator_)) + "'s limit " + format_number("%.4g", f.limit) +
      (f.onset < 1.0 ? std::string(" (on several contacts the cycle can begin below the limit)")
                     : std::string()) +
      ": at rest the slip overshoots zero every step, a two-step cycle in place of static "
      "friction (a rolling body creeps); dt <= " +
      format_number("%.2g", dt_ * scale) +
      " s, contact.alpha <= " + format_number("%.2g", model_.contact.alpha * scale) +
      " s/m or --integrator implicit_euler holds it");
  return facts;
}

}  // namespace contact2d
