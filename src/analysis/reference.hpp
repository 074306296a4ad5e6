// The converged reference of a scene and how trajectories are measured
// against it.
#pragma once

#include <string>
#include <vector>

#include "core/run.hpp"
#include "reference/dense_reference.hpp"

namespace contact2d::analysis {

// Position error ‖Δ(x, y)‖ of the COM and angle error |Δθ|, maximum over the
// sampled times and at the last sample.
struct TrajectoryError {
  double max_pos = 0.0;
  double end_pos = 0.0;
  double max_angle = 0.0;
  double end_angle = 0.0;
  double end_time = 0.0;
  size_t samples = 0;
};

// A fixed-step run's samples against the dense reference at the same times.
TrajectoryError error_against(const Trajectory& run, const DenseTrajectory& reference);

// Two dense trajectories compared at the given times.
TrajectoryError error_between(const DenseTrajectory& a, const DenseTrajectory& b,
                              const std::vector<double>& times);

// Two sampled runs compared at the sample times they share (|Δt| ≤ 1e-9·dt).
TrajectoryError error_between(const Trajectory& a, const Trajectory& b);

// 0, output_dt, 2·output_dt, …, and the end of the run.
std::vector<double> output_times(const SimParams& sim);

// Deepest penetration of the reference over [0, duration], sampled at `dt`.
double max_penetration(const Model& model, const DenseTrajectory& reference, double dt);

// The converged reference at a tolerance, with its wall-clock time (best of
// `repeats` runs: each is a few milliseconds, and the best is the least
// disturbed by anything else on the machine).
struct TimedReference {
  DenseTrajectory trajectory;
  double tol = 0.0;
  double seconds = 0.0;
};
TimedReference timed_reference(const Scene& scene, double tol, int repeats = 3);

// Self-consistency of the reference: each tolerance against a much tighter
// one, at the scene's output times.
struct ToleranceRow {
  double tol = 0.0;
  TrajectoryError error;
  double seconds = 0.0;
  DenseStats stats;
  std::string failure;  // empty when the run completed
};

struct ReferenceStudy {
  double truth_tol = 0.0;
  double truth_seconds = 0.0;
  DenseStats truth_stats;
  std::vector<ToleranceRow> rows;
  // How much the scene magnifies a change of the initial height by δ: the
  // largest position deviation over the run divided by δ (δ = 1e-8 m). A
  // tumbling box or T magnifies every error made before its impacts.
  double amplification = 0.0;
};

ReferenceStudy study_reference(const Scene& scene, const std::vector<double>& tols,
                               double truth_tol, unsigned threads = 0);

}  // namespace contact2d::analysis
