// Differences between two trajectories sampled at the same times.
//
// Per sample i: position error e_i = |(x, y)_a − (x, y)_b| (Euclidean, m),
// angle error |θ_a − θ_b|, velocity error |(vx, vy)_a − (vx, vy)_b| and
// |ω_a − ω_b|. Reported: the maxima over samples, the RMS of e_i,
// √(Σ e_i² / N), and the errors at the last common sample.
#pragma once

#include "core/run.hpp"

namespace contact2d::mujoco {

struct TrajectoryErrors {
  long long samples = 0;         // common samples compared
  double max_pos = 0.0;          // m
  double rms_pos = 0.0;          // m
  double max_angle = 0.0;        // rad
  double max_vel = 0.0;          // m/s
  double max_omega = 0.0;        // rad/s
  double end_pos = 0.0;          // m
  double end_angle = 0.0;        // rad
  double time_of_max_pos = 0.0;  // s
};

// Compares the samples the two have in common (the shorter length); sample
// times must agree (they do when both follow the scene's sim settings).
TrajectoryErrors compare_trajectories(const Trajectory& a, const Trajectory& b);

}  // namespace contact2d::mujoco
