#include "core/simulate.hpp"

namespace contact2d {

State initial_state(const Scene& scene) {
  State s = scene.initial;
  if (scene.shape == Shape::PointMass) {
    s.q.z() = 0.0;
    s.v.z() = 0.0;
  }
  return s;
}

RunResult run(const Scene& scene, const std::function<void(const Sample&)>& on_sample) {
  const Model model = make_model(scene);
  const SimParams& sim = scene.sim;
  const long long steps = step_count(sim);
  const long long stride = sample_stride(sim);
  State state = initial_state(scene);
  const DivergenceMonitor monitor(model, state);

  RunResult result;
  on_sample({0.0, state});
  for (long long i = 1; i <= steps; ++i) {
    const double t = static_cast<double>(i) * sim.dt;
    if (step(model, sim.integrator, sim.dt, state) == StepStatus::NewtonFailed) {
      result.divergence = Divergence{DivergenceKind::NewtonFailed, t, 0.0, 0.0};
    } else {
      result.divergence = monitor.check(state, t);
    }
    result.steps = i;
    if (result.divergence) return result;
    if (i % stride == 0 || i == steps) on_sample({t, state});
  }
  return result;
}

Trajectory simulate(const Scene& scene) {
  Trajectory trajectory;
  trajectory.samples.reserve(
      static_cast<size_t>(step_count(scene.sim) / sample_stride(scene.sim) + 2));
  const RunResult result = run(scene, [&](const Sample& s) { trajectory.samples.push_back(s); });
  trajectory.divergence = result.divergence;
  return trajectory;
}

}  // namespace contact2d
