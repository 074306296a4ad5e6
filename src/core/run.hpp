// The run loop, the same for every engine (core/stepper.hpp):
//
//   for i = 1 … N (N = duration/Δt):
//     status = stepper.step()                                   advance one Δt
//     divergence = check_step(status, stepper, monitor, t)      core/divergence.hpp
//     stop at the first divergence; otherwise hand every output_dt-th state
//     (and the first and last) to the caller
//
// The game, which steps frame by frame with a player's force, calls
// stepper.step() and check_step() itself (it adds the force's work).
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "core/divergence.hpp"
#include "core/stepper.hpp"

namespace contact2d {

struct Sample {
  double t = 0.0;
  State state;
};

struct Trajectory {
  std::vector<Sample> samples;
  std::optional<Divergence> divergence;  // set when the run stopped early
  EnergyBalance energy;                  // over every step (core/divergence.hpp)
  DepthRecord depth;                     // over every step (core/divergence.hpp)
  double available_energy = 0.0;         // the monitor's E_avail, J
};

// Why a finished run is not physics (describe_nonphysical); empty when it is.
std::string nonphysical(const Trajectory& trajectory, const Scene& scene);

// The check after a step that ended at time t with `status`: the engine's
// own failure, else the divergence rule on the stepper's state and contacts.
// applied_work is the work done by applied forces so far.
std::optional<Divergence> check_step(StepStatus status, const Stepper& stepper,
                                     const DivergenceMonitor& monitor, double t,
                                     double applied_work = 0.0, double* energy = nullptr);

struct RunResult {
  std::optional<Divergence> divergence;  // set when the run stopped early
  long long steps = 0;                   // steps taken
  EnergyBalance energy;                  // over every step taken
  DepthRecord depth;                     // over every step taken
  double available_energy = 0.0;         // the monitor's E_avail, J
};

// Runs the stepper from its current state (time 0) for sim.duration at
// sim.dt, sampling every sim.output_dt (the stepper's own Δt must be sim.dt).
RunResult run(Stepper& stepper, const SimParams& sim,
              const std::function<void(const Sample&)>& on_sample);

// run() into a trajectory.
Trajectory simulate(Stepper& stepper, const SimParams& sim);

// The reference solver on a scene (its integrator, Δt and duration).
Trajectory simulate(const Scene& scene);

}  // namespace contact2d
