#include "core/integrators.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <cstring>
#include <limits>
#include <utility>

namespace contact2d {

std::string_view integrator_name(Integrator integrator) {
  switch (integrator) {
    case Integrator::ExplicitEuler: return "explicit_euler";
    case Integrator::SemiImplicitEuler: return "semi_implicit_euler";
    case Integrator::ImplicitEuler: return "implicit_euler";
    case Integrator::RK4: return "rk4";
  }
  return "?";
}

std::string_view integrator_title(Integrator integrator) {
  switch (integrator) {
    case Integrator::ExplicitEuler: return "explicit Euler";
    case Integrator::SemiImplicitEuler: return "semi-implicit Euler";
    case Integrator::ImplicitEuler: return "implicit Euler";
    case Integrator::RK4: return "RK4";
  }
  return "?";
}

std::optional<Integrator> parse_integrator(std::string_view name) {
  for (Integrator integrator : kAllIntegrators) {
    if (integrator_name(integrator) == name) return integrator;
  }
  return std::nullopt;
}

namespace {

// Bit for bit the same vector (+0 and −0 differ, a NaN equals itself): the
// force stage's output is a function of these bits.
bool same_bits(const Vec3& a, const Vec3& b) {
  for (int i = 0; i < 3; ++i) {
    std::uint64_t x = 0, y = 0;
    std::memcpy(&x, &a[i], sizeof x);
    std::memcpy(&y, &b[i], sizeof y);
    if (x != y) return false;
  }
  return true;
}

constexpr int kNewtonMaxIterations = 30;
constexpr int kMaxSplitDepth = 6;
constexpr double kNewtonTolerance = 1e-10;

// The force stage at an intermediate configuration q (contacts into scratch).
Vec3 acceleration_at(const Model& model, StepWorkspace& ws, const Vec3& q, const Vec3& v) {
  find_contacts(model, q, ws.scratch);
  return acceleration(model, ws.scratch, v);
}

void explicit_euler(const Model& model, double dt, State& s, StepWorkspace& ws) {
  const Vec3 a = acceleration(model, ws.contacts, s.v);
  s.q += dt * s.v;
  s.v += dt * a;
}

void semi_implicit_euler(const Model& model, double dt, State& s, StepWorkspace& ws) {
  s.v += dt * acceleration(model, ws.contacts, s.v);
  s.q += dt * s.v;
}

void rk4(const Model& model, double dt, State& s, StepWorkspace& ws) {
  const Vec3 q0 = s.q;
  const Vec3 v0 = s.v;
  const Vec3& k1q = v0;
  const Vec3 k1v = acceleration(model, ws.contacts, v0);
  const Vec3 k2q = v0 + 0.5 * dt * k1v;
  const Vec3 k2v = acceleration_at(model, ws, q0 + 0.5 * dt * k1q, k2q);
  const Vec3 k3q = v0 + 0.5 * dt * k2v;
  const Vec3 k3v = acceleration_at(model, ws, q0 + 0.5 * dt * k2q, k3q);
  const Vec3 k4q = v0 + dt * k3v;
  const Vec3 k4v = acceleration_at(model, ws, q0 + dt * k3q, k4q);
  s.q = q0 + dt / 6.0 * (k1q + 2.0 * k2q + 2.0 * k3q + k4q);
  s.v = v0 + dt / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
}

// Newton, and on failure two half steps (recursively). Each successful
// (sub)step leaves ws.contacts at the new state, as step() promises.
bool implicit_euler(const Model& model, double dt, State& s, int depth, StepWorkspace& ws) {
  State trial = s;
  if (implicit_euler_newton(model, dt, trial, ws)) {
    s = trial;
    // ws.scratch holds the contacts at q + Δt·v', computed by the same
    // expression as the new s.q: the contacts of the new state, bit for bit.
    std::swap(ws.contacts, ws.scratch);
    return true;
  }
  if (depth >= kMaxSplitDepth) return false;
  return implicit_euler(model, 0.5 * dt, s, depth + 1, ws) &&
         implicit_euler(model, 0.5 * dt, s, depth + 1, ws);
}

// Largest h·|λ| such that |R(h·λ)| ≤ 1 for both roots λ of s² + 2ζs + 1
// (ω = 1), where R is the amplification polynomial of a one-stage-per-step
// method applied to y' = λy. Bisection on h; the stable set is an interval
// from 0 for the methods used here.
template <typename Amplification>
double scalar_stability_limit(double zeta, Amplification amplification) {
  using C = std::complex<double>;
  const C disc = std::sqrt(C(zeta * zeta - 1.0, 0.0));
  const C roots[2] = {-zeta + disc, -zeta - disc};
  auto stable = [&](double h) {
    for (const C& lambda : roots) {
      if (std::abs(amplification(h * lambda)) > 1.0 + 1e-12) return false;
    }
    return true;
  };
  double lo = 0.0, hi = 10.0;
  if (stable(hi)) return hi;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (stable(mid) ? lo : hi) = mid;
  }
  return lo;
}

}  // namespace

// J·x = b for a 3×3 J by Gaussian elimination with partial pivoting, written
// out: the same method as Eigen's PartialPivLU, without its general-size
// loops, which were the largest single cost of a Newton iteration.
Vec3 solve3(Eigen::Matrix3d a, Vec3 b) {
  for (int k = 0; k < 2; ++k) {
    int p = k;
    for (int i = k + 1; i < 3; ++i) {
      if (std::abs(a(i, k)) > std::abs(a(p, k))) p = i;
    }
    if (p != k) {
      a.row(p).swap(a.row(k));
      std::swap(b[p], b[k]);
    }
    for (int i = k + 1; i < 3; ++i) {
      const double f = a(i, k) / a(k, k);
      for (int j = k + 1; j < 3; ++j) a(i, j) -= f * a(k, j);
      b[i] -= f * b[k];
    }
  }
  Vec3 x;
  x[2] = b[2] / a(2, 2);
  x[1] = (b[1] - a(1, 2) * x[2]) / a(1, 1);
  x[0] = (b[0] - a(0, 1) * x[1] - a(0, 2) * x[2]) / a(0, 0);
  return x;
}

// |J⁻¹·g|∞ ≤ |g|∞/(1 − q) for J = I − E with q = ‖E‖∞ (the largest row
// sum of |E|) below 1: J⁻¹ = Σ Eⁿ (Neumann series), so ‖J⁻¹‖∞ ≤ Σ qⁿ. Only
// q ≤ 1/2 is used: there the solve's own rounding (solve3 is backward
// stable: it solves (J + ΔJ)·x = b with ‖ΔJ‖ a few ulps of ‖J‖ ≤ 1.5) moves
// the bound by a relative 1e-15, far inside the factor 2 that
// implicit_euler_newton keeps in hand. +∞ otherwise.
double newton_step_bound(const Eigen::Matrix3d& e, const Vec3& g) {
  const double q = e.cwiseAbs().rowwise().sum().maxCoeff();
  if (!(q <= 0.5)) return std::numeric_limits<double>::infinity();
  return g.lpNorm<Eigen::Infinity>() / (1.0 - q);
}

// ws.contacts are those of s.q throughout (s is only written on success).
//
// Each iteration solves J·δ = −G(v') for the full Newton step δ and then
// backtracks: δ, δ/2, δ/4, … down to δ/1024, accepting the first fraction
// whose residual is strictly smaller in the max norm. If none is, the
// iteration has stalled (the piecewise force put a kink between v' and the
// root, or the Jacobian of the branch at v' points the wrong way): the solve
// fails and step() splits the step. Converged when, with s = 1 + |v'|∞,
// both the full step and the residual are small: |δ|∞ ≤ tol·s and
// |G(v')|∞ ≤ tol·s (tol = 1e-10; G is a velocity, like δ) — checked at the
// iterate before stepping, and after a step taken in full.
bool implicit_euler_newton(const Model& model, double dt, State& s, StepWorkspace& ws) {
  // Every residual is evaluated with the Jacobian of a at its point (one
  // force stage gives both), so the iterate's Jacobian is at hand when the
  // iterate is accepted; a backtracking trial that is rejected wastes it.
  AccelerationJacobian da, da_trial;
  Vec3 a_next, a_trial;  // a(q + Δt·v', v') of the iterate and of the trial
  auto residual = [&](const Vec3& v_next, AccelerationJacobian& jac, Vec3& a) {
    const Vec3 q_next = s.q + dt * v_next;
    find_contacts(model, q_next, ws.scratch);
    a = acceleration_jacobian(model, ws.scratch, q_next, v_next, jac, ws.probe);
    return Vec3(v_next - s.v - dt * a);
  };
  // The semi-implicit predictor, with a(q, v) from the previous accepted
  // solve when this step starts where it ended (bitwise) under the same
  // model and applied force: the value the force stage would compute again.
  const StepWorkspace::Accepted& last = ws.accepted;
  const bool same = last.model == &model && same_bits(last.q, s.q) && same_bits(last.v, s.v) &&
                    same_bits(last.applied, model.applied);
  Vec3 v_next = s.v + dt * (same ? last.a : acceleration(model, ws.contacts, s.v));
  Vec3 g = residual(v_next, da, a_next);
  auto small = [](const Vec3& x, const Vec3& v) {
    return x.lpNorm<Eigen::Infinity>() <= kNewtonTolerance * (1.0 + v.lpNorm<Eigen::Infinity>());
  };
  auto accept = [&](const Vec3& v) {
    s.q += dt * v;
    s.v = v;
    ws.accepted = {s.q, s.v, model.applied, a_next, &model};
    return true;
  };
  for (int iteration = 0; iteration < kNewtonMaxIterations; ++iteration) {
    // ws.scratch holds the contacts at q' = q + Δt·v' of the current
    // iterate and da the derivatives of a there (its residual was the last
    // one evaluated).
    const Eigen::Matrix3d e = dt * (dt * da.dq + da.dv);
    // The convergence test asks |δ|∞ ≤ tol·s of the step a solve here would
    // give; when the bound on |δ|∞ (newton_step_bound) meets half of that,
    // the solve could only confirm it: the same iterate is accepted, bit for
    // bit, one 3×3 solve sooner. Otherwise the solve decides.
    if (small(g, v_next) && newton_step_bound(e, g) <=
                                0.5 * kNewtonTolerance * (1.0 + v_next.lpNorm<Eigen::Infinity>()))
      return accept(v_next);
    const Eigen::Matrix3d jacobian = Eigen::Matrix3d::Identity() - e;
    const Vec3 delta = solve3(jacobian, -g);
    if (!delta.allFinite()) return false;
    if (small(delta, v_next) && small(g, v_next)) return accept(v_next);
    double fraction = 1.0;
    Vec3 trial = v_next + delta;
    Vec3 g_trial = residual(trial, da_trial, a_trial);
    while (!(g_trial.lpNorm<Eigen::Infinity>() < g.lpNorm<Eigen::Infinity>())) {
      if (fraction < 1e-3) return false;  // no decrease down to δ/1024: stalled
      fraction *= 0.5;
      trial = v_next + fraction * delta;
      g_trial = residual(trial, da_trial, a_trial);
    }
    v_next = trial;
    g = g_trial;
    da = da_trial;
    a_next = a_trial;
    if (fraction == 1.0 && small(delta, v_next) && small(g, v_next)) return accept(v_next);
  }
  return false;
}

StepStatus step(const Model& model, Integrator integrator, double dt, State& state,
                StepWorkspace& ws) {
  switch (integrator) {
    case Integrator::ExplicitEuler: explicit_euler(model, dt, state, ws); break;
    case Integrator::SemiImplicitEuler: semi_implicit_euler(model, dt, state, ws); break;
    case Integrator::RK4: rk4(model, dt, state, ws); break;
    case Integrator::ImplicitEuler:
      // Refreshes ws.contacts itself after every accepted (sub)step.
      return implicit_euler(model, dt, state, 0, ws) ? StepStatus::Ok : StepStatus::NewtonFailed;
  }
  find_contacts(model, state.q, ws.contacts);  // the position stage of the new state
  return StepStatus::Ok;
}

double stability_limit(Integrator integrator, double zeta) {
  using C = std::complex<double>;
  switch (integrator) {
    case Integrator::ImplicitEuler: return std::numeric_limits<double>::infinity();
    case Integrator::SemiImplicitEuler: {
      const double jury = 2.0 * (std::sqrt(1.0 + zeta * zeta) - zeta);
      return zeta > 0.0 ? std::min(1.0 / zeta, jury) : jury;
    }
    case Integrator::ExplicitEuler:
      return scalar_stability_limit(zeta, [](C z) { return 1.0 + z; });
    case Integrator::RK4:
      return scalar_stability_limit(
          zeta, [](C z) { return 1.0 + z * (1.0 + z * (0.5 + z * (1.0 / 6.0 + z / 24.0))); });
  }
  return 0.0;
}

}  // namespace contact2d
