// Sliding and rolling friction against their closed forms.
//
// Sliding. A flat box (width w, height h, resting on its bottom corners)
// launched at v0 is slowed by Ft = −μ·Fn·tanh(α·v_c), v_c the corners' slip
// speed, Fn summed over both corners = m·g on average (the vertical momentum
// starts and ends at zero, so ∫(Fn − m·g)dt = 0). With v_c = v:
//   m·dv/dt = −μ·m·g·tanh(α·v), and the distance to rest is
//   s0 = ∫₀^v0 v/(μ·g·tanh(α·v)) dv = v0²/(2μg) + (π²/12 − ε)/(α²·μ·g),
// ε = α²·∫_{v0}^∞ 2v/(e^{2αv} − 1)dv < e^{−2αv0}·(2αv0 + 1) = 3e-12 at
// α·v0 = 15 (1e-14 m of distance): the tanh adds π²/(12·α²·μ·g) to the
// Coulomb distance.
//
// Compliance. The friction force F = μ·m·g·tanh(α·v_c) acts h/2 below the
// centre; the corners balance its torque F·h/2 by loading the front corner
// and unloading the back one by ΔF = F·h/(2w), which on springs of
// stiffness k pitches the box nose-down by θ = −2ΔF/(k·w) = −β·tanh(α·v_c),
//   β = μ·m·g·h/(k·w²)   (quasi-static: the pitch mode, ~700 rad/s at
// k = 1e5, is fast against the slide). While tanh = 1 the pitch is constant
// and changes nothing (the start-up transient only redistributes the
// load). In the tail, as tanh(α·v) falls to 0, the box pitches back at
// ω = dθ/dt = β·α·μ·g·sech²(αv)·tanh(αv) > 0 and the corners slip at
// v_c = v + ω·h/2 instead of v: the extra friction μ·g·α·sech²(αv)·(h/2)·ω
// shortens the slide. To first order in β (v0·α ≫ 1), with the
// perturbation Δv of v obeying dΔv/dt = −μgα·sech²(αv)·(Δv + (h/2)·ω):
//   s_k = ∫Δv dt = −(h·β/2)·∫₀^∞ u/(sinh u·cosh³u) du = −(h·β/2)·(π²/8 − ½)
//       = −m·μ·g·h²·(π²/8 − ½)/(2·k·w²),
// independent of v0 and α: −2.70e-6 m at k = 1e5, −2.70e-7 m at k = 1e6
// (μ = 0.3, m = 1 kg, w = 0.4 m, h = 0.2 m). It falls as 1/k.
// Next term: the pitch lags its quasi-static value by the damper's time
// constant τ ≤ c/k (c/(2k) with one compressing corner, c/k with both) and
// the tail changes tanh at the rate μ·g·α, so the remainder is of relative
// size ≲ τ·μ·g·α: 0.19 at k = 1e5 (c = 2√(k·m), α = 10), 0.059 at k = 1e6.
// RK4 at Δt = 1e-4 integrates the slide to ~1e-10 m, and the stop threshold
// 1e-9 m/s leaves v/(μgα) < 1e-10 m to go.
//
// Rolling. A disc (I = m·R²/2) rolling at v0 without slip: the rolling torque
// μ_roll·Fn·sgn(ω) and the friction force F that keeps it rolling satisfy
// m·a = F, I·α = R·F + μ_roll·m·g, a = −α·R, so
//   a = −μ_roll·g/(R·(1 + I/(m·R²))) = −μ_roll·g/(1.5·R),  s = v0²/(2|a|).
// With sgn regularised as tanh(α·R·ω) the same integral adds π²/(12·α²·|a|).
// The regularised sliding friction adds a first-order term: to carry the
// force m·|a| the contact must slip at v_s = atanh(|a|/(μ·g))/α. The slip
// builds up in the first ~1 ms: with d(2v + u)/dt depending only on the rim
// speed u = −R·ω, it raises v by v_s/3 and lowers u by 2·v_s/3 against the
// no-slip line; u then stops at (v0 − 2v_s/3)/|a| while v = u + v_s, so
//   s = v0²/(2|a|) + v_s·v0/(3|a|) + π²/(12·α²·|a|) + O(v_s², 1/α²)
// (1.37e-3 m and 1.3e-4 m at α = 100; the slip term halves as α doubles).
//
// Tolerance of the disc: RK4 at Δt = 1e-4 integrates the smooth roll to
// ~1e-10 m; what remains is the coupling of the contact's vertical
// transient with the friction that spins the disc up by the slip
// ≈ atanh(μ_roll/(1.5·R·μ))/α, second order in the transient amplitude:
// measured 1.8e-5 m. Tolerance 1e-4 m, 0.003 % of the distance; the slip
// term (1.37e-3 m) is 14× the tolerance, so the test fails without it, and
// a wrong inertia factor (1.5 → 1 or 2) would move the distance by a third.
// (The tanh term of the disc, 1.3e-4 m, is only 1.3× the tolerance: it is
// included for completeness, not checked.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "benchmarks/rolling.hpp"
#include "benchmarks/sliding.hpp"
#include "core/stepper.hpp"
#include "support/support.hpp"

namespace contact2d {
namespace {

// x where the body's speed first drops below v_stop (or the last x).
double stop_distance(const Scene& scene, double v_stop) {
  const Trajectory trajectory = simulate(scene);
  EXPECT_FALSE(trajectory.divergence);
  for (const Sample& s : trajectory.samples) {
    if (s.t > 0.0 && std::abs(s.state.v.x()) < v_stop) return s.state.q.x() - scene.initial.q.x();
  }
  ADD_FAILURE() << "did not stop";
  return 0.0;
}

// The box slide at α = 10 s/m, μ = 0.3, v0 = 1.5 m/s: Coulomb distance
// 0.382 m, tanh term 2.795e-3 m. Expected s0 + s_k; tolerance
// (c/k)·μ·g·α·|s_k| + 1e-9 m (the lag remainder above, plus the integration
// and the stop): 5.0e-7 m at k = 1e5 and 1.7e-8 m at k = 1e6. The tanh term
// is 5600× the tolerance and s_k 5× (16× at k = 1e6): the test fails if the
// tanh correction or the compliance term is dropped, and the two
// stiffnesses check that the residual of the Coulomb + tanh law falls as 1/k.
// Measured residuals s − (s0 + s_k): −1.25e-7 m (k = 1e5) and −4.1e-9 m
// (k = 1e6), 4× below the tolerance, shrinking as k^(−3/2) like the lag.
TEST(SlidingFriction, FlatBoxStopsAtCoulombDistancePlusTanhCorrection) {
  for (double k : {1e5, 1e6}) {
    Scene scene = default_scene(Shape::Box);
    scene.contact.k = k;
    scene.contact.c = 2.0 * std::sqrt(scene.contact.k * scene.mass);
    scene.contact.mu = 0.3;
    scene.contact.alpha = 10.0;
    scene.sim.integrator = Integrator::RK4;
    scene.sim.duration = 2.0;
    const double g = scene.sim.gravity, mu = scene.contact.mu, alpha = scene.contact.alpha;
    const double m = scene.mass, w = scene.width, h = scene.height;
    const double v0 = 1.5;
    scene.initial.q = Vec3(0.0, 0.5 * h - m * g / (2.0 * k), 0.0);
    scene.initial.v = Vec3(v0, 0.0, 0.0);

    const benchmarks::BoxSlide slide =
        benchmarks::box_sliding_distance(v0, mu, g, alpha, m, w, h, k);
    const double coulomb = slide.coulomb, tanh_tail = slide.tanh, compliance = slide.pitch;
    const double expected = slide.distance();
    const double lag = scene.contact.c / k * mu * g * alpha;  // τ·μ·g·α, τ ≤ c/k
    const double tolerance = lag * std::abs(compliance) + 1e-9;
    // The regularised law never stops exactly; 1e-9 m/s leaves < 1e-10 m to go.
    const double s = stop_distance(scene, 1e-9);
    std::printf(
        "box slide, k = %.0e: s = %.10f m = Coulomb %.10f + tanh %.4g + compliance %.4g "
        "+ residual %.3g m (tolerance %.3g m)\n",
        k, s, coulomb, tanh_tail, compliance, s - expected, tolerance);
    EXPECT_NEAR(s, expected, tolerance) << "k = " << k;
  }
}

TEST(RollingFriction, DiscDeceleratesAtMuRollGOverOnePointFiveR) {
  Scene scene = default_scene(Shape::Circle);
  scene.contact.k = 1e5;
  scene.contact.c = 2.0 * std::sqrt(scene.contact.k * scene.mass);
  scene.contact.mu = 0.5;
  scene.contact.mu_roll = 0.01;
  scene.contact.alpha = 100.0;
  scene.sim.integrator = Integrator::RK4;
  scene.sim.duration = 4.0;
  const double g = scene.sim.gravity, R = scene.radius;
  const double v0 = 2.0;
  scene.initial.q = Vec3(0.0, R - scene.mass * g / scene.contact.k, 0.0);
  scene.initial.v = Vec3(v0, 0.0, -v0 / R);

  const double decel = benchmarks::rolling_resistance_deceleration(scene.contact.mu_roll, g, R,
                                                                   benchmarks::kDiscInertiaRatio);
  // Deceleration over the first second, from the sampled velocity.
  const Trajectory trajectory = simulate(scene);
  ASSERT_FALSE(trajectory.divergence);
  const auto at = [&](double t) {
    return trajectory.samples[static_cast<size_t>(std::llround(t / scene.sim.output_dt))].state;
  };
  const double measured_decel = (at(0.5).v.x() - at(1.5).v.x()) / 1.0;
  std::printf("disc: deceleration %.9f m/s² vs mu_roll*g/(1.5R) = %.9f\n", measured_decel, decel);
  // Between 0.5 s and 1.5 s tanh(α·R·ω) = tanh(≥ 100) is 1 to 1e-80: the
  // deceleration is exact up to the integration error, ~1e-9 m/s².
  EXPECT_NEAR(measured_decel, decel, 1e-6 * decel);

  const double alpha = scene.contact.alpha;
  const benchmarks::RollingStop stop = benchmarks::rolling_distance_terms(
      v0, decel, scene.contact.mu, g, alpha, benchmarks::kDiscInertiaRatio);
  const double coulomb = stop.roll, slip_term = stop.slip, tanh_tail = stop.tanh;
  const double s = stop_distance(scene, 1e-9);
  std::printf("disc roll: s = %.9f m, analytic %.9f m + slip %.4g m + tanh %.3g m = %.9f m\n", s,
              coulomb, slip_term, tanh_tail, coulomb + slip_term + tanh_tail);
  EXPECT_NEAR(s, coulomb + slip_term + tanh_tail, 1e-4);
}

// The default disc with μ = 0.5, μ_roll = 0.01 m, c = 200 N·s/m, at its rest
// depth, rolling at 0.3 m/s without slip, for `duration` s.
Scene rolling_disc(double duration) {
  Scene scene = default_scene(Shape::Circle);
  scene.contact.mu = 0.5;
  scene.contact.mu_roll = 0.01;
  scene.contact.c = 200.0;
  scene.sim.duration = duration;
  scene.initial.q = Vec3(0.0, scene.radius - scene.mass * scene.sim.gravity / scene.contact.k, 0.0);
  scene.initial.v = Vec3(0.3, 0.0, -0.3 / scene.radius);
  return scene;
}

TEST(RollingFriction, DiscAtRestNeitherChattersNorCreeps) {
  const Scene scene = rolling_disc(10.0);
  const Trajectory trajectory = simulate(scene);
  ASSERT_FALSE(trajectory.divergence);
  // After the stop (≈ 0.5 s), ω must not change sign step to step and x must
  // stay put: over the last 5 s it moves less than 1 µm.
  int sign_changes = 0;
  double previous = 0.0;
  double x_at_5 = 0.0;
  for (const Sample& s : trajectory.samples) {
    if (s.t < 5.0) continue;
    if (x_at_5 == 0.0) x_at_5 = s.state.q.x();
    if (s.state.v.z() * previous < 0.0) ++sign_changes;
    previous = s.state.v.z();
  }
  EXPECT_EQ(sign_changes, 0);
  EXPECT_NEAR(trajectory.samples.back().state.q.x(), x_at_5, 1e-6);
}

// The friction's own step limit (core/divergence.hpp, friction_step). At
// rest the tanh law is a damper on the disc's slip v + ω·R of rate
// μ·g·α·(1 + m·R²/I) = 3·μ·g·α, plus the rolling torque's on ω,
// μ_roll·m·g·α·R/I = 2·μ_roll·g·α/R: 1.67e4 1/s at μ = 0.5, μ_roll = 0.01 m,
// R = 0.1 m, α = 1e4 s/m (both written out here, not asked of the code).
// A scheme whose velocity update is explicit overshoots it past its limit
// on the negative real axis: 2 for semi-implicit Euler, 2.785 for RK4 (the
// real root of z³ − 4z² + 12z − 24, |1 − z + z²/2 − z³/6 + z⁴/24| = 1).
// Checked on the disc of DiscAtRestNeitherChattersNorCreeps, stepped
// sample by sample: with α set so that rate·Δt is 0.9 of the limit ω
// decays to zero (|ω| < 1e-12 rad/s after 3 s: the rate is 2.3e3 1/s or
// more, so anything left after 3 s is round-off); with 1.1 of it the disc
// never comes to rest (|ω| > 1e-6 rad/s) and stays finite: in semi-implicit
// Euler ω flips sign on every step (a two-step cycle: measured ±2 mrad/s at
// 1.08 of the limit), in RK4 it creeps (measured ω = −0.7 mrad/s, steady).
// The warning comes with the second only; implicit Euler has no such limit.
TEST(FrictionStep, TheDiscChattersAtRestExactlyPastTheLimitAndIsWarned) {
  const Scene scene = rolling_disc(4.0);
  const double g = scene.sim.gravity, r = scene.radius;
  const double rate_per_alpha = 3.0 * 0.5 * g + 2.0 * 0.01 * g / r;  // 1/s per s/m
  for (const auto& [integrator, limit] :
       {std::pair{Integrator::SemiImplicitEuler, 2.0}, std::pair{Integrator::RK4, 2.7852935634}}) {
    for (double fraction : {0.9, 1.1}) {
      Scene s = scene;
      s.sim.integrator = integrator;
      s.contact.alpha = fraction * limit / (rate_per_alpha * s.sim.dt);
      s.sim.output_dt = s.sim.dt;
      const std::string what =
          std::string(integrator_name(integrator)) + " at " + std::to_string(fraction);
      const Model model = make_model(s);
      const FrictionStep f = friction_step(model, integrator, s.sim.dt);
      EXPECT_NEAR(f.rate_dt, fraction * limit, 1e-9 * limit) << what;
      EXPECT_NEAR(f.limit, limit, 1e-9) << what;
      ReferenceStepper stepper(s);
      EXPECT_EQ(stepper.facts(s).warnings.size(), fraction > 1.0 ? 1u : 0u) << what;
      const Trajectory t = simulate(s);
      ASSERT_FALSE(t.divergence) << what;
      int flips = 0, after = 0;
      double largest = 0.0, previous = 0.0;
      for (const Sample& sample : t.samples) {
        if (sample.t < 3.0) continue;
        const double w = sample.state.v.z();
        ASSERT_TRUE(std::isfinite(w)) << what;
        largest = std::max(largest, std::abs(w));
        if (after++ > 0 && w * previous < 0.0) ++flips;
        previous = w;
      }
      if (fraction < 1.0) {
        EXPECT_LT(largest, 1e-12) << what;
      } else {
        EXPECT_GT(largest, 1e-6) << what;
        if (integrator == Integrator::SemiImplicitEuler) {
          EXPECT_EQ(flips, after - 1) << what << ": ω flips sign on every step";
        }
      }
    }
  }
  Scene implicit = scene;
  implicit.sim.integrator = Integrator::ImplicitEuler;
  implicit.contact.alpha = 1e6;
  EXPECT_FALSE(friction_step(make_model(implicit), Integrator::ImplicitEuler, 1e-4).beyond());
}

// On several contacts the slip couples with the body's pitch through the
// contacts' compliance, which λ leaves out: a box (1 kg, 0.4 × 0.2 m, μ =
// 0.5, α = 100 s/m, Kelvin–Voigt) sliding to rest on its two bottom corners,
// λ = μ·α·g·(1 + m·(h/2)²/I) = 785 1/s (I = m(w² + h²)/12), cycles from
// 0.85 of semi-implicit Euler's limit 2/λ (measured: Δt = 2.2e-3 s cycles,
// 2.15e-3 s comes to rest). The warning comes from 0.8 of it: at 0.75 the
// box comes to rest unwarned (|ω| < 1e-9 rad/s after 6 s), at 0.95 it
// cycles and is warned.
TEST(FrictionStep, ABoxOnTwoCornersIsWarnedBeforeItsCycleBegins) {
  Scene scene = default_scene(Shape::Box);
  scene.contact.mu = 0.5;
  scene.contact.alpha = 100.0;
  scene.contact.k = 1e4;
  scene.contact.c = 50.0;
  scene.contact.damping = DampingLaw::KelvinVoigt;
  scene.sim.duration = 8.0;
  const double g = scene.sim.gravity, h = scene.height, w = scene.width, m = scene.mass;
  scene.initial.q = Vec3(0.0, 0.5 * h - 0.5 * m * g / scene.contact.k, 0.0);
  scene.initial.v = Vec3(0.3, 0.0, 0.0);
  const double inertia = m * (w * w + h * h) / 12.0;
  const double lambda = 0.5 * 100.0 * g * (1.0 + m * 0.25 * h * h / inertia);
  for (double fraction : {0.75, 0.95}) {
    Scene s = scene;
    s.sim.dt = fraction * 2.0 / lambda;
    s.sim.output_dt = s.sim.dt;
    ReferenceStepper stepper(s);
    const Trajectory t = simulate(stepper, s.sim);
    ASSERT_FALSE(t.divergence) << fraction;
    EXPECT_EQ(stepper.facts(s).warnings.size(), fraction > 0.8 ? 1u : 0u) << fraction;
    double largest = 0.0;
    for (const Sample& sample : t.samples)
      if (sample.t > 6.0) largest = std::max(largest, std::abs(sample.state.v.z()));
    if (fraction < 0.8) {
      EXPECT_LT(largest, 1e-9) << fraction;
    } else {
      EXPECT_GT(largest, 1e-4) << fraction;
    }
  }
}

// smooth_sign is contact2d's bounded tanh (core/vector_math.hpp; its
// accuracy is tests/core/test_tanh.cpp's): bit for bit bounded_tanh on a
// fine grid across the saturation threshold (|x| = 22), exactly ±1 from
// there on, and the non-finite inputs.
TEST(SmoothSign, IsTheBoundedTanhAndSaturatesAt22) {
  for (double x = -40.0; x <= 40.0; x += 1.0 / 1024.0) {
    ASSERT_EQ(smooth_sign(x), bounded_tanh(x)) << "x = " << x;
    if (std::fabs(x) >= 22.0) {
      ASSERT_EQ(smooth_sign(x), std::copysign(1.0, x)) << "x = " << x;
    }
  }
  for (double x : {21.999999999999996, 22.0, 22.000000000000004, 1e300, -1e300}) {
    EXPECT_EQ(smooth_sign(x), std::tanh(x)) << "x = " << x;  // ±1 on both
    EXPECT_EQ(smooth_sign(-x), std::tanh(-x)) << "x = " << -x;
  }
  EXPECT_EQ(smooth_sign(INFINITY), 1.0);
  EXPECT_EQ(smooth_sign(-INFINITY), -1.0);
  EXPECT_TRUE(std::isnan(smooth_sign(NAN)));
}

}  // namespace
}  // namespace contact2d
