#include "mujoco/comparison.hpp"

#include <algorithm>
#include <cmath>

namespace contact2d::mujoco {

TrajectoryErrors compare_trajectories(const Trajectory& a, const Trajectory& b) {
  TrajectoryErrors e;
  const size_t n = std::min(a.samples.size(), b.samples.size());
  double sum_sq = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const State& sa = a.samples[i].state;
    const State& sb = b.samples[i].state;
    const double pos = (sa.q.head<2>() - sb.q.head<2>()).norm();
    const double angle = std::abs(sa.q.z() - sb.q.z());
    if (pos > e.max_pos) {
      e.max_pos = pos;
      e.time_of_max_pos = a.samples[i].t;
    }
    e.max_angle = std::max(e.max_angle, angle);
    e.max_vel = std::max(e.max_vel, (sa.v.head<2>() - sb.v.head<2>()).norm());
    e.max_omega = std::max(e.max_omega, std::abs(sa.v.z() - sb.v.z()));
    sum_sq += pos * pos;
    e.end_pos = pos;
    e.end_angle = angle;
  }
  e.samples = static_cast<long long>(n);
  e.rms_pos = n > 0 ? std::sqrt(sum_sq / static_cast<double>(n)) : 0.0;
  return e;
}

}  // namespace contact2d::mujoco
