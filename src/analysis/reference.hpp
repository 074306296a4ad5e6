// The converged reference of a scene and how trajectories are measured
// against it.
#pragma once

#include <string>
#include <vector>

#include "analysis/trajectory_error.hpp"
#include "core/run.hpp"
#include "reference/dense_reference.hpp"

namespace contact2d::analysis {

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
