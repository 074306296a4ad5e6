#include "analysis/reference.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "analysis/engine.hpp"

namespace contact2d::analysis {
std::vector<double> output_times(const SimParams& sim) {
  std::vector<double> times;
  const long long n = static_cast<long long>(std::floor(sim.duration / sim.output_dt + 1e-9));
  for (long long i = 0; i <= n; ++i)
    times.push_back(std::min(sim.duration, static_cast<double>(i) * sim.output_dt));
  if (times.back() < sim.duration) times.push_back(sim.duration);
  return times;
}

double max_penetration(const Model& model, const DenseTrajectory& reference, double dt) {
  double deepest = 0.0;
  const long long n = static_cast<long long>(std::ceil(reference.t_end() / dt));
  for (long long i = 0; i <= n; ++i) {
    const double t = std::min(reference.t_end(), static_cast<double>(i) * dt);
    deepest = std::max(deepest, contact2d::max_penetration(model, reference.at(t).q));
  }
  return deepest;
}

TimedReference timed_reference(const Scene& scene, double tol, int repeats) {
  TimedReference out;
  out.tol = tol;
  out.seconds = INFINITY;
  for (int r = 0; r < std::max(1, repeats); ++r) {
    const auto start = std::chrono::steady_clock::now();
    DenseTrajectory trajectory = converged_reference(scene, tol);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    out.seconds = std::min(out.seconds, seconds);
    if (r == 0) out.trajectory = std::move(trajectory);
  }
  return out;
}

ReferenceStudy study_reference(const Scene& scene, const std::vector<double>& tols,
                               double truth_tol, unsigned threads) {
  ReferenceStudy study;
  study.truth_tol = truth_tol;
  std::vector<TimedReference> runs(tols.size() + 2);
  parallel_for(runs.size(), threads, [&](size_t i) {
    if (i < tols.size()) {
      runs[i] = timed_reference(scene, tols[i]);
    } else if (i == tols.size()) {
      runs[i] = timed_reference(scene, truth_tol);
    } else {
      Scene perturbed = scene;
      perturbed.initial.q.y() += 1e-8;
      runs[i] = timed_reference(perturbed, truth_tol, 1);
    }
  });
  const TimedReference& truth = runs[tols.size()];
  study.truth_seconds = truth.seconds;
  study.truth_stats = truth.trajectory.stats();
  const std::vector<double> times = output_times(scene.sim);
  for (size_t i = 0; i < tols.size(); ++i) {
    ToleranceRow row;
    row.tol = tols[i];
    row.seconds = runs[i].seconds;
    row.stats = runs[i].trajectory.stats();
    row.failure = runs[i].trajectory.failure();
    if (row.failure.empty()) row.error = error_between(runs[i].trajectory, truth.trajectory, times);
    study.rows.push_back(row);
  }
  study.amplification =
      error_between(runs.back().trajectory, truth.trajectory, times).max_pos / 1e-8;
  return study;
}

}  // namespace contact2d::analysis
