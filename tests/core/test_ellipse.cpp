// The ellipse (core/ellipse.hpp): its contact geometry against independent
// computations, the conservative spring, rest, rebound, obstacles and the
// scene file. Semi-axes a = 0.2 m (body x), b = 0.1 m (body y) unless said.
//
// 1. Geometry. The lowest point of the rim R(θ)·(a·cos φ, b·sin φ) found by
//    brute force over N = 100000 samples of φ, against ellipse_lowest_point.
//    The sampled minimum of y(φ) (an amplitude-h sinusoid in φ, h ≤ a) lies
//    above the true one by at most ½·h·(π/N)² ≤ 9.9e-11 m (the nearest
//    sample is within π/N of the minimiser); its x is off by at most
//    |x′|·π/N ≤ a·π/N = 6.3e-6 m. The turn rate against a central difference
//    of r_x (step 1e-5 rad): truncation ≤ h²/6·max|r_x‴|, and max|r_x‴| is
//    at θ = 0, (a² − b²)/b·(4 + 3(a² − b²)/b²) = 3.9 m (Taylor expansion of
//    r_x at 0; a scan of θ at 40 digits finds no larger value), so
//    6.5e-11 m/rad (attained at θ = 0), plus rounding 4ε·max|r_x|/h = 9e-12
//    (max|r_x| = 0.1 m): tolerance 1e-10 m/rad.
//
// 2. Conservative spring: the force stage's (F, τ) at v = 0, g = 0, μ = 0
//    is −∇(½·k·d²) by central differences of energy().
//
// 3. Rest depth m·g/k (benchmarks/rest.hpp, one contact), flat and upright.
//
// 4. Rebound under Kelvin–Voigt: without gravity against
//    benchmarks::kelvin_voigt_restitution (as tests/core/test_rebound.cpp),
//    with gravity against the damped oscillator of benchmarks/oscillator.hpp.
//
// 5. Obstacles: a box's vertical face, a vertical capsule, a round post.
//
// 6. The scene file's keys a, b, inertia and the range check of b.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "benchmarks/impact.hpp"
#include "benchmarks/oscillator.hpp"
#include "benchmarks/rest.hpp"
#include "core/contacts.hpp"
#include "core/dynamics.hpp"
#include "core/ellipse.hpp"
#include "core/input_error.hpp"
#include "core/integrators.hpp"
#include "core/obstacles.hpp"
#include "core/rng.hpp"
#include "core/run.hpp"
#include "core/scene.hpp"
#include "io/scene_file.hpp"
#include "reference/dense_reference.hpp"
#include "support/support.hpp"

namespace contact2d {
namespace {

constexpr double kA = 0.2;  // semi-axis along the body's x, m
constexpr double kB = 0.1;  // semi-axis along the body's y, m
constexpr double kEps = std::numeric_limits<double>::epsilon();

// The angles of the geometry and obstacle tests: the axes, a few fixed
// ones in every quadrant, and six from a fixed SplitMix64 sequence.
std::vector<double> test_angles() {
  std::vector<double> angles = {0.0, test::kPi / 2, -test::kPi / 2, test::kPi / 4, 0.7, -1.1, 2.3,
                                3.0};
  std::uint64_t state = 20240611;
  for (int i = 0; i < 6; ++i) angles.push_back(test::kPi * (2.0 * next_uniform(state) - 1.0));
  return angles;
}

// ---------------------------------------------------------------------------
// 1. Geometry.

TEST(EllipseGeometry, LowestPointMatchesBruteForceMinimumOverTheRim) {
  constexpr int kSamples = 100000;
  std::vector<double> cos_phi(kSamples), sin_phi(kSamples);
  for (int i = 0; i < kSamples; ++i) {
    const double phi = 2.0 * test::kPi * i / kSamples;
    cos_phi[i] = std::cos(phi);
    sin_phi[i] = std::sin(phi);
  }
  const double half_spacing = test::kPi / kSamples;
  const double tol_y = 0.5 * kA * half_spacing * half_spacing + 1e-15;  // ≤ 9.9e-11 m
  const double tol_x = kA * half_spacing + 1e-15;                       // ≤ 6.3e-6 m
  for (const double theta : test_angles()) {
    const double c = std::cos(theta), s = std::sin(theta);
    int best = 0;
    double best_y = std::numeric_limits<double>::infinity();
    for (int i = 0; i < kSamples; ++i) {
      const double y = s * kA * cos_phi[i] + c * kB * sin_phi[i];  // row 2 of R·e_b
      if (y < best_y) {
        best_y = y;
        best = i;
      }
    }
    const double best_x = c * kA * cos_phi[best] - s * kB * sin_phi[best];
    const Vec2 r = ellipse_lowest_point(kA, kB, theta);
    // The sampled minimum is never below the true one.
    EXPECT_GE(best_y - r.y(), -1e-15) << "theta = " << theta;
    EXPECT_LE(best_y - r.y(), tol_y) << "theta = " << theta;
    EXPECT_NEAR(r.x(), best_x, tol_x) << "theta = " << theta;
  }
}

TEST(EllipseGeometry, LowestPointOnTheAxes) {
  // θ = 0: h = √(b²) = b exactly (IEEE sqrt of a square), r_x = −0.
  const Vec2 flat = ellipse_lowest_point(kA, kB, 0.0);
  EXPECT_EQ(flat.y(), -kB);
  EXPECT_EQ(flat.x(), 0.0);
  // θ = π/2 in double: cos θ = 6.1e-17, not 0, so r_x = −(a² − b²)·6.1e-17/a
  // ≈ −9e-18 m and h = a to within an ulp: tolerance 1e-15 m.
  const Vec2 upright = ellipse_lowest_point(kA, kB, test::kPi / 2);
  EXPECT_NEAR(upright.y(), -kA, 1e-15);
  EXPECT_NEAR(upright.x(), 0.0, 1e-15);
  // A circle (a = b): the lowest point is straight below at every θ.
  for (const double theta : test_angles()) {
    const Vec2 r = ellipse_lowest_point(kB, kB, theta);
    EXPECT_NEAR(r.y(), -kB, 1e-15);
    EXPECT_NEAR(r.x(), 0.0, 1e-15);
  }
}

TEST(EllipseGeometry, TurnRateMatchesCentralDifferenceOfLeverArm) {
  // Tolerance in the header: 6.5e-11 truncation + 9e-12 rounding < 1e-10.
  const double h = 1e-5;
  const double max_third = (kA * kA - kB * kB) / kB * (4.0 + 3.0 * (kA * kA - kB * kB) / (kB * kB));
  ASSERT_LT(h * h / 6.0 * max_third + 4.0 * kEps * 0.1 / h, 1e-10);
  const double tol = 1e-10;
  std::vector<double> angles = test_angles();
  for (int i = 0; i < 64; ++i) angles.push_back(2.0 * test::kPi * i / 64);
  double worst = 0.0, worst_y = 0.0;
  for (const double theta : angles) {
    const Vec2 plus = ellipse_lowest_point(kA, kB, theta + h);
    const Vec2 minus = ellipse_lowest_point(kA, kB, theta - h);
    const double fd_x = (plus.x() - minus.x()) / (2.0 * h);
    const double fd_y = (plus.y() - minus.y()) / (2.0 * h);
    const double rate = ellipse_lowest_point_turn_rate(kA, kB, theta);
    EXPECT_NEAR(rate, fd_x, tol) << "theta = " << theta;
    // dr_y/dθ = r_x (the envelope theorem the spring's torque rests on):
    // the same truncation with |r_y‴| = |r_x″| ≤ 0.65 m, so the same tolerance.
    EXPECT_NEAR(ellipse_lowest_point(kA, kB, theta).x(), fd_y, tol) << "theta = " << theta;
    worst = std::max(worst, std::abs(rate - fd_x));
    worst_y = std::max(worst_y, std::abs(ellipse_lowest_point(kA, kB, theta).x() - fd_y));
  }
  // At θ = 0 the closed form: dr_x/dθ = −(a² − b²)/b.
  EXPECT_NEAR(ellipse_lowest_point_turn_rate(kA, kB, 0.0), -(kA * kA - kB * kB) / kB, 1e-15);
  std::printf("turn rate: max |rate - FD| %.3g, max |r_x - dr_y/dtheta FD| %.3g (tolerance %.3g)\n",
              worst, worst_y, tol);
}

// ---------------------------------------------------------------------------
// 2. Conservative spring. With v = 0, g = 0 and μ = μ_roll = 0 the force
// stage's (F_x, F_y, τ) = (m·a_x, m·a_y, I·a_θ) must be −∇E of
// E = energy() = Σ ½·k·d² (no kinetic, no gravity term). Central differences
// with step h: truncation h²/6·|E‴|. Along θ (ground),
// E‴ = k·(3·r_x·r_x′ − d·r_x″) (d′ = −r_x), |E‴| ≤ 1e4·(3·0.1·0.3 +
// 2e-3·0.65) < 1e3 J, so 1.7e-8 N·m at h = 1e-5; rounding: d = h(θ) − y is
// off by ≈ 2ε·0.2 m = 9e-17 m, E by k·d·9e-17 ≤ 2e-15 J, over 2h: 1e-10 N·m.
// Along x, y the ground's E is ½·k·(y − …)², exactly quadratic in y: only
// rounding. Tolerance 1e-7 N·m and N, ~1e-7 of the torque (≈ 1 N·m) and force.
//
// Against an obstacle the lever arm comes from a golden-section search whose
// minimum is flat: f(φ) = sd(e(φ)) is known to δf ≈ 4ε·1 m ≈ 1e-15 m, so φ*
// only to √(2·δf/f″) with f″ the rim's extent normal to the surface at its
// extreme point (w or h(θ), ≥ b): 1.4e-7
// rad, the contact point to a·1.4e-7 = 3e-8 m along the tangent, the torque
// to k·d·3e-8 ≤ 6e-7 N·m. Tolerance 2e-6 N·m there (the forces keep 1e-7).

struct Gradient {
  Vec3 force;  // (F_x, F_y, τ) of the force stage
  Vec3 fd;     // −∇E by central differences
};

Gradient force_and_energy_gradient(const Model& model, const Vec3& q, double h) {
  const Vec3 a = acceleration(model, q, Vec3::Zero());
  Gradient g;
  g.force = Vec3(model.body.mass * a.x(), model.body.mass * a.y(), model.body.inertia * a.z());
  for (int j = 0; j < 3; ++j) {
    State plus, minus;
    plus.q = q;
    minus.q = q;
    plus.q[j] += h;
    minus.q[j] -= h;
    g.fd[j] = -(energy(model, plus) - energy(model, minus)) / (2.0 * h);
  }
  return g;
}

Model conservative_model(const std::vector<Obstacle>& obstacles) {
  Scene scene = default_scene(Shape::Ellipse);
  scene.a = kA;
  scene.b = kB;
  scene.contact.k = 1e4;
  scene.contact.c = 200.0;  // no effect at v = 0
  scene.contact.mu = 0.0;
  scene.contact.mu_roll = 0.0;
  scene.obstacles = obstacles;
  Model model = make_model(scene);
  model.gravity = 0.0;
  return model;
}

TEST(EllipseConservative, GroundTorqueIsMinusEnergyGradient) {
  const Model model = conservative_model({});
  const double h = 1e-5;
  double worst = 0.0;
  for (const double theta : test_angles()) {
    const double depth = 2e-3;
    const double s = std::sin(theta), c = std::cos(theta);
    const double height = std::sqrt(kA * kA * s * s + kB * kB * c * c);  // centre − lowest point
    const Vec3 q(0.3, height - depth, theta);
    const Gradient g = force_and_energy_gradient(model, q, h);
    EXPECT_NEAR(g.force.x(), g.fd.x(), 1e-7) << "theta = " << theta;
    EXPECT_NEAR(g.force.y(), g.fd.y(), 1e-7) << "theta = " << theta;
    EXPECT_NEAR(g.force.z(), g.fd.z(), 1e-7) << "theta = " << theta;
    // The spring itself: F_y = k·d (n = +y; d to rounding, k·4ε·0.2 m ≈ 2e-12 N)
    // and no sideways force at μ = 0.
    EXPECT_NEAR(g.force.y(), model.contact.k * depth, 1e-9);
    EXPECT_EQ(g.force.x(), 0.0);
    worst = std::max(worst, std::abs(g.force.z() - g.fd.z()));
  }
  std::printf("ground: max |tau - (-dE/dtheta)| %.3g N·m\n", worst);
}

TEST(EllipseConservative, ObstacleForceAndTorqueAreMinusEnergyGradient) {
  // A box whose left face is x = 0.5 and a capsule lying along y = 0.4
  // (its top at 0.45), well away from the ground; one at a time.
  const std::vector<Obstacle> obstacles = {
      make_box_obstacle(1.5, 1.0, 2.0, 2.0),
      make_segment_obstacle(Vec2(-2.0, 0.4), Vec2(2.0, 0.4), 0.05)};
  const double h = 1e-5, depth = 2e-3;
  double worst = 0.0, worst_force = 0.0;
  for (size_t j = 0; j < obstacles.size(); ++j) {
    const Model model = conservative_model({obstacles[j]});
    for (const double theta : test_angles()) {
      const double s = std::sin(theta), c = std::cos(theta);
      Vec3 q;
      if (j == 0) {  // the rim's rightmost point `depth` into the face x = 0.5
        q = Vec3(0.5 - std::sqrt(kA * kA * c * c + kB * kB * s * s) + depth, 1.0, theta);
      } else {  // its lowest point `depth` into the capsule's top y = 0.45
        q = Vec3(0.1, 0.45 + std::sqrt(kA * kA * s * s + kB * kB * c * c) - depth, theta);
      }
      const Gradient g = force_and_energy_gradient(model, q, h);
      EXPECT_NEAR(g.force.x(), g.fd.x(), 1e-7) << "obstacle " << j << ", theta = " << theta;
      EXPECT_NEAR(g.force.y(), g.fd.y(), 1e-7) << "obstacle " << j << ", theta = " << theta;
      EXPECT_NEAR(g.force.z(), g.fd.z(), 2e-6) << "obstacle " << j << ", theta = " << theta;
      worst = std::max(worst, std::abs(g.force.z() - g.fd.z()));
      worst_force =
          std::max(worst_force, (g.force.head<2>() - g.fd.head<2>()).cwiseAbs().maxCoeff());
    }
  }
  std::printf("obstacles: max |F - (-dE/dx, -dE/dy)| %.3g N, |tau - (-dE/dtheta)| %.3g N·m\n",
              worst_force, worst);
}

// ---------------------------------------------------------------------------
// 3. Rest depth. One contact carries the weight: d = m·g/k
// (benchmarks::rest_depth with N = 1). Critically damped Kelvin–Voigt
// (test::resting_scene: k = 1e4, ζ = 1, ω = 100 rad/s, Δt = 1e-4). At rest
// a = 0 is a fixed point of every integrator, so the only error is the
// transient (1 + ω·t)·e^(−ω·t) plus rounding: tolerance 1e-9·d, as in
// tests/core/test_static.cpp.
//
// Flat (θ = 0): r_x = −0 exactly, the torque is 0 and θ stays 0 (checked to
// 1e-12 rad as for the flat box), 2 s.
// Upright (θ = π/2, on the end of the major axis): an unstable equilibrium.
// θ = π/2 in double is π/2 − 6.1e-17, a tilt that grows as cosh(λ·t) with
// λ² = m·g·(a² − b²)/(a·I) (the centre's height a − (a² − b²)/(2a)·δ²
// near the top, frictionless so I about the COM): λ = 10.8 /s. Over 0.5 s
// (the transient (1 + 50)·e^(−50) = 1e-20) the tilt grows by cosh(5.4) = 110;
// even a Newton residual of 1e-12 rad would reach 1.1e-10 rad and move the
// centre by (a² − b²)/(2a)·δ² = 1e-21 m. So the same 1e-9·d, and
// |θ − π/2| < 1e-9 rad. (Measured: θ does not move at all, Δt·ω staying
// below half an ulp of π/2; the depth is m·g/k to 1.2e-15 m.)

class EllipseRest : public ::testing::TestWithParam<Integrator> {};

TEST_P(EllipseRest, FlatSinksByWeightOverStiffness) {
  Scene scene = test::resting_scene(Shape::Ellipse, GetParam());
  scene.a = kA;
  scene.b = kB;
  scene.initial.q = Vec3(0.0, kB, 0.0);
  const double d = benchmarks::rest_depth(scene.mass, scene.sim.gravity, scene.contact.k, 1);
  const State s = test::final_state(scene);
  EXPECT_NEAR(kB - s.q.y(), d, 1e-9 * d);
  EXPECT_NEAR(s.q.z(), 0.0, 1e-12);
  EXPECT_NEAR(s.q.x(), 0.0, 1e-12);
}

TEST_P(EllipseRest, UprightHoldsOnTheMajorAxisForAShortRun) {
  Scene scene = test::resting_scene(Shape::Ellipse, GetParam());
  scene.a = kA;
  scene.b = kB;
  scene.sim.duration = 0.5;
  scene.initial.q = Vec3(0.0, kA, test::kPi / 2);
  const double d = benchmarks::rest_depth(scene.mass, scene.sim.gravity, scene.contact.k, 1);
  const State s = test::final_state(scene);
  std::printf("upright (%s): depth - m·g/k = %.3g m, theta - pi/2 = %.3g rad\n",
              std::string(integrator_name(GetParam())).c_str(), kA - s.q.y() - d,
              s.q.z() - test::kPi / 2);
  EXPECT_NEAR(kA - s.q.y(), d, 1e-9 * d);
  EXPECT_NEAR(s.q.z(), test::kPi / 2, 1e-9);
}

INSTANTIATE_TEST_SUITE_P(EllipseAllIntegrators, EllipseRest, ::testing::ValuesIn(kAllIntegrators),
                         [](const auto& info) { return std::string(integrator_name(info.param)); });

// ---------------------------------------------------------------------------
// 4. Rebound under Kelvin–Voigt, flat (θ = 0, ω = 0, v_x = 0): r_x = −0, so
// the lowest point stays under the centre, the torque is 0 and θ stays 0:
// the motion is the 1-D spring–damper of the centre's height.
//
// (a) Without gravity, exactly as tests/core/test_rebound.cpp for the point
// mass: RK4 at ω·Δt = 1e-3, starting 1e-12 m deep at v0 = 1 m/s; the kink
// of the law inside one step bounds the error by 2ζ·(ω·Δt)² = 2e-6·ζ
// relative (there measured at most 3e-8).

TEST(EllipseRebound, KelvinVoigtWithoutGravityMatchesClosedForm) {
  for (const double zeta : {0.1, 0.3, 0.6}) {
    Scene scene = test::impact_scene(Shape::Ellipse, DampingLaw::KelvinVoigt, zeta);
    scene.a = kA;
    scene.b = kB;
    const double v0 = 1.0;
    scene.initial.q = Vec3(0.0, kB - 1e-12, 0.0);
    scene.initial.v = Vec3(0.0, -v0, 0.0);
    const Trajectory trajectory = simulate(scene);
    ASSERT_FALSE(trajectory.divergence);
    const State& end = trajectory.samples.back().state;
    ASSERT_GT(end.q.y(), kB) << "still in contact at the end";
    const double e = end.v.y() / v0;
    const double expected = benchmarks::kelvin_voigt_restitution(zeta);
    std::printf("ellipse kelvin_voigt g=0 zeta=%.2f  e_sim=%.10f  e_closed=%.10f\n", zeta, e,
                expected);
    EXPECT_NEAR(e, expected, 2e-6 * zeta * expected);
    EXPECT_EQ(end.q.z(), 0.0);
    EXPECT_EQ(end.v.z(), 0.0);
  }
}

// (b) With gravity, dropped from rest at H = 0.05 m (lowest point above the
// ground), m = 1 kg, k = 1e4 N/m, ζ = 0.1 (c = 20 N·s/m), g = 9.81.
// Closed form, piece by piece (benchmarks/oscillator.hpp): the fall
// reaches z = 0 at v_in = √(2gH); in contact z'' = −g − k·z − c·z' (per
// unit mass) is damped_oscillator from (0, −v_in) while the Kelvin–Voigt
// force −k·z − c·z' is positive; it returns to zero at s_e (bisection on the
// closed form to 1e-15 s), at z_e < 0, w_e; from there the flight rises to
// z = 0 at w_out = √(w_e² + 2g·z_e). The force stays off on the way up if
// the point reaches z = 0 before the clamped law's aim
// k·d − c·v_n = t·(c·g − k·w_e) + k·g·t²/2 turns positive again, at
// t = 2(w_e/g − c/k): checked below (else the body would not leave).
// The restitution is w_out/v_in. (Without gravity it would be 0.7443; gravity
// over the contact time π/ω_d ≈ 0.03 s changes it by ≈ g·t_c/v_in ≈ 0.3, so
// the gravity-free form does not apply here.)
struct DropRebound {
  double v_in = 0.0;     // speed at touchdown, m/s
  double t_touch = 0.0;  // s
  double t_force_zero = 0.0;
  double t_out = 0.0;     // the lowest point back at z = 0, s
  double w_out = 0.0;     // its speed there, m/s
  double reengage = 0.0;  // when the clamped law would push again, after t_force_zero
};

DropRebound closed_form_drop(double g, double k, double c, double height) {
  DropRebound r;
  r.t_touch = benchmarks::fall_time(g, height, 0.0);
  r.v_in = -benchmarks::damped_oscillator(g, 0.0, 0.0, height, 0.0, r.t_touch).w;
  auto force = [&](double s) {
    const benchmarks::OscillatorState z = benchmarks::damped_oscillator(g, k, c, 0.0, -r.v_in, s);
    return -k * z.z - c * z.w;
  };
  // Bracket the first sign change (the force is c·v_in > 0 at s = 0), then bisect.
  const double period = 2.0 * test::kPi / std::sqrt(k - 0.25 * c * c);
  double lo = 0.0, hi = 0.0;
  for (int i = 1; i <= 400; ++i) {
    hi = period * i / 400.0;
    if (force(hi) <= 0.0) break;
    lo = hi;
  }
  for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
    const double mid = 0.5 * (lo + hi);
    (force(mid) > 0.0 ? lo : hi) = mid;
  }
  const double s_e = 0.5 * (lo + hi);
  const benchmarks::OscillatorState exit =
      benchmarks::damped_oscillator(g, k, c, 0.0, -r.v_in, s_e);
  r.t_force_zero = r.t_touch + s_e;
  r.w_out = std::sqrt(exit.w * exit.w + 2.0 * g * exit.z);
  r.t_out = r.t_force_zero + (exit.w - r.w_out) / g;  // w falls linearly in flight
  r.reengage = 2.0 * (exit.w / g - c / k);
  return r;
}

Scene drop_scene(double zeta, double height) {
  Scene scene = default_scene(Shape::Ellipse);
  scene.a = kA;
  scene.b = kB;
  scene.mass = 1.0;
  scene.contact.k = 1e4;
  scene.contact.c = zeta * 2.0 * std::sqrt(scene.mass * scene.contact.k);
  scene.contact.mu = 0.0;
  scene.contact.damping = DampingLaw::KelvinVoigt;
  scene.initial.q = Vec3(0.0, kB + height, 0.0);
  return scene;
}

constexpr double kDropZeta = 0.1;
constexpr double kDropHeight = 0.05;

// The converged reference (Dormand–Prince with events) at tol = 1e-10:
// global error a few times tol (tests/reference/test_dense_reference.cpp
// measures 9.7e-10 m at 1e-10 on a bouncing point mass), the closed form is
// exact to the bisection's 1e-15 s: tolerance 1e-8 on the restitution
// (and 1e-8 m/s, 1e-8 m on the state 10 ms into the flight), as in
// tests/reference/test_reference_closed_forms.cpp.
TEST(EllipseRebound, DropUnderGravityConvergedReferenceMatchesClosedForm) {
  Scene scene = drop_scene(kDropZeta, kDropHeight);
  const double g = scene.sim.gravity, m = scene.mass;
  const DropRebound cf = closed_form_drop(g, scene.contact.k / m, scene.contact.c / m, kDropHeight);
  ASSERT_LT(cf.t_out - cf.t_force_zero, cf.reengage) << "the force would push again: no clean exit";
  const double later = 0.01;  // into the rising flight (apex at w_out/g = 0.076 s)
  scene.sim.duration = cf.t_out + later;
  const DenseTrajectory ref = converged_reference(scene, 1e-10);
  ASSERT_TRUE(ref.ok()) << ref.failure();
  const State s = ref.at(cf.t_out + later);
  const double w = s.v.y() + g * later;  // back to z = 0 in the exact flight
  const double y = kB + cf.w_out * later - 0.5 * g * later * later;
  std::printf(
      "ellipse drop (reference): e = %.12f, closed form %.12f (g-free %.6f); y - closed %.3g m, "
      "events %lld\n",
      w / cf.v_in, cf.w_out / cf.v_in, benchmarks::kelvin_voigt_restitution(kDropZeta), s.q.y() - y,
      ref.stats().events);
  EXPECT_NEAR(w / cf.v_in, cf.w_out / cf.v_in, 1e-8);
  EXPECT_NEAR(s.q.y(), y, 1e-8);
  EXPECT_NEAR(s.q.z(), 0.0, 1e-12);
  EXPECT_NEAR(s.q.x(), 0.0, 1e-12);
}

// Semi-implicit Euler at Δt = 1e-5 and 1e-6 s (ω·Δt = 1e-3, 1e-4), stepped
// one step at a time: the first step with the lowest point back above the
// ground gives w_out = √(v² + 2g·z) (the exact flight back to z = 0). A
// first-order method with three O(Δt) terms, none of which averages out:
//   entry  the Kelvin–Voigt force jumps to c·v_in at touchdown and the step
//          that first ends below the ground applies it for up to one step
//          too long or short: ≤ (c/m)·v_in·Δt, relative 2ζ·ω·Δt;
//   exit   the spring is still loaded where the force reaches zero (depth
//          c·w_e/k, not 0), where the method's shadow energy ½v² + ½ω²x²
//          ± ½·Δt·ω²·x·v differs from the energy by ½·(c/m)·Δt·w_e²,
//          relative ½ζ·ω·Δt in w; with the damper's explicit evaluation, of
//          the same order, ≤ ζ·ω·Δt;
//   flight in free fall the method's ½v² + g·y drifts by −½·g·Δt·|v| (exactly,
//          per unit mass), relative −½·g·Δt/v² in w: ½·g·Δt/v_in falling,
//          ½·g·Δt/w_out rising, together ≤ g·Δt/w_out.
// Tolerance (3ζ·ω + g/w_out)·Δt relative: 4.4e-4 and 4.4e-5. Measured
// over 40 steps Δt in [0.8, 1.2]·1e-5 and as many in [0.8, 1.2]·1e-6 (the
// error is a sawtooth in Δt from where touchdown falls in a step, not a
// smooth C·Δt): at most 1.7e-4 and 1.9e-5 relative, 0.16·ω·Δt.
TEST(EllipseRebound, DropUnderGravitySemiImplicitEulerMatchesClosedForm) {
  const Scene scene = drop_scene(kDropZeta, kDropHeight);
  const Model model = make_model(scene);
  const double g = scene.sim.gravity, m = scene.mass, k = scene.contact.k;
  const DropRebound cf = closed_form_drop(g, k / m, scene.contact.c / m, kDropHeight);
  const double expected = cf.w_out / cf.v_in;
  double e_at[2] = {0.0, 0.0};
  const double dts[2] = {1e-5, 1e-6};
  for (int run = 0; run < 2; ++run) {
    const double dt = dts[run];
    StepWorkspace ws(model);
    State s = scene.initial;
    find_contacts(model, s.q, ws.contacts);
    bool touched = false;
    const long long steps = static_cast<long long>((cf.t_out + 0.01) / dt);
    for (long long i = 0; i < steps; ++i) {
      step(model, Integrator::SemiImplicitEuler, dt, s, ws);
      const double z = s.q.y() - kB;
      if (z < 0.0) touched = true;
      if (touched && z >= 0.0) {
        e_at[run] = std::sqrt(s.v.y() * s.v.y() + 2.0 * g * z) / cf.v_in;
        break;
      }
    }
    ASSERT_TRUE(touched);
    EXPECT_NEAR(s.q.z(), 0.0, 1e-12);
  }
  std::printf(
      "ellipse drop (semi-implicit Euler): e = %.10f (dt 1e-5), %.10f (dt 1e-6), closed form "
      "%.10f; errors %.3g, %.3g\n",
      e_at[0], e_at[1], expected, e_at[0] - expected, e_at[1] - expected);
  for (int run = 0; run < 2; ++run) {
    const double tol = (3.0 * kDropZeta * std::sqrt(k / m) + g / cf.w_out) * dts[run];
    EXPECT_NEAR(e_at[run], expected, tol * expected) << "dt = " << dts[run];
  }
}

// ---------------------------------------------------------------------------
// 5. Obstacles. The contact is the rim's extreme point: against a vertical
// face at x = X from the left, the rightmost point, x-extent
// w = √(a²·cos²θ + b²·sin²θ) from the centre at r = (w, (a² − b²)·s·c/w)
// (the support point A·e_x/√(e_xᵀA·e_x), A = R·diag(a², b²)·Rᵀ), depth the
// overlap p_x + w − X, normal (−1, 0). Tolerances: depth and r_x (a smooth
// maximum: second order in the search's error) ≈ rounding of coordinates
// ≈ 1 m: 1e-14 m. r_y, along the face, is where the minimum is flat:
// f(φ) is known to δf ≈ 4ε·1 m, so φ* to √(2·δf/w) ≤ 1.4e-7 rad (w ≥ b),
// and r_y to a·1.4e-7 = 3e-8 m: tolerance 1e-7 m. The found point must lie
// on the rim (its body-frame (u/a)² + (v/b)² = 1 to 1e-12).

void expect_on_rim(const Vec2& r, double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  const double u = c * r.x() + s * r.y(), v = -s * r.x() + c * r.y();
  EXPECT_NEAR(u * u / (kA * kA) + v * v / (kB * kB), 1.0, 1e-12) << "theta = " << theta;
}

TEST(EllipseObstacle, BoxFaceContactIsTheRimExtremeWithTheOverlapAsDepth) {
  const double overlap = 3e-3;
  // Left face x = 0.5 (box [0.5, 2.5] × [0, 2]) and right face x = −0.5
  // (box [−2.5, −0.5] × [0, 2]); centre at height 1, far from the other faces.
  const Obstacle right_box = make_box_obstacle(1.5, 1.0, 2.0, 2.0);
  const Obstacle left_box = make_box_obstacle(-1.5, 1.0, 2.0, 2.0);
  double worst_ry = 0.0, worst_depth = 0.0;
  for (const double theta : test_angles()) {
    const double c = std::cos(theta), s = std::sin(theta);
    const double w = std::sqrt(kA * kA * c * c + kB * kB * s * s);
    const double ry = (kA * kA - kB * kB) * s * c / w;
    for (const int side : {+1, -1}) {  // +1: the box to the right of the ellipse
      const Obstacle& box = side > 0 ? right_box : left_box;
      const Vec2 p(side * (0.5 - w + overlap), 1.0);
      ObstacleContact hit;
      ASSERT_TRUE(ellipse_obstacle_contact(box, kA, kB, p, c, s, hit))
          << "theta = " << theta << ", side " << side;
      EXPECT_NEAR(hit.depth, overlap, 1e-14) << "theta = " << theta << ", side " << side;
      EXPECT_EQ(hit.normal.x(), -side);
      EXPECT_EQ(hit.normal.y(), 0.0);
      EXPECT_NEAR(hit.r.x(), side * w, 1e-14) << "theta = " << theta << ", side " << side;
      EXPECT_NEAR(hit.r.y(), side * ry, 1e-7) << "theta = " << theta << ", side " << side;
      expect_on_rim(hit.r, theta);
      worst_ry = std::max(worst_ry, std::abs(hit.r.y() - side * ry));
      worst_depth = std::max(worst_depth, std::abs(hit.depth - overlap));
    }
  }
  std::printf("box face: max |depth - overlap| %.3g m, max |r_y - closed form| %.3g m\n",
              worst_depth, worst_ry);
  // Just apart (the rim 1e-6 m short of the face): no contact.
  ObstacleContact hit;
  EXPECT_FALSE(
      ellipse_obstacle_contact(right_box, kA, kB, Vec2(0.5 - kA - 1e-6, 1.0), 1.0, 0.0, hit));
}

TEST(EllipseObstacle, ContactStageFindsTheBoxFaceAndNotTheGround) {
  // Through find_contacts on a model: one contact, obstacle 0, same values.
  Scene scene = default_scene(Shape::Ellipse);
  scene.a = kA;
  scene.b = kB;
  scene.obstacles = {make_box_obstacle(1.5, 1.0, 2.0, 2.0)};
  const Model model = make_model(scene);
  ContactSet contacts(model);
  const double theta = 0.7, overlap = 2e-3;
  const double c = std::cos(theta), s = std::sin(theta);
  const double w = std::sqrt(kA * kA * c * c + kB * kB * s * s);
  find_contacts(model, Vec3(0.5 - w + overlap, 1.0, theta), contacts);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_EQ(contacts.ground_count(), 0u);
  const Contact& hit = *contacts.begin();
  EXPECT_EQ(hit.obstacle, 0);
  EXPECT_NEAR(hit.depth, overlap, 1e-14);
  EXPECT_EQ(hit.nx, -1.0);
  EXPECT_EQ(hit.ny, 0.0);
  EXPECT_NEAR(hit.rx, w, 1e-14);
  EXPECT_NEAR(hit.ry, (kA * kA - kB * kB) * s * c / w, 1e-7);
}

// A vertical capsule x = X, y ∈ [0.5, 1.5], radius ρ: its left surface is
// the line x = X − ρ where the rim's extreme point (y within [0.5, 1.5])
// touches, so the same depth, normal and point as a box face, and the same
// tolerances (a capsule's depth is |c − q| − ρ: rounding of coordinates
// ≈ 1 m). Its normal (c − q)/|c − q| has q = (X, q_y) with q_y the
// projection of c_y, equal to it to rounding: n_y to 1e-14.
// A round post (a segment with equal ends) of radius ρ centred at (X, Y)
// under an unturned ellipse centred above it: the nearest rim point to a
// point on the extension of the minor axis is the vertex (0, −b) (the
// ellipse's evolute lies inside it), so depth ρ − (p_y − b − Y) and normal
// (0, 1), to rounding. Along the rim the minimum is flat: φ* is known to
// √(2·δf/f″), f″ = b + a²/D ≥ b (D = 0.047 m the distance from the post's
// centre to the vertex), ≤ 1.4e-7 rad as above, so r_x to 1e-7 m and the
// normal's x to 1e-7/D: 2.2e-6.
TEST(EllipseObstacle, CapsuleSideAndRoundPost) {
  const double radius = 0.05, x_axis = 0.6, overlap = 3e-3;
  const Obstacle capsule = make_segment_obstacle(Vec2(x_axis, 0.5), Vec2(x_axis, 1.5), radius);
  double worst_ry = 0.0;
  for (const double theta : test_angles()) {
    const double c = std::cos(theta), s = std::sin(theta);
    const double w = std::sqrt(kA * kA * c * c + kB * kB * s * s);
    const double ry = (kA * kA - kB * kB) * s * c / w;
    const Vec2 p(x_axis - radius - w + overlap, 1.0);
    ObstacleContact hit;
    ASSERT_TRUE(ellipse_obstacle_contact(capsule, kA, kB, p, c, s, hit)) << "theta = " << theta;
    EXPECT_NEAR(hit.depth, overlap, 1e-14) << "theta = " << theta;
    EXPECT_NEAR(hit.normal.x(), -1.0, 1e-14) << "theta = " << theta;
    EXPECT_NEAR(hit.normal.y(), 0.0, 1e-14) << "theta = " << theta;
    EXPECT_NEAR(hit.r.x(), w, 1e-14) << "theta = " << theta;
    EXPECT_NEAR(hit.r.y(), ry, 1e-7) << "theta = " << theta;
    expect_on_rim(hit.r, theta);
    worst_ry = std::max(worst_ry, std::abs(hit.r.y() - ry));
  }
  const double post_x = 0.2, post_y = 0.3;
  const Obstacle post = make_segment_obstacle(Vec2(post_x, post_y), Vec2(post_x, post_y), radius);
  const Vec2 p(post_x, post_y + radius + kB - overlap);
  ObstacleContact hit;
  ASSERT_TRUE(ellipse_obstacle_contact(post, kA, kB, p, 1.0, 0.0, hit));
  EXPECT_NEAR(hit.depth, overlap, 1e-14);
  EXPECT_NEAR(hit.normal.x(), 0.0, 2.2e-6);
  EXPECT_NEAR(hit.normal.y(), 1.0, 1e-14);
  EXPECT_NEAR(hit.r.x(), 0.0, 1e-7);
  EXPECT_NEAR(hit.r.y(), -kB, 1e-14);
  expect_on_rim(hit.r, 0.0);
  std::printf("capsule side: max |r_y - closed form| %.3g m; post: r_x %.3g m, n_x %.3g\n",
              worst_ry, hit.r.x(), hit.normal.x());
}

// ---------------------------------------------------------------------------
// 6. Scene file: [body] mass, a, b, inertia; inertia 0 (or absent) is a
// uniform plate's m·(a² + b²)/4; b ≤ 0 is out of range under key "body.b".

const char* kEllipseScene = R"(scene = "ellipse"
[body]
mass = 2.0
a = 0.3
b = 0.15
inertia = 0.05
[initial]
y = 0.5
theta = 0.25
)";

TEST(EllipseSceneFile, ReadsSemiAxesAndInertia) {
  const Scene scene = parse_scene(kEllipseScene, "ellipse.toml");
  EXPECT_EQ(scene.shape, Shape::Ellipse);
  EXPECT_EQ(scene.mass, 2.0);
  EXPECT_EQ(scene.a, 0.3);
  EXPECT_EQ(scene.b, 0.15);
  EXPECT_EQ(scene.inertia, 0.05);
  EXPECT_EQ(scene.initial.q.z(), 0.25);
  const RigidBody body = make_body(scene);
  EXPECT_EQ(body.semi_axes, Vec2(0.3, 0.15));
  EXPECT_EQ(body.inertia, 0.05);
  EXPECT_EQ(body.mass, 2.0);
  EXPECT_TRUE(body.rotates);
}

TEST(EllipseSceneFile, InertiaZeroOrAbsentIsTheUniformPlate) {
  std::string text = kEllipseScene;
  text.replace(text.find("inertia = 0.05"), 14, "inertia = 0.0");
  // m·(a² + b²)/4 = 2·(0.09 + 0.0225)/4 = 0.05625 kg·m², to rounding.
  EXPECT_NEAR(make_body(parse_scene(text, "zero.toml")).inertia, 0.05625, 1e-15);
  text.replace(text.find("inertia = 0.0"), 13, "");
  EXPECT_NEAR(make_body(parse_scene(text, "absent.toml")).inertia, 0.05625, 1e-15);
}

TEST(EllipseSceneFile, NonPositiveSemiAxisIsRejected) {
  for (const char* value : {"0.0", "-0.1"}) {
    std::string text = kEllipseScene;
    text.replace(text.find("b = 0.15"), 8, std::string("b = ") + value);
    try {
      parse_scene(text, "bad.toml");
      ADD_FAILURE() << "b = " << value << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("body.b"), std::string::npos) << e.what();
    }
    Scene scene = parse_scene(kEllipseScene, "good.toml");
    scene.b = std::stod(value);
    const auto error = validate(scene);
    ASSERT_TRUE(error.has_value()) << "b = " << value;
    EXPECT_EQ(error->key, "body.b");
  }
  // A missing b is not an error: it takes the default of core/scene.hpp,
  // b = 0.1 m (a [body] key left out keeps its documented default).
  {
    std::string text = kEllipseScene;
    text.replace(text.find("b = 0.15"), 8, "");
    EXPECT_EQ(parse_scene(text, "missing.toml").b, 0.1);
  }
  // A box's key in an ellipse's [body] is an unknown key.
  std::string text = kEllipseScene;
  text.replace(text.find("b = 0.15"), 8, "radius = 0.15");
  EXPECT_THROW(parse_scene(text, "unknown.toml"), InputError);
}

}  // namespace
}  // namespace contact2d
