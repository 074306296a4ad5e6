// How far apart two trajectories are: the one error definition of the
// project, used by compare (reference against MuJoCo), the sweep (a run
// against the converged reference) and the report.
//
// At every common sample time t_i (i = 1 … N):
//   e_i   = ‖(x, y)_a − (x, y)_b‖          position error of the COM, m
//   θ_i   = |θ_a − θ_b|                     angle error, rad
//   v_i   = ‖(vx, vy)_a − (vx, vy)_b‖,  ω_i = |ω_a − ω_b|
// Reported: the maxima over the samples (and the time of the largest e_i),
// the RMS √(Σ e_i² / N), and the errors at the last common sample.
#pragma once

#include <vector>

#include "core/run.hpp"
#include "reference/dense_reference.hpp"

namespace contact2d::analysis {

struct TrajectoryError {
  size_t samples = 0;            // common samples compared
  double max_pos = 0.0;          // m
  double rms_pos = 0.0;          // m
  double max_angle = 0.0;        // rad
  double max_vel = 0.0;          // m/s
  double max_omega = 0.0;        // rad/s
  double end_pos = 0.0;          // m
  double end_angle = 0.0;        // rad
  double end_time = 0.0;         // s, the last common sample
  double time_of_max_pos = 0.0;  // s
};

// Two sampled runs at the sample times they share (|Δt| ≤ 1e-12·max(1, t)).
TrajectoryError error_between(const Trajectory& a, const Trajectory& b);

// A sampled run against the dense reference at the run's sample times.
TrajectoryError error_against(const Trajectory& run, const DenseTrajectory& reference);

// Two dense trajectories at the given times.
TrajectoryError error_between(const DenseTrajectory& a, const DenseTrajectory& b,
                              const std::vector<double>& times);

}  // namespace contact2d::analysis
