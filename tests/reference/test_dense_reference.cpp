// The converged reference (core/dense_reference): its force law is the
// core's, it follows closed-form bounces through every kind of event to
// rounding level, it finds a corner's brief graze even when its steps are
// long, and it converges on the four built-in scenes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "benchmarks/oscillator.hpp"
#include "core/run.hpp"
#include "io/scene_file.hpp"
#include "reference/dense_reference.hpp"

namespace contact2d {
namespace {

// ------------------------------------------------------------ force law

// With the mode read from the state, the reference's right-hand side is the
// core's acceleration(): the same expressions in the same order, so the two
// agree to the last bit or within a few ulps if the compiler reorders. The
// tolerance, 1e-12 relative to the largest force term (k·d, c·|v| or m·g
// per unit mass), is 4000 ulps: far below any modelling difference (a
// missing damper term at these states is ≥ 1e-3 relative) and far above
// rounding.
TEST(DenseReference, RightHandSideIsTheCoreForceLaw) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int in_contact = 0;
  for (Shape shape : {Shape::PointMass, Shape::Box, Shape::TShape, Shape::Circle}) {
    for (DampingLaw law : {DampingLaw::Compression, DampingLaw::KelvinVoigt}) {
      Scene scene = default_scene(shape);
      scene.contact.k = 1e5;
      scene.contact.c = 300.0;
      scene.contact.mu = 0.7;
      scene.contact.alpha = 50.0;
      scene.contact.mu_roll = 0.02;
      scene.contact.damping = law;
      Model model = make_model(scene);
      model.applied = Vec3(1.5, -2.0, 0.3);
      for (int i = 0; i < 2000; ++i) {
        // Heights within ±0.3 m of the ground put some points inside.
        const Vec3 q(unit(rng), 0.3 * unit(rng), shape == Shape::PointMass ? 0.0 : 3.0 * unit(rng));
        const Vec3 v(2.0 * unit(rng), 2.0 * unit(rng),
                     shape == Shape::PointMass ? 0.0 : 10.0 * unit(rng));
        in_contact += max_penetration(model, q) > 0.0;
        const Vec3 a_core = acceleration(model, q, v);
        const Vec3 a_ref = dense_reference_acceleration(model, q, v);
        // Size of the largest single force term per unit mass (spring at
        // 0.3 m, damper at |v_c| ≤ 2 + 10·0.36 m/s, weight), and its torque
        // per unit inertia for the angular component.
        const double linear = (1e5 * 0.3 + 300.0 * 6.0 + 10.0) / model.body.mass;
        const double angular =
            model.body.inertia > 0.0
                ? linear * model.body.mass * body_extent(model.body) / model.body.inertia
                : 0.0;
        for (int j = 0; j < 3; ++j) {
          EXPECT_NEAR(a_ref[j], a_core[j], 1e-12 * (j == 2 ? angular : linear))
              << shape_name(shape) << " component " << j << " at q = " << q.transpose()
              << ", v = " << v.transpose();
        }
      }
    }
  }
  // The random states must exercise the contact branches, not just free fall.
  EXPECT_GT(in_contact, 4000);
}

// ----------------------------------------------------- closed-form bounce

// A point mass (m = 1, k = 1e4, μ = 0) dropped from rest, its contact point
// 0.3 m above the ground. Height z of the contact point, velocity w = ż.
// Every phase is linear with constant coefficients and has a closed form:
//   flight:      z'' = −g
//   contact:     z'' = −g − (k/m)·z − (c_on/m)·z'   (c_on = c or 0 by mode)
// Compression law: the damper acts while w < 0; it switches off at the
// deepest point (w = 0) and the spring alone returns the body to z = 0.
// Kelvin–Voigt: the force −k·z − c·w is applied while positive; when it
// reaches 0 (before z = 0, since w > 0) the point floats inside the ground
// (free flight) until z = 0.
// Phase ends are found by bracketing (grid of 1e-6 s) and bisection to
// rounding level on the closed forms, so the analytic event times are exact
// to ~1e-16 s.
struct Phase {
  double k = 0.0, c = 0.0;  // per unit mass
};

struct Piece {
  double t0 = 0.0, t1 = 0.0;
  double z0 = 0.0, w0 = 0.0;
  Phase phase;
};

constexpr double kG = 9.81;

// Closed form of z'' = −g − k·z − c·z' from (z0, w0) after time s
// (benchmarks/oscillator.hpp; underdamped in this test).
void evolve(const Phase& p, double z0, double w0, double s, double& z, double& w) {
  const benchmarks::OscillatorState out = benchmarks::damped_oscillator(kG, p.k, p.c, z0, w0, s);
  z = out.z;
  w = out.w;
}

// First s > 0 where f(z, w) changes sign from its sign just after s = 0.
double phase_end(const Phase& p, double z0, double w0,
                 const std::function<double(double, double)>& f) {
  auto value = [&](double s) {
    double z, w;
    evolve(p, z0, w0, s, z, w);
    return f(z, w);
  };
  const double h = 1e-6;
  const double sign0 = value(h) > 0.0 ? 1.0 : -1.0;
  double a = h, b = h;
  // A phase that has not ended after 1 s is taken to last (the point has
  // settled in contact); every phase these tests locate is under 0.1 s.
  while (value(b) * sign0 > 0.0 && b < 1.0) {
    a = b;
    b += h;
  }
  for (int i = 0; i < 200 && b - a > 1e-17; ++i) {
    const double m = 0.5 * (a + b);
    (value(m) * sign0 > 0.0 ? a : b) = m;
  }
  return 0.5 * (a + b);
}

std::vector<Piece> analytic_bounces(DampingLaw law, double c, double duration) {
  const double k = 1e4;
  std::vector<Piece> pieces;
  double t = 0.0, z = 0.3, w = 0.0;
  auto push = [&](Phase p, double s) {
    pieces.push_back({t, t + s, z, w, p});
    double z1, w1;
    evolve(p, z, w, s, z1, w1);
    t += s;
    z = z1;
    w = w1;
  };
  while (t < duration) {
    // Flight down to the ground: z = 0.
    const double s_fall = benchmarks::fall_time(kG, z, w);
    push(Phase{}, s_fall);
    if (law == DampingLaw::Compression) {
      const Phase damped{k, c}, spring{k, 0.0};
      push(damped, phase_end(damped, z, w, [](double, double w) { return w; }));
      push(spring, phase_end(spring, z, w, [](double z, double) { return z; }));
    } else {
      const Phase damped{k, c};
      push(damped, phase_end(damped, z, w, [&](double z, double w) { return -k * z - c * w; }));
      push(Phase{}, phase_end(Phase{}, z, w, [](double z, double) { return z; }));
    }
    // After the exit the flight formula above takes over again.
  }
  return pieces;
}

double analytic_height(const std::vector<Piece>& pieces, double t) {
  for (const Piece& p : pieces) {
    if (t <= p.t1) {
      double z, w;
      evolve(p.phase, p.z0, p.w0, t - p.t0, z, w);
      return z;
    }
  }
  return NAN;
}

double bounce_error(DampingLaw law, double c, double tol, long long* events = nullptr) {
  const double duration = 1.5;
  Scene scene = default_scene(Shape::PointMass);
  scene.half_height = 0.05;
  scene.contact.k = 1e4;
  scene.contact.c = c;
  scene.contact.mu = 0.0;
  scene.contact.damping = law;
  scene.initial.q = Vec3(0.0, 0.35, 0.0);
  scene.sim.duration = duration;
  const DenseTrajectory ref = converged_reference(scene, tol);
  EXPECT_TRUE(ref.ok()) << ref.failure();
  if (events) *events = ref.stats().events;
  const std::vector<Piece> pieces = analytic_bounces(law, c, duration);
  double worst = 0.0;
  for (int i = 0; i <= 15000; ++i) {
    const double t = 1e-4 * i;
    worst = std::max(worst, std::abs(ref.at(t).q.y() - 0.05 - analytic_height(pieces, t)));
  }
  return worst;
}

// Tolerance 1e-9 m. Measured at tol = 1e-12: 1.3e-11 m (compression) and
// 8.6e-12 m (Kelvin–Voigt). An event located only to within its step (h ~ 1e-3 s
// in flight, ~1e-4 s in contact) would err by (c/m)·|w|·δt·T ≈ 20·2.4·1e-4·1 ≈
// 5e-3 m at the entry jump alone; a damper switch missed by δt errs by
// (c/m)·|a|·δt²: even δt = 1e-6 s gives 1e-7 m. So 1e-9 m leaves 80× margin
// over the measurement and still catches any event handled to worse than a
// microsecond. (Checked by breaking the event location: with each crossing
// put at the end of its step instead of located, this error is 0.31 m.)
TEST(DenseReference, FollowsClosedFormBouncesCompressionLaw) {
  long long events = 0;
  const double err = bounce_error(DampingLaw::Compression, 20.0, 1e-12, &events);
  EXPECT_LT(err, 1e-9);
  // 1.5 s from 0.3 m: three contacts, each entry, damper off, exit.
  EXPECT_GE(events, 9);
}

TEST(DenseReference, FollowsClosedFormBouncesKelvinVoigt) {
  long long events = 0;
  const double err = bounce_error(DampingLaw::KelvinVoigt, 20.0, 1e-12, &events);
  EXPECT_LT(err, 1e-9);
  EXPECT_GE(events, 9);  // entry, force reaches zero, exit: three times
}

// The error follows the tolerance: each 100× tighter tolerance gains at least
// 10× (DOPRI5 with a controller on the local error per step gives a global
// error roughly proportional to the tolerance; measured 97× and 86× per
// 100×: 8.2e-6, 8.4e-8, 9.7e-10 m at 1e-6, 1e-8, 1e-10).
// If the events cost the method its order, the error would stall at the
// O(h) event error instead.
TEST(DenseReference, BounceErrorFollowsTolerance) {
  const double e6 = bounce_error(DampingLaw::Compression, 20.0, 1e-6);
  const double e8 = bounce_error(DampingLaw::Compression, 20.0, 1e-8);
  const double e10 = bounce_error(DampingLaw::Compression, 20.0, 1e-10);
  EXPECT_LT(e8, e6 / 10.0);
  EXPECT_LT(e10, e8 / 10.0);
}

// -------------------------------------------------------------- chatter

// The Kelvin-Voigt bounce of FollowsClosedFormBouncesKelvinVoigt run for
// 20 s, so that the default h_max (duration/100 = 0.2 s) lets the steps grow
// longer than the late, small bounces. At the exit at t = 1.66128 s (rising
// at 0.047 m/s) the step redone up to the located crossing stops one ulp
// short of the surface (c_y = -2^-57 m), and the next step, 17 ms long,
// contains the whole 9.5 ms flight: the contact function is on its wrong
// side at both of its ends in the free mode, and (rounding) at its start in
// the contact mode too. The modes flipped back and forth at that instant;
// a rule that gives up after 8 such zero-length flips accepted the step in the
// free mode with the point 2.5 mm inside the ground at its end, missing the
// re-entry at t = 1.67077 s: the point fell on without any contact force and
// the trajectory left the closed form by 2.4 mm (measured with that rule:
// it fails this test with 2.39e-3 m at t = 1.7434 s). The rate at the start says the point is
// leaving the ground, so the free mode is right and the return within the step is a crossing to
// locate. Tolerance: 1e-9 m as in the closed-form bounce tests above (their derivation applies
// unchanged; the 20 s run at tol 1e-12 measures 8.6e-12 m over [0, 1.75] s), six orders of
// magnitude below the 2.4e-3 m miss.
TEST(DenseReference, ChatteringExitInsideALongStepIsLocatedNotSkipped) {
  Scene scene = default_scene(Shape::PointMass);
  scene.half_height = 0.05;
  scene.contact.k = 1e4;
  scene.contact.c = 20.0;
  scene.contact.mu = 0.5;
  scene.contact.damping = DampingLaw::KelvinVoigt;
  scene.initial.q = Vec3(0.0, 0.35, 0.0);
  scene.sim.duration = 20.0;
  const DenseTrajectory ref = converged_reference(scene, 1e-12);
  ASSERT_TRUE(ref.ok()) << ref.failure();
  // The situation is reached: the exit and its 8 zero-length flips are 9
  // mode switches recorded at one instant. (Depends on rounding; if a
  // compiler change removes the chatter, this says so instead of the test
  // passing without driving the flip limit.)
  const std::vector<double>& times = ref.event_times();
  size_t repeat = 1, most = 1;
  for (size_t i = 1; i < times.size(); ++i) {
    repeat = times[i] == times[i - 1] ? repeat + 1 : 1;
    most = std::max(most, repeat);
  }
  EXPECT_GE(most, 9u) << "the zero-length flip limit is no longer reached";
  const std::vector<Piece> pieces = analytic_bounces(DampingLaw::KelvinVoigt, 20.0, 1.75);
  double worst = 0.0, worst_t = 0.0;
  for (int i = 0; i <= 17500; ++i) {
    const double t = 1e-4 * i;
    const double err = std::abs(ref.at(t).q.y() - 0.05 - analytic_height(pieces, t));
    if (err > worst) {
      worst = err;
      worst_t = t;
    }
  }
  EXPECT_LT(worst, 1e-9) << "at t = " << worst_t;
}

// A box sliding at 0.3 m/s under the soft cone (μ = 0.3, k = 1e5 N/m, c =
// 632 N·s/m, impratio 3.95): the push c·μ·|v_t| at zero depth lifts a
// corner faster than it falls, so at 0.0858 s a corner has no consistent
// mode on the surface (the fixed-step reference hops there; docs/physics.md
// counts the hops of the same box at 1.5 m/s at three steps). The converged
// solution must refuse, and its reason must name the soft cone's push with
// its size: c·μ·|v_t|/(1 + μ²/impratio), |v_t| ≈ 0.3 − μ·g·t = 0.0475 m/s →
// 8.8 N. (At 1.5 m/s the same happens at 0.42 s, after 5 times the work:
// 35 s under the sanitizers.)
TEST(DenseReference, NamesTheSoftConesPushWhenAContactChatters) {
  const Scene scene = parse_scene(
      "scene = \"box\"\n[body]\nmass = 1.0\nwidth = 0.4\nheight = 0.2\n"
      "[contact]\nk = 1e5\nc = 632.455532\nmu = 0.3\ndamping = \"kelvin_voigt\"\n"
      "friction_law = \"soft_cone\"\ncone_ratio = 3.9528470754209484\n"
      "[initial]\ny = 0.099951\nvx = 0.3\n"
      "[sim]\ndt = 1e-4\nduration = 0.2\n",
      "soft-cone slide");
  const DenseTrajectory ref = converged_reference(scene, 1e-12);
  ASSERT_FALSE(ref.ok()) << "the soft cone's chatter no longer stops the converged solution";
  std::printf("%s\n", ref.failure().c_str());
  EXPECT_NE(ref.failure().find("chattering"), std::string::npos);
  EXPECT_NE(ref.failure().find("under soft_cone"), std::string::npos);
  const size_t at = ref.failure().find("impratio) = ");
  ASSERT_NE(at, std::string::npos) << ref.failure();
  const double push = std::stod(ref.failure().substr(at + 12));
  const double t = std::stod(ref.failure().substr(ref.failure().find("t = ") + 4));
  // The box decelerates at μ·g while it slides (the push adds to the
  // normal force only while a corner touches, ~10 % of the time at Δt =
  // 1e-4 s, and the hops change |v_t| by little): within 2 % of the estimate.
  const double v_t = 0.3 - 0.3 * 9.81 * t;
  EXPECT_NEAR(push, 632.455532 * 0.3 * v_t / (1.0 + 0.09 / 3.9528470754209484), 0.02 * push);
}

// ------------------------------------------------------------- grazing

// A box (0.4 × 0.2 m) without gravity turning at 2 rad/s, centre at a height
// 1e-4 m below its half-diagonal: each corner dips 1e-4 m into the ground for
// about 30 ms as it sweeps past the bottom, with no force before. In free
// rotation the right-hand side is exactly zero except for the rotation, so
// the step-size controller would take the longest step allowed; with steps
// of 0.25 s (half a radian) the corner is above the ground at both ends of
// the step that contains the dip. The interior-extremum test must find it.
// Criterion: the long-step run matches a run capped at 1 ms to 1e-8 m
// (both are tol = 1e-12 runs of the same ODE; measured difference 3e-13 m),
// and the contact visibly acted (vertical speed 0.019 m/s afterwards,
// against exactly 0 without contact). With the interior-extremum test
// disabled, the long-step run sees no event and misses by 9e-3 m.
TEST(DenseReference, FindsABriefGrazeInsideALongStep) {
  Scene scene = default_scene(Shape::Box);
  scene.width = 0.4;
  scene.height = 0.2;
  scene.contact.k = 1e5;
  scene.contact.c = 0.0;
  scene.contact.mu = 0.0;
  scene.sim.gravity = 0.0;
  const double half_diagonal = std::hypot(0.2, 0.1);
  const Model model = make_model(scene);
  State s0;
  s0.q = Vec3(0.0, half_diagonal - 1e-4, 0.0);
  s0.v = Vec3(0.0, 0.0, 2.0);
  DenseOptions long_steps;
  long_steps.h_max = 0.25;
  DenseOptions short_steps;
  short_steps.h_max = 1e-3;
  const DenseTrajectory a = integrate_dense(model, s0, 1.0, long_steps);
  const DenseTrajectory b = integrate_dense(model, s0, 1.0, short_steps);
  ASSERT_TRUE(a.ok()) << a.failure();
  ASSERT_TRUE(b.ok()) << b.failure();
  EXPECT_GT(a.stats().events, 0);
  const State ea = a.at(1.0), eb = b.at(1.0);
  EXPECT_GT(std::abs(eb.v.y()), 1e-3);
  EXPECT_LT((ea.q - eb.q).norm(), 1e-8);
  EXPECT_LT((ea.v - eb.v).norm(), 1e-8);
}

// --------------------------------------------------- built-in scenes

// Self-consistency on the shipped scenes: the reference at tol 1e-12
// against tol 1e-14, at the scene's output times. The issue asks for a
// converged reference good to about 1e-9 m; measured 1e-14 (circle),
// 1.5e-12 (box), 1.3e-12 (T), 1.8e-11 m (point mass), so 1e-9 m is the
// requirement with ≥ 50× margin. And it must converge: tol 1e-8 errs more
// than tol 1e-12 (measured 1.9e-11..2e-6 m), which fails if the tolerance
// stopped mattering.
class BuiltInScene : public ::testing::TestWithParam<const char*> {};

TEST_P(BuiltInScene, ReferenceIsSelfConsistentTo1e9) {
  const Scene scene = load_scene(std::string(CONTACT2D_SCENES_DIR) + "/" + GetParam() + ".toml");
  const DenseTrajectory truth = converged_reference(scene, 1e-14);
  const DenseTrajectory ref = converged_reference(scene, 1e-12);
  const DenseTrajectory loose = converged_reference(scene, 1e-8);
  ASSERT_TRUE(truth.ok() && ref.ok() && loose.ok());
  double err = 0.0, err_loose = 0.0;
  for (double t = 0.0; t <= scene.sim.duration; t += 1e-3) {
    err = std::max(err, (ref.at(t).q.head<2>() - truth.at(t).q.head<2>()).norm());
    err_loose = std::max(err_loose, (loose.at(t).q.head<2>() - truth.at(t).q.head<2>()).norm());
  }
  EXPECT_LT(err, 1e-9);
  EXPECT_GT(err_loose, err);
}

INSTANTIATE_TEST_SUITE_P(Scenes, BuiltInScene,
                         ::testing::Values("point_mass", "box", "tshape", "circle"));

// A scene the method cannot finish within its step budget says so instead
// of returning a partial trajectory as if it were whole.
TEST(DenseReference, ReportsAnExhaustedStepBudget) {
  Scene scene = default_scene(Shape::PointMass);
  const Model model = make_model(scene);
  DenseOptions options;
  options.max_steps = 10;
  const DenseTrajectory ref = integrate_dense(model, initial_state(scene), 2.0, options);
  EXPECT_FALSE(ref.ok());
  EXPECT_NE(ref.failure().find("steps"), std::string::npos);
  EXPECT_LT(ref.t_end(), 2.0);
}

// Obstacles have switching functions the reference does not locate: it
// refuses them rather than return a trajectory that ignores them.
TEST(DenseReference, RefusesObstacles) {
  Scene scene = default_scene(Shape::Circle);
  scene.obstacles.push_back(make_box_obstacle(1.0, 0.5, 0.2, 1.0));
  const DenseTrajectory ref = converged_reference(scene, 1e-10);
  EXPECT_FALSE(ref.ok());
  EXPECT_NE(ref.failure().find("obstacles"), std::string::npos);
}

}  // namespace
}  // namespace contact2d
