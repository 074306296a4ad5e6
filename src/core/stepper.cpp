#include "core/stepper.hpp"

#include <limits>

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

}  // namespace contact2d
