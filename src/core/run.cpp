#include "core/run.hpp"

#include "core/cancel.hpp"

#include <algorithm>
#include <limits>

namespace contact2d {

std::optional<Divergence> check_step(StepStatus status, const Stepper& stepper,
                                     const DivergenceMonitor& monitor, double t,
                                     double applied_work, double* energy) {
  switch (status) {
    case StepStatus::NewtonFailed: return Divergence{DivergenceKind::NewtonFailed, t, 0.0, 0.0};
    case StepStatus::NonFinite:
      return Divergence{DivergenceKind::NonFinite, t, std::numeric_limits<double>::quiet_NaN(),
                        0.0};
    case StepStatus::Ok: break;
  }
  return monitor.check(stepper.state(), stepper.contacts(), t, applied_work, energy);
}

RunResult run(Stepper& stepper, const SimParams& sim,
              const std::function<void(const Sample&)>& on_sample) {
  const long long steps = step_count(sim);
  const long long stride = sample_stride(sim);
  const DivergenceMonitor monitor(stepper.model(), stepper.state(), stepper.contacts());

  RunResult result;
  EnergyBalance& balance = result.energy;
  result.available_energy = monitor.available_energy();
  balance.initial = balance.final = energy(stepper.model(), stepper.contacts(), stepper.state());
  balance.free_flight_gain = free_flight_gain(stepper.model(), sim.integrator, sim.dt, steps);
  balance.stability = stepper.stability();
  balance.tolerance = energy_rise_tolerance(balance.stability, monitor.available_energy()) +
                      balance.free_flight_gain;
  // Where the run ended (DepthRecord), also when it stops early.
  auto record_end = [&](double t) {
    result.depth.size = body_size(stepper.model().body);
    result.depth.time = t;
    result.depth.depth = max_penetration(stepper.contacts());
    result.depth.y = stepper.state().q.y();
  };
  double lowest = balance.initial;    // min over the steps so far
  bool contact_since_lowest = false;  // a contact was active since that minimum
  on_sample({0.0, stepper.state()});
  stepper.plan(steps);
  for (long long i = 1; i <= steps; ++i) {
    if ((i & 1023) == 0) throw_if_cancelled();  // a Python Ctrl-C (core/cancel.hpp)
    const double t = static_cast<double>(i) * sim.dt;
    double e = balance.final;
    result.divergence = check_step(stepper.step(), stepper, monitor, t, 0.0, &e);
    result.steps = i;
    if (result.divergence) {
      record_end(t);
      return result;
    }
    balance.final = e;
    const bool touching = !stepper.contacts().empty();
    if (e < lowest) {
      lowest = e;
      contact_since_lowest = touching;
    } else {
      contact_since_lowest = contact_since_lowest || touching;
    }
    if (e - lowest > balance.max_rise) {
      balance.max_rise = e - lowest;
      balance.time_of_max_rise = t;
      balance.rise_in_contact = contact_since_lowest;
    }
    if (i % stride == 0 || i == steps) on_sample({t, stepper.state()});
  }
  record_end(static_cast<double>(steps) * sim.dt);
  return result;
}

Trajectory simulate(Stepper& stepper, const SimParams& sim) {
  Trajectory trajectory;
  // Room for the samples of a usual run; a longer one grows as it streams
  // (reserving 1e9 samples up front would fail before the first step).
  const long long samples = step_count(sim) / sample_stride(sim) + 2;
  trajectory.samples.reserve(static_cast<size_t>(std::min<long long>(samples, 1 << 20)));
  const RunResult result =
      run(stepper, sim, [&](const Sample& s) { trajectory.samples.push_back(s); });
  trajectory.divergence = result.divergence;
  trajectory.energy = result.energy;
  trajectory.depth = result.depth;
  trajectory.available_energy = result.available_energy;
  return trajectory;
}

std::string nonphysical(const Trajectory& trajectory, const Scene& scene) {
  return describe_nonphysical(trajectory.energy, trajectory.depth, trajectory.available_energy,
                              scene);
}

Trajectory simulate(const Scene& scene) {
  ReferenceStepper stepper(scene);
  return simulate(stepper, scene.sim);
}

}  // namespace contact2d
