// The run loop: step a scene from its initial state for sim.duration,
// checking the divergence rule after every step and handing every
// sim.output_dt-th state (and the first) to the caller.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "core/divergence.hpp"
#include "core/scene.hpp"

namespace contact2d {

struct Sample {
  double t = 0.0;
  State state;
};

struct RunResult {
  std::optional<Divergence> divergence;  // set when the run stopped early
  long long steps = 0;                   // steps taken
};

// Point mass: the state keeps θ = ω = 0 whatever the caller passed.
State initial_state(const Scene& scene);

RunResult run(const Scene& scene, const std::function<void(const Sample&)>& on_sample);

struct Trajectory {
  std::vector<Sample> samples;
  std::optional<Divergence> divergence;
};

Trajectory simulate(const Scene& scene);

}  // namespace contact2d
