#include "analysis/trajectory_error.hpp"

#include <algorithm>
#include <cmath>

namespace contact2d::analysis {
namespace {

struct Accumulator {
  TrajectoryError e;
  double sum_sq = 0.0;

  void add(double t, const State& a, const State& b) {
    const double pos = (a.q.head<2>() - b.q.head<2>()).norm();
    const double angle = std::abs(a.q.z() - b.q.z());
    if (pos > e.max_pos) {
      e.max_pos = pos;
      e.time_of_max_pos = t;
    }
    e.max_angle = std::max(e.max_angle, angle);
    e.max_vel = std::max(e.max_vel, (a.v.head<2>() - b.v.head<2>()).norm());
    e.max_omega = std::max(e.max_omega, std::abs(a.v.z() - b.v.z()));
    sum_sq += pos * pos;
    e.end_pos = pos;
    e.end_angle = angle;
    e.end_time = t;
    ++e.samples;
  }

  TrajectoryError finish() {
    e.rms_pos = e.samples > 0 ? std::sqrt(sum_sq / static_cast<double>(e.samples)) : 0.0;
    return e;
  }
};

}  // namespace

TrajectoryError error_between(const Trajectory& a, const Trajectory& b) {
  Accumulator acc;
  size_t j = 0;
  for (const Sample& s : a.samples) {
    const double tolerance = 1e-12 * std::max(1.0, s.t);
    while (j < b.samples.size() && b.samples[j].t < s.t - tolerance) ++j;
    if (j == b.samples.size()) break;
    if (std::abs(b.samples[j].t - s.t) <= tolerance) acc.add(s.t, s.state, b.samples[j].state);
  }
  return acc.finish();
}

TrajectoryError error_against(const Trajectory& run, const DenseTrajectory& reference) {
  Accumulator acc;
  for (const Sample& s : run.samples) acc.add(s.t, s.state, reference.at(s.t));
  return acc.finish();
}

TrajectoryError error_between(const DenseTrajectory& a, const DenseTrajectory& b,
                              const std::vector<double>& times) {
  Accumulator acc;
  for (double t : times) acc.add(t, a.at(t), b.at(t));
  return acc.finish();
}

}  // namespace contact2d::analysis
