// MuJoCo's discrete-time bounce (mujoco/bounce.hpp).
#include "mujoco/bounce.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mujoco/solref_tool.hpp"

namespace contact2d::mujoco {
namespace {

constexpr int kPhases = 8;
constexpr long kMaxSteps = kMaxBounceSteps;

// The rows' accelerations at (x, v): MuJoCo's forces on the rows in contact.
Eigen::VectorXd acceleration(const std::vector<BounceRow>& rows, const Eigen::MatrixXd& A,
                             const Eigen::VectorXd& x, const Eigen::VectorXd& v) {
  const Eigen::Index n = x.size();
  std::vector<Eigen::Index> active;
  for (Eigen::Index i = 0; i < n; ++i)
    if (x(i) <= 0.0) active.push_back(i);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
  while (!active.empty()) {
    const auto m = static_cast<Eigen::Index>(active.size());
    Eigen::MatrixXd system(m, m);
    Eigen::VectorXd aref(m);
    for (Eigen::Index a = 0; a < m; ++a) {
      const Eigen::Index i = active[static_cast<size_t>(a)];
      const BounceRow& r = rows[static_cast<size_t>(i)];
      const double d = mujoco_impedance(r.solimp, x(i));
      for (Eigen::Index b = 0; b < m; ++b) system(a, b) = A(i, active[static_cast<size_t>(b)]);
      system(a, a) += (1.0 - d) / d * r.weight;
      aref(a) = -r.B * v(i) - r.K * d * x(i);
    }
    const Eigen::VectorXd solved = system.ldlt().solve(aref);
    std::vector<Eigen::Index> pushing;
    for (Eigen::Index a = 0; a < m; ++a)
      if (solved(a) > 0.0) pushing.push_back(active[static_cast<size_t>(a)]);
    if (pushing.size() == active.size()) {
      for (Eigen::Index a = 0; a < m; ++a) f(active[static_cast<size_t>(a)]) = solved(a);
      break;
    }
    active = pushing;
  }
  return A * f;
}

}  // namespace

Bounce mujoco_bounce(const std::vector<BounceRow>& rows, const Eigen::MatrixXd& coupling, double dt,
                     bool rk4, double v0) {
  const auto n = static_cast<Eigen::Index>(rows.size());
  Bounce out;
  double smallest = std::numeric_limits<double>::infinity(), largest = -smallest;
  for (int phase = 0; phase < kPhases; ++phase) {
    // One step before the first contact: RK4's stages may touch within it.
    Eigen::VectorXd x = Eigen::VectorXd::Constant(n, (phase + 0.5) / kPhases * v0 * dt);
    Eigen::VectorXd v = Eigen::VectorXd::Constant(n, -v0);
    long steps = 0;
    bool touched = false;
    for (; steps < kMaxSteps && !(touched && (x.array() > 0.0).all()); ++steps) {
      const Eigen::VectorXd before = v;
      if (rk4) {
        const Eigen::VectorXd a1 = acceleration(rows, coupling, x, v);
        const Eigen::VectorXd x2 = x + 0.5 * dt * v, v2 = v + 0.5 * dt * a1;
        const Eigen::VectorXd a2 = acceleration(rows, coupling, x2, v2);
        const Eigen::VectorXd x3 = x + 0.5 * dt * v2, v3 = v + 0.5 * dt * a2;
        const Eigen::VectorXd a3 = acceleration(rows, coupling, x3, v3);
        const Eigen::VectorXd x4 = x + dt * v3, v4 = v + dt * a3;
        const Eigen::VectorXd a4 = acceleration(rows, coupling, x4, v4);
        x += dt / 6.0 * (v + 2.0 * v2 + 2.0 * v3 + v4);
        v += dt / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
      } else {
        v += dt * acceleration(rows, coupling, x, v);
        x += dt * v;
      }
      touched = touched || (x.array() <= 0.0).any() || v != before;
    }
    if (steps >= kMaxSteps) out.left = false;
    const double e = v.mean() / v0;
    out.restitution += e / kPhases;
    out.contact_time += static_cast<double>(steps - 1) * dt / kPhases;
    smallest = std::min(smallest, e);
    largest = std::max(largest, e);
  }
  out.spread = largest - smallest;
  return out;
}

}  // namespace contact2d::mujoco
