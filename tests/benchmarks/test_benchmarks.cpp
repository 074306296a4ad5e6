// The closed forms of src/benchmarks/ against independent numbers: each
// ODE the header states integrated here with a small fixed step of RK4
// (its own right-hand side, written from the physics, not from the closed
// form), and textbook values. A test fails if a formula is wrong by more
// than its stated tolerance; every tolerance is far below the term it
// checks (stated at each).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <vector>

#include "benchmarks/impact.hpp"
#include "benchmarks/oscillator.hpp"
#include "benchmarks/rest.hpp"
#include "benchmarks/rolling.hpp"
#include "benchmarks/sliding.hpp"
#include "benchmarks/slope.hpp"
#include "benchmarks/soft_constraint.hpp"

namespace contact2d::benchmarks {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kG = 9.81;

template <size_t N>
using Vec = std::array<double, N>;

// One classical Runge–Kutta step of y' = f(y) (autonomous).
template <size_t N>
void rk4(Vec<N>& y, double h, const std::function<Vec<N>(const Vec<N>&)>& f) {
  const auto add = [](const Vec<N>& a, const Vec<N>& b, double s) {
    Vec<N> out;
    for (size_t i = 0; i < N; ++i) out[i] = a[i] + s * b[i];
    return out;
  };
  const Vec<N> k1 = f(y);
  const Vec<N> k2 = f(add(y, k1, 0.5 * h));
  const Vec<N> k3 = f(add(y, k2, 0.5 * h));
  const Vec<N> k4 = f(add(y, k3, h));
  for (size_t i = 0; i < N; ++i) y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
}

// ------------------------------------------------------------------ rest

TEST(Rest, DepthIsWeightOverStiffnessPerPoint) {
  EXPECT_NEAR(rest_depth(1.0, kG, 1e4, 1), 9.81e-4, 1e-18);
  EXPECT_NEAR(rest_depth(1.0, kG, 1e4, 2), 4.905e-4, 1e-18);
  // A mass on N critically damped springs under gravity, integrated to rest
  // (50 time constants): m·x'' = m·g − N·(k·x + c·x').
  for (int n : {1, 2, 4}) {
    const double m = 2.0, k = 3e3, c = 2.0 * std::sqrt(k * m / n);
    Vec<2> y{0.0, 0.0};  // depth, its rate
    for (int i = 0; i < 200000; ++i)
      rk4<2>(y, 1e-5, [&](const Vec<2>& s) {
        return Vec<2>{s[1], kG - n * (k * s[0] + c * s[1]) / m};
      });
    EXPECT_NEAR(rest_depth(m, kG, k, n), y[0], 1e-12 * y[0]) << n << " points";
  }
}

TEST(Rest, SoftConstraintDepthBalancesTheRowForce) {
  // A free body, Â = 1/m: MuJoCo's RestPenetration statement p = g·(1 − d)/s.
  EXPECT_NEAR(soft_constraint_rest_depth(2.0, kG, 0.5, 0.9, 1, 100.0), kG * 0.1 / 100.0, 1e-15);
  // The point mass of docs/closed-forms.md under the calibrated mapping:
  // Â = 2/(3m), s = k·Â, d = 1e-4: (1 − d)·m·g/k = 9.809019e-4 m.
  const double a_hat = 2.0 / 3.0, d = 1e-4, s = 1e4 * a_hat;
  const double p = soft_constraint_rest_depth(1.0, kG, a_hat, d, 1, s);
  EXPECT_NEAR(p, 9.809019e-4, 1e-13);
  // The row force at that depth, f = aref/R with aref = K·d·p, K = s/d²,
  // R = (1 − d)/d·Â, carries the weight (3 rows: a third each).
  const double p3 = soft_constraint_rest_depth(1.0, kG, a_hat, d, 3, s);
  const double f = (s / (d * d)) * d * p3 / ((1.0 - d) / d * a_hat);
  EXPECT_NEAR(3.0 * f, kG, 1e-12);
}

// ------------------------------------------------------------------ impact

// The oscillator x'' = −F(x, x') from x = 0, x' = 1 in units of 1/ω, until
// F returns to zero (found between steps by linear interpolation, error
// O(h²) = 1e-10). Returns (τ, e = −x'(τ)).
struct Exit {
  double time = 0.0, e = 0.0;
};
Exit integrate_impact(const std::function<double(double, double)>& force) {
  const double h = 1e-5;
  Vec<2> y{0.0, 1.0};
  double t = 0.0;
  // The first step leaves x = 0 where F = 2ζ > 0 (or 0 undamped).
  for (int i = 0; i < 10000000; ++i) {
    const Vec<2> before = y;
    rk4<2>(y, h, [&](const Vec<2>& s) { return Vec<2>{s[1], -force(s[0], s[1])}; });
    const double fa = force(before[0], before[1]), fb = force(y[0], y[1]);
    if (i > 0 && fa > 0.0 && fb <= 0.0) {
      const double w = fa / (fa - fb);
      return {t + w * h, -(before[1] + w * (y[1] - before[1]))};
    }
    t += h;
  }
  ADD_FAILURE() << "no exit";
  return {};
}

// The clamped Kelvin–Voigt force: max(0, x + 2ζx') — the body leaves where
// x + 2ζx' falls to 0 (the function's own sign change, not the clamp).
Exit kelvin_voigt_numeric(double zeta) {
  return integrate_impact([zeta](double x, double v) { return x + 2.0 * zeta * v; });
}
// The compression-only damper, x + 2ζ·max(0, x'): leaves at x = 0.
Exit compression_numeric(double zeta) {
  return integrate_impact([zeta](double x, double v) { return x + 2.0 * zeta * std::max(0.0, v); });
}

TEST(Impact, KelvinVoigtMatchesTheIntegratedOscillator) {
  for (double zeta : {0.0, 0.05, 0.1, 0.3, 0.6, 0.9, 1.5, 3.0}) {
    const Exit n = kelvin_voigt_numeric(zeta);
    EXPECT_NEAR(kelvin_voigt_restitution(zeta), n.e, 1e-8) << "ζ = " << zeta;
    EXPECT_NEAR(kelvin_voigt_contact_time(zeta), n.time, 1e-8) << "ζ = " << zeta;
  }
  // Critical damping, its own closed form: e = e^(−2), τ = 2 (it was the
  // limit from ζ = 1 + 1e-6 and printed 0.1353351), and the integrated
  // oscillator at the integrator's tolerance.
  const Exit crit = kelvin_voigt_numeric(1.0);
  EXPECT_NEAR(kelvin_voigt_restitution(1.0), std::exp(-2.0), 1e-16);
  EXPECT_EQ(kelvin_voigt_contact_time(1.0), 2.0);
  EXPECT_NEAR(kelvin_voigt_restitution(1.0), crit.e, 1e-8);
  EXPECT_NEAR(kelvin_voigt_contact_time(1.0), crit.time, 1e-8);
  // docs/closed-forms.md's table.
  EXPECT_NEAR(kelvin_voigt_restitution(0.1), 0.744079, 5e-7);
  EXPECT_NEAR(kelvin_voigt_restitution(0.3), 0.450975, 5e-7);
  EXPECT_TRUE(std::isnan(kelvin_voigt_restitution(-0.1)));
}

// Both sides of ζ = 1 tend to the critical case along its first-order
// expansion (benchmarks/impact.hpp): e(1 + ε) = e^(−2)·(1 − 4ε/3) + O(ε²),
// τ(1 + ε) = 2 − 2ε/3 + O(ε²), with ε of either sign. The remainder is
// second order: 0.17·ε² (e) and 0.27·ε² (τ), measured from ε = ±1e-2 to
// ±1e-6; the bound 0.5·ε² + 1e-11 holds it down to ε = 1e-8, where the
// 1e-11 is the rounding of the two general forms near ζ = 1 (ω_d or
// √(ζ² − 1) → 0: about 1e-16/√(2|ε|) relative, measured ≤ 4.4e-13).
TEST(Impact, KelvinVoigtIsContinuousThroughCriticalDamping) {
  const double e0 = std::exp(-2.0);
  for (const double eps : {1e-2, 1e-3, 1e-4, 1e-6, 1e-8}) {
    for (const double sign : {-1.0, 1.0}) {
      const double d = sign * eps;
      const double bound = 0.5 * eps * eps + 1e-11;
      EXPECT_NEAR(kelvin_voigt_restitution(1.0 + d), e0 * (1.0 - 4.0 * d / 3.0), bound)
          << "ζ = 1 + " << d;
      EXPECT_NEAR(kelvin_voigt_contact_time(1.0 + d), 2.0 - 2.0 * d / 3.0, bound)
          << "ζ = 1 + " << d;
    }
  }
}

TEST(Impact, CompressionOnlyDamperMatchesTheIntegratedOscillator) {
  for (double zeta : {0.05, 0.1, 0.3, 0.6, 0.9}) {
    const Exit n = compression_numeric(zeta);
    // The damper's switch at x' = 0 inside a step: a jump of 2ζ in ∂F/∂x'
    // costs O(ζ·h²) there; 1e-8 is 1e3 × that.
    EXPECT_NEAR(compression_restitution(zeta), n.e, 1e-8) << "ζ = " << zeta;
    EXPECT_NEAR(compression_contact_time(zeta), n.time, 1e-8) << "ζ = " << zeta;
  }
  EXPECT_NEAR(compression_restitution(0.1), 0.862600, 5e-7);
  EXPECT_NEAR(compression_restitution(0.3), 0.671547, 5e-7);
  EXPECT_NEAR(compression_contact_time(0.0), kPi, 1e-15);  // undamped: half a period
  EXPECT_TRUE(std::isnan(compression_restitution(1.0)));
}

TEST(Impact, DashpotIsTheTextbookCoefficientAndBelowTheClampedLaw) {
  // The unclamped dashpot separates at x = 0 after half a damped period.
  for (double zeta : {0.1, 0.3}) {
    Vec<2> y{0.0, 1.0};
    Vec<2> before = y;
    const double h = 1e-5;
    do {
      before = y;
      rk4<2>(y, h, [zeta](const Vec<2>& s) { return Vec<2>{s[1], -(s[0] + 2.0 * zeta * s[1])}; });
    } while (y[0] > 0.0);
    const double w = before[0] / (before[0] - y[0]);
    const double e = -(before[1] + w * (y[1] - before[1]));
    EXPECT_NEAR(dashpot_restitution(zeta), e, 1e-8) << "ζ = " << zeta;
    EXPECT_LT(dashpot_restitution(zeta), kelvin_voigt_restitution(zeta));
  }
  EXPECT_NEAR(dashpot_restitution(0.1), 0.7292, 5e-5);  // docs: 0.729 against 0.744
  EXPECT_NEAR(impact_normal_impulse(2.0, 0.5, 3.0), 9.0, 1e-15);
}

// ------------------------------------------------------------------ sliding

TEST(Sliding, CoulombIsTheTextbookUniformDeceleration) {
  // v0 = 2 m/s, μ = 0.5, g = 9.81: s = 4/9.81 = 0.4077 m, t = 2/4.905 s.
  EXPECT_NEAR(coulomb_sliding_distance(2.0, 0.5, kG), 0.4077, 5e-5);
  EXPECT_NEAR(coulomb_sliding_distance(2.0, 0.5, kG), 4.0 / 9.81, 1e-15);
  EXPECT_NEAR(coulomb_sliding_time(2.0, 0.5, kG), 0.4077, 5e-5);
}

// dv/dt = −a·tanh(αv), dx/dt = v, RK4 at Δt = 1e-5 s.
struct TanhRun {
  std::function<double(double)> speed_at;  // sampled every 1e-3 s, nearest
  double distance = 0.0, time_to = 0.0;
};
TanhRun integrate_tanh(double v0, double a, double alpha, double seconds, double v_th) {
  const double h = 1e-5;
  Vec<2> y{0.0, v0};
  auto samples = std::make_shared<std::vector<double>>();
  TanhRun out;
  const long n = std::lround(seconds / h);
  for (long i = 0; i < n; ++i) {
    if (i % 100 == 0) samples->push_back(y[1]);  // t = i·h
    const Vec<2> before = y;
    rk4<2>(y, h, [&](const Vec<2>& s) { return Vec<2>{s[1], -a * std::tanh(alpha * s[1])}; });
    if (before[1] > v_th && y[1] <= v_th)
      out.time_to = (i + (before[1] - v_th) / (before[1] - y[1])) * h;
  }
  samples->push_back(y[1]);  // t = seconds
  out.distance = y[0];
  out.speed_at = [samples](double t) {
    return (*samples)[static_cast<size_t>(std::lround(t / 1e-3))];
  };
  return out;
}

TEST(Sliding, TanhDistanceIsCoulombsPlusPiSquaredOver12AlphaSquaredMuG) {
  // α·v0 = 15 (ε < 3e-12 m) and 100; 5 s leave v/(μgα) < 1e-20 m to go.
  for (const auto& [v0, mu, alpha] : {std::array<double, 3>{1.5, 0.3, 10.0}, {1.0, 0.5, 100.0}}) {
    const double s = integrate_tanh(v0, mu * kG, alpha, 5.0, 0.0).distance;
    const double excess = tanh_sliding_distance_excess(mu, kG, alpha);
    std::printf(
        "tanh slide v0 %g mu %g alpha %g: integrated %.12f, closed form %.12f, excess %.4g\n", v0,
        mu, alpha, s, tanh_sliding_distance(v0, mu, kG, alpha), excess);
    EXPECT_NEAR(tanh_sliding_distance(v0, mu, kG, alpha), s, 1e-9);
    EXPECT_GT(excess, 1e3 * 1e-9);  // the excess is checked, not lost in the tolerance
  }
}

TEST(Sliding, TanhSpeedAndTimeSolveTheOde) {
  const double v0 = 3.0, alpha = 100.0, a = 0.5 * kG;  // α·v0 = 300: sinh in logarithms
  const TanhRun run = integrate_tanh(v0, a, alpha, 1.0, 0.01);
  for (double t : {0.0, 0.1, 0.5, 0.6, 0.62, 0.7, 1.0})
    EXPECT_NEAR(tanh_sliding_speed(v0, a, alpha, t), run.speed_at(t), 1e-10) << "t = " << t;
  const double v1 = 1.0, u_th = 0.01;
  const TanhRun slow = integrate_tanh(v1, a, alpha, 0.5, u_th);
  EXPECT_NEAR(tanh_sliding_time(v1, u_th, a, alpha), slow.time_to, 1e-8);
  // Against Coulomb's (v0 − v)/a: later by the O(1/α) transition.
  EXPECT_GT(tanh_sliding_time(v1, u_th, a, alpha), (v1 - u_th) / a + 1e-4);
}

TEST(Sliding, BoxPitchTermIsTheIntegralOfTheQuasiStaticPitch) {
  // ∫₀^∞ u/(sinh u·cosh³u) du by Simpson's rule (integrand → 1 at u = 0).
  const int n = 200000;
  const double top = 40.0, du = top / n;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double u = i * du;
    const double f = i == 0 ? 1.0 : u / (std::sinh(u) * std::pow(std::cosh(u), 3));
    sum += f * (i == 0 || i == n ? 1.0 : (i % 2 ? 4.0 : 2.0));
  }
  const double integral = sum * du / 3.0;
  EXPECT_NEAR(integral, kPi * kPi / 8.0 - 0.5, 1e-12);
  // s_k = −(h·β/2)·integral, β = μ·m·g·h/(k·w²): the box of docs/closed-forms.md.
  const double m = 1.0, mu = 0.3, w = 0.4, h = 0.2, k = 1e5;
  const double beta = mu * m * kG * h / (k * w * w);
  EXPECT_NEAR(box_pitch_distance(m, mu, kG, w, h, k), -0.5 * h * beta * integral, 1e-18);
  EXPECT_NEAR(box_pitch_distance(m, mu, kG, w, h, k), -2.70e-6, 5e-9);
  const BoxSlide b = box_sliding_distance(1.5, mu, kG, 10.0, m, w, h, k);
  EXPECT_EQ(b.distance(), b.coulomb + b.tanh + b.pitch);
  EXPECT_NEAR(b.coulomb, 0.382263, 5e-7);  // docs: Coulomb v0²/(2μg)
  EXPECT_NEAR(b.distance(), 0.385055, 5e-7);
}

// ------------------------------------------------------------------ rolling

// A round body (m = 1, R = 0.1, I = κ·m·R²) with the normal load m·g:
// m·v' = F, I·ω' = R·F + τ_r, F = −μ·m·g·tanh(α(v + ωR)),
// τ_r = −μ_roll·m·g·tanh(α·R·ω). State (x, v, ω); RK4 at 1e-5 s.
struct Disc {
  double R = 0.1, kappa = 0.5, mu = 0.5, mu_roll = 0.0, alpha = 100.0;
  Vec<3> rate(const Vec<3>& s) const {
    const double inertia = kappa * R * R;  // m = 1
    const double f = -mu * kG * std::tanh(alpha * (s[1] + s[2] * R));
    const double torque = -mu_roll * kG * std::tanh(alpha * R * s[2]);
    return {s[1], f, (R * f + torque) / inertia};
  }
};

TEST(Rolling, ResistanceDeceleratesAtMuRollGOverROnePlusKappa) {
  for (const auto& [kappa, alpha] :
       {std::array<double, 2>{0.5, 100.0}, {1.0, 100.0}, {0.5, 400.0}, {1.0, 400.0}}) {
    Disc disc;
    disc.kappa = kappa;
    disc.mu_roll = 0.01;
    disc.alpha = alpha;
    const double v0 = 1.0;
    Vec<3> y{0.0, v0, -v0 / disc.R};
    double v_half = 0.0;
    const double h = 1e-5;
    const double a = rolling_resistance_deceleration(disc.mu_roll, kG, disc.R, kappa);
    for (long i = 1; i <= 400000; ++i) {  // 4 s, past the stop
      rk4<3>(y, h, [&](const Vec<3>& s) { return disc.rate(s); });
      if (i == 50000) v_half = y[1];
      if (i == 100000) {
        EXPECT_NEAR((v_half - y[1]) / 0.5, a, 1e-9 * a) << "κ = " << kappa;
      }
    }
    const double s = rolling_distance(v0, a, disc.mu, kG, alpha, kappa);
    const RollingStop terms = rolling_distance_terms(v0, a, disc.mu, kG, alpha, kappa);
    const double slip_term = terms.slip;
    std::printf(
        "rolling κ = %g, α = %g: integrated %.9f m, closed form %.9f m, off %.3g m "
        "(slip term %.3g m)\n",
        kappa, alpha, y[0], s, y[0] - s, slip_term);
    // The remainder is O(1/α²): v_s is O(1/α) too, and the two tanh laws
    // overlap in the stop. Measured 1.8e-5 (κ = ½) and 1.3e-5 m (κ = 1) at
    // α = 100, a sixteenth of that at α = 400; the tolerance 3e-5·(100/α)² is
    // below the slip term it checks by 20× (α = 100) and 90× (α = 400).
    const double tolerance = 3e-5 * (100.0 / alpha) * (100.0 / alpha);
    EXPECT_NEAR(s, y[0], tolerance) << "κ = " << kappa << ", α = " << alpha;
    EXPECT_GT(slip_term, 20.0 * tolerance);
    // Term by term: the roll is the uniform deceleration's v0²/(2a), the
    // tanh term the sliding law's π²/(12α²a), and what the integration
    // adds beyond them is the slip term (the same remainder).
    EXPECT_NEAR(terms.roll, v0 * v0 / (2.0 * a), 1e-15 * terms.roll);
    EXPECT_NEAR(terms.tanh, tanh_sliding_distance_excess(1.0, a, alpha), 1e-15 * terms.tanh);
    EXPECT_NEAR(y[0] - terms.roll - terms.tanh, terms.slip, tolerance);
  }
  EXPECT_NEAR(rolling_resistance_deceleration(0.01, kG, 0.1, 0.5), 0.654, 1e-12);  // docs
}

TEST(Rolling, SlideToRollConservesAngularMomentumAboutTheContact) {
  // The textbook bowling ball: a solid sphere (κ = 2/5) launched without
  // spin ends rolling at 5v0/7 after Coulomb's 2v0/(7μg); the disc at 2v0/3.
  EXPECT_NEAR(slide_to_roll_final_speed(7.0, 0.0, 0.4), 5.0, 1e-14);
  EXPECT_NEAR(7.0 / slide_to_roll_slip_deceleration(0.5, kG, 0.4), 2.0 * 7.0 / (7.0 * 0.5 * kG),
              1e-14);
  EXPECT_NEAR(slide_to_roll_final_speed(1.0, 0.0, 0.5), 2.0 / 3.0, 1e-15);
  for (const auto& [kappa, omega0] : {std::array<double, 2>{0.5, 0.0}, {0.5, 5.0}, {0.4, -3.0}}) {
    Disc disc;
    disc.kappa = kappa;
    disc.mu = 0.3;
    const double v0 = 2.0, u0 = v0 + omega0 * disc.R;
    const double a_u = slide_to_roll_slip_deceleration(disc.mu, kG, kappa);
    Vec<3> y{0.0, v0, omega0};
    const double h = 1e-5;
    double worst_u = 0.0, worst_v = 0.0, worst_w = 0.0, t_th = 0.0;
    const double u_th = 0.01;
    for (long i = 1; i <= 200000; ++i) {  // 2 s
      const double u_before = y[1] + y[2] * disc.R;
      rk4<3>(y, h, [&](const Vec<3>& s) { return disc.rate(s); });
      const double u = y[1] + y[2] * disc.R, t = i * h;
      if (u_before > u_th && u <= u_th) t_th = t - h * (u_th - u) / (u_before - u);
      if (i % 100 != 0) continue;
      worst_u = std::max(worst_u, std::abs(u - tanh_sliding_speed(u0, a_u, disc.alpha, t)));
      worst_v = std::max(worst_v, std::abs(y[1] - slide_to_roll_speed(v0, u0, u, kappa)));
      worst_w =
          std::max(worst_w, std::abs(y[2] - slide_to_roll_spin(omega0, u0, u, disc.R, kappa)));
    }
    const double vf = slide_to_roll_final_speed(v0, omega0 * disc.R, kappa);
    // v and ω share each step's impulse exactly, so L = κ·R·ω − v is kept to
    // the rounding of 2e5 steps (measured 1.8e-12 m/s).
    EXPECT_LT(worst_u, 1e-10) << "κ = " << kappa << ", ω0 = " << omega0;
    EXPECT_LT(worst_v, 1e-11);
    EXPECT_LT(worst_w, 1e-10);
    EXPECT_NEAR(y[1], vf, 1e-11);
    EXPECT_NEAR(tanh_sliding_time(u0, u_th, a_u, disc.alpha), t_th, 1e-8);
    // x(T) = v_final·T + offset, the tail after 2 s below 1e-15 m.
    EXPECT_NEAR(y[0] - vf * 2.0, slide_to_roll_distance_offset(u0, disc.mu, kG, disc.alpha, kappa),
                1e-9);
  }
}

// The impact's normal impulse P applied in many small parts dP; each part
// brings a friction impulse of at most μ·dP against the slip, and no more
// than stops it (slip mass m/(1 + 1/κ)).
SpinImpact integrate_spin_impact(double vx, double rim, double p, double m, double mu,
                                 double kappa) {
  const int n = 1000000;
  const double dp = p / n;
  for (int i = 0; i < n; ++i) {
    const double u = vx + rim;
    const double stop = std::abs(u) * m / (1.0 + 1.0 / kappa);
    const double ft = std::copysign(std::min(mu * dp, stop), u);
    vx -= ft / m;
    rim -= ft / (kappa * m);
  }
  return {vx, rim, std::abs(vx + rim) < 1e-12};
}

TEST(Rolling, BackspinImpulseBalanceSlidesThroughOrRollsOut) {
  const double e = kelvin_voigt_restitution(0.3), p = impact_normal_impulse(1.0, e, 1.0);
  for (const auto& [omega, kappa] : {std::array<double, 2>{30.0, 0.5}, {5.0, 0.5}, {12.0, 0.4}}) {
    const double rim = omega * 0.1;
    const SpinImpact closed = spin_impact(1.0, rim, p, 1.0, 0.5, kappa);
    const SpinImpact numeric = integrate_spin_impact(1.0, rim, p, 1.0, 0.5, kappa);
    EXPECT_EQ(closed.rolls, numeric.rolls) << "ω = " << omega;
    EXPECT_NEAR(closed.vx, numeric.vx, 1e-9) << "ω = " << omega;
    EXPECT_NEAR(closed.rim, numeric.rim, 1e-9) << "ω = " << omega;
  }
  // docs/closed-forms.md, section 5b (the disc, P = (1 + e)·1 N·s).
  const SpinImpact slides = spin_impact(1.0, 3.0, p, 1.0, 0.5, 0.5);
  EXPECT_FALSE(slides.rolls);
  EXPECT_NEAR(slides.vx, 0.274512, 5e-7);
  EXPECT_NEAR(slides.rim, 1.549025, 5e-7);
  const SpinImpact rolls = spin_impact(1.0, 0.5, p, 1.0, 0.5, 0.5);
  EXPECT_TRUE(rolls.rolls);
  EXPECT_NEAR(rolls.vx, 0.5, 1e-15);
  EXPECT_NEAR(rolls.rim, -0.5, 1e-15);
}

// ------------------------------------------------------------------ slope

// m·dv/dt = m·g·sinθ − friction(v), RK4 at 1e-5 s; v after `seconds`.
double slope_speed(double v0, double seconds, const std::function<double(double)>& accel) {
  Vec<1> y{v0};
  const long n = std::lround(seconds / 1e-5);
  for (long i = 0; i < n; ++i)
    rk4<1>(y, 1e-5, [&](const Vec<1>& s) { return Vec<1>{accel(s[0])}; });
  return y[0];
}

TEST(Slope, SlidesAtGTimesSinMinusMuCos) {
  const double th = 30.0 * kPi / 180.0, mu = 0.3, alpha = 100.0;
  EXPECT_NEAR(slope_sliding_acceleration(kG, th, mu), 2.356287, 5e-7);  // docs
  const auto accel = [&](double v) {
    return kG * std::sin(th) - mu * kG * std::cos(th) * std::tanh(alpha * v);
  };
  const double v1 = slope_speed(0.5, 0.1, accel), v2 = slope_speed(v1, 0.3, accel);
  EXPECT_NEAR(slope_sliding_acceleration(kG, th, mu), (v2 - v1) / 0.3, 1e-9);
}

TEST(Slope, TanhLawCreepsAtAtanhTanThetaOverMuOverAlpha) {
  const double th = 15.0 * kPi / 180.0, mu = 0.5, alpha = 100.0;
  EXPECT_NEAR(tanh_creep_speed(th, mu, alpha), 5.984e-3, 5e-7);  // docs
  const double v = slope_speed(0.0, 0.5, [&](double u) {
    return kG * std::sin(th) - mu * kG * std::cos(th) * std::tanh(alpha * u);
  });
  EXPECT_NEAR(tanh_creep_speed(th, mu, alpha), v, 1e-12);
}

TEST(Slope, ViscousCreepBalancesTheWeightAlongTheSlope) {
  const double th = 15.0 * kPi / 180.0, m = 1.5, impratio = 40.0, c = 30.0, d = 0.9;
  const int n = 2;
  const double b = impratio * c / (1.0 - d);  // each point's viscous slope, N·s/m
  const double v =
      slope_speed(0.0, 0.5, [&](double u) { return kG * std::sin(th) - n * b * u / m; });
  EXPECT_NEAR(soft_constraint_creep_speed(m, kG, th, n, impratio, c, d), v, 1e-15);
  EXPECT_NEAR(slope_rest_depth(m, kG, th, 1e5, 2) * 2.0 * 1e5, m * kG * std::cos(th), 1e-12);
}

// ------------------------------------------------------------ rolling stop

TEST(Rolling, CoulombRollStopsAtVSquaredOverTwoA) {
  // Uniform deceleration a = 0.5 m/s² from 2 m/s: 4 m, integrated with
  // RK4 (exact for the quadratic) until the speed reaches 0.
  EXPECT_NEAR(rolling_resistance_distance(2.0, 0.5), 4.0, 1e-15);
  Vec<2> y{0.0, 3.0};  // x, v
  const double a = 0.7, h = 1e-4;
  while (y[1] > a * h) rk4<2>(y, h, [&](const Vec<2>& s) { return Vec<2>{s[1], -a}; });
  rk4<2>(y, y[1] / a, [&](const Vec<2>& s) { return Vec<2>{s[1], -a}; });  // the last bit
  EXPECT_NEAR(rolling_resistance_distance(3.0, a), y[0], 1e-9);
  // The tanh laws' distance tends to it as α → ∞ (slip and tanh terms
  // fall as 1/α and 1/α²).
  const double a_roll = rolling_resistance_deceleration(0.01, kG, 0.1, kDiscInertiaRatio);
  EXPECT_NEAR(rolling_distance(2.0, a_roll, 0.5, kG, 1e9, kDiscInertiaRatio),
              rolling_resistance_distance(2.0, a_roll), 1e-8);
}

// ------------------------------------------------------------ oscillator

// z'' = −g − k·z − c·z' per unit mass, integrated with RK4.
Vec<2> integrate_oscillator(double k, double c, double z0, double w0, double s, long steps) {
  Vec<2> y{z0, w0};
  const double h = s / static_cast<double>(steps);
  for (long i = 0; i < steps; ++i)
    rk4<2>(y, h, [&](const Vec<2>& q) { return Vec<2>{q[1], -kG - k * q[0] - c * q[1]}; });
  return y;
}

TEST(Oscillator, DampedSolutionMatchesTheIntegratedOde) {
  // k = 1e4 1/s², ζ = 0.1 and 0.6, entering at 2.4 m/s; after 3 ms (in
  // contact) and 40 ms (several periods, settled towards z_eq = −g/k).
  // RK4 at ω·h = 1e-4: error ~ (ω·h)⁴ per period, far below 1e-10 m.
  for (double zeta : {0.1, 0.6}) {
    const double k = 1e4, c = 2.0 * zeta * std::sqrt(k);
    for (double s : {3e-3, 4e-2}) {
      const Vec<2> y = integrate_oscillator(k, c, 0.0, -2.4, s, static_cast<long>(s / 1e-6));
      const OscillatorState exact = damped_oscillator(kG, k, c, 0.0, -2.4, s);
      EXPECT_NEAR(exact.z, y[0], 1e-10) << "ζ " << zeta << ", s " << s;
      EXPECT_NEAR(exact.w, y[1], 1e-8) << "ζ " << zeta << ", s " << s;
    }
  }
  // The undamped spring without gravity: z = z0·cos(ωt), ω = √k.
  const OscillatorState cosine = damped_oscillator(0.0, 4.0, 0.0, 0.1, 0.0, 0.3);
  EXPECT_NEAR(cosine.z, 0.1 * std::cos(0.6), 1e-16);
  EXPECT_NEAR(cosine.w, -0.2 * std::sin(0.6), 1e-16);
  // Overdamped and critical: outside the closed form, NaN.
  EXPECT_TRUE(std::isnan(damped_oscillator(kG, 1e4, 200.0, 0.0, -1.0, 1e-3).z));
  EXPECT_TRUE(std::isnan(damped_oscillator(kG, 1e4, 300.0, 0.0, -1.0, 1e-3).w));
}

TEST(Oscillator, FlightIsTheParabolaAndFallTimeItsRoot) {
  // RK4 is exact on the parabola (to the rounding of 1000 steps).
  const Vec<2> y = integrate_oscillator(0.0, 0.0, 0.3, 1.2, 0.25, 1000);
  const OscillatorState flight = damped_oscillator(kG, 0.0, 0.0, 0.3, 1.2, 0.25);
  EXPECT_NEAR(flight.z, y[0], 1e-12);
  EXPECT_NEAR(flight.w, y[1], 1e-12);
  // From rest at 0.3 m: √(2·0.3/g) = 0.2473097 s.
  EXPECT_NEAR(fall_time(kG, 0.3, 0.0), std::sqrt(0.6 / kG), 1e-15);
  EXPECT_NEAR(fall_time(kG, 0.3, 0.0), 0.2473097, 1e-7);
  // Thrown up at 1.2 m/s: the integrated flight reaches z = 0 then.
  const double t = fall_time(kG, 0.3, 1.2);
  EXPECT_NEAR(integrate_oscillator(0.0, 0.0, 0.3, 1.2, t, 1000)[0], 0.0, 1e-12);
}

TEST(Oscillator, DropDepthIsTheUndampedTurningPoint) {
  // m = 2 kg dropped from rest 0.1 m above a spring k = 5e4 N/m: flight,
  // then m·z'' = −m·g − k·z below z = 0, integrated (RK4, h = 1e-7 s) to
  // the turning point w = 0. The force is continuous at z = 0, so RK4
  // loses at most O(h²) there: below 1e-12 m.
  const double m = 2.0, k = 5e4, height = 0.1;
  Vec<2> y{height, 0.0};
  const auto rate = [&](const Vec<2>& q) {
    return Vec<2>{q[1], -kG - (q[0] < 0.0 ? k / m * q[0] : 0.0)};
  };
  double deepest = 0.0;
  while (y[1] <= 0.0) {
    rk4<2>(y, 1e-7, rate);
    deepest = std::min(deepest, y[0]);
  }
  EXPECT_NEAR(drop_depth(m, kG, k, height), -deepest, 1e-9);
  // Dropped from the spring's top (H = 0): twice the static depth m·g/k.
  EXPECT_NEAR(drop_depth(m, kG, k, 0.0), 2.0 * rest_depth(m, kG, k, 1), 1e-18);
}

TEST(Oscillator, BouncingHeightIsFlightAndSpringInTurn) {
  // Apex 0.25 m, k = 1e4 1/s²: the phases checked against the flight and
  // the undamped oscillator above (each tested against an integrated ODE)
  // and against the energy, which the undamped bounce conserves.
  const double z0 = 0.25, k = 1e4;
  const double t1 = fall_time(kG, z0, 0.0);
  const double v1 = -kG * t1;
  EXPECT_NEAR(bouncing_height(kG, k, z0, 0.1), damped_oscillator(kG, 0, 0, z0, 0, 0.1).z, 1e-15);
  EXPECT_NEAR(bouncing_height(kG, k, z0, t1), 0.0, 1e-14);
  // In contact: the oscillator from (0, v1), 2 ms after touching.
  EXPECT_NEAR(bouncing_height(kG, k, z0, t1 + 2e-3), damped_oscillator(kG, k, 0, 0, v1, 2e-3).z,
              1e-14);
  // The contact ends where the oscillator returns to z = 0 with the speed
  // −v1 (energy): find that time by bisection on the oscillator itself.
  double lo = 1e-3, hi = 2.0 * M_PI / std::sqrt(k);
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (damped_oscillator(kG, k, 0, 0, v1, mid).z < 0.0 ? lo : hi) = mid;
  }
  EXPECT_NEAR(damped_oscillator(kG, k, 0, 0, v1, lo).w, -v1, 1e-9);
  const double period = 2.0 * t1 + lo;
  // Back at the apex after one period, and the same motion again.
  EXPECT_NEAR(bouncing_height(kG, k, z0, period), z0, 1e-9);
  EXPECT_NEAR(bouncing_height(kG, k, z0, period + 0.1), bouncing_height(kG, k, z0, 0.1), 1e-9);
  // Rising: the parabola from (0, −v1), 50 ms after leaving.
  EXPECT_NEAR(bouncing_height(kG, k, z0, t1 + lo + 0.05),
              damped_oscillator(kG, 0, 0, 0, -v1, 0.05).z, 1e-9);
}

// ------------------------------------------------------- soft constraint

TEST(SoftConstraint, RowForceSolvesItsEquation) {
  // f·R = aref − a0 − A·f, R = (1 − d)/d·Â, at several constants.
  for (double d : {1e-4, 0.5, 0.9, 0.99}) {
    const double a = 1.7, a_hat = 2.0 / 3.0, aref = 35.0, a0 = -kG;
    const double f = soft_constraint_force(a, a_hat, d, aref, a0);
    const double r = (1.0 - d) / d * a_hat;
    EXPECT_NEAR(f * r, aref - a0 - a * f, 1e-12 * (aref - a0)) << "d " << d;
  }
  // d → 1: the hard constraint, f = (aref − a0)/A.
  EXPECT_NEAR(soft_constraint_force(2.0, 0.5, 1.0, 3.0, -1.0), 2.0, 1e-15);
  // At the depth of benchmarks/rest.hpp (aref = K·d·p, K = s/d², a0 = −g)
  // the row carries the weight m·g and the body does not accelerate.
  const double m = 1.5, a_hat = 2.0 / 3.0, d = 0.9, stiffness = 1e4 * a_hat;
  const double p = soft_constraint_rest_depth(m, kG, a_hat, d, 1, stiffness);
  const double big_k = stiffness / (d * d);
  EXPECT_NEAR(soft_constraint_force(1.0 / m, a_hat, d, big_k * d * p, -kG), m * kG, 1e-12 * kG);
}

TEST(SoftConstraint, EllipticConeIsTheWeightedProjection) {
  const double k = 1e4, p = 1e-3, c = 50.0, mu = 0.5, impratio = 200.0;
  // Inside the cone: the rows alone.
  const ConeForce inside = elliptic_cone_force(k, p, c, -0.1, 1e-5, mu, impratio);
  EXPECT_EQ(inside.normal, k * p + c * 0.1);
  EXPECT_EQ(inside.tangential, -impratio * c * 1e-5);
  // On it: the f_n minimising (f_n − f_n⁰)² + (μ·f_n − |f_t⁰|)²/impratio
  // (bisection on the sign of the cost's slope), and |f_t| = μ·f_n.
  for (double vt : {2.0, -0.5}) {
    const double fn0 = k * p, ft0 = std::abs(impratio * c * vt);
    const auto slope = [&](double fn) { return (fn - fn0) + mu * (mu * fn - ft0) / impratio; };
    double lo = 0.0, hi = 1e4;
    for (int i = 0; i < 200; ++i) (slope(0.5 * (lo + hi)) < 0.0 ? lo : hi) = 0.5 * (lo + hi);
    const ConeForce on = elliptic_cone_force(k, p, c, 0.0, vt, mu, impratio);
    EXPECT_NEAR(on.normal, 0.5 * (lo + hi), 1e-9 * on.normal) << "v_t " << vt;
    EXPECT_NEAR(std::abs(on.tangential), mu * on.normal, 1e-12 * on.normal);
    EXPECT_LT(on.tangential * vt, 0.0);  // against the slip
  }
}

}  // namespace
}  // namespace contact2d::benchmarks
