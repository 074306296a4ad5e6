// The MuJoCo engine: a scene run through its generated MJCF.
//
// Steps mj_step with the scene's integrator (Euler, RK4 or implicit) from the
// keyframe "initial" and samples at the reference's times (t = 0, every
// sim.output_dt-th step and the last). The planar state is read from qpos
// and qvel: x = x0 + qpos[0], y = y0 + qpos[1] (x0, y0 the body's model
// position), θ = qpos[2], (vx, vy, ω) = qvel (0 for θ, ω without a hinge).
//
// Divergence: MuJoCo resets mjData silently when qacc goes bad (it only
// counts a warning), so after every step the adapter checks the bad-number
// counters and applies the reference's own rule (core/divergence.hpp) to the
// MuJoCo state; the run stops at the first failure and no later sample is
// recorded.
#pragma once

#include <string>
#include <vector>

#include "core/simulate.hpp"
#include "mujoco/mjcf.hpp"

namespace contact2d::mujoco {

struct MujocoRun {
  Trajectory trajectory;
  double seconds = 0.0;               // wall clock of the stepping alone
  std::vector<std::string> warnings;  // MuJoCo's runtime warnings
  SolverSettings settings;
};

// Generates the model, loads it (InputError on a load error or warning) and
// runs it.
MujocoRun run_mujoco(const Scene& scene, const MjcfOptions& options);

// Runs already generated MJCF text.
MujocoRun run_mujoco_xml(const Scene& scene, const std::string& xml, const std::string& origin);

}  // namespace contact2d::mujoco
