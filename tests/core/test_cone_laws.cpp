// The two cone friction laws (core/contact.hpp) against their closed forms.
//
// soft_cone, one ground contact, slip v_t, no rolling. With F* = k·d − c·v_n,
// b = ρ·c:
//   stick  b·|v_t| ≤ μ·F*:  Fn = F*, Ft = −b·v_t
//   slide  Fn = (F* + μ·c·|v_t|)/(1 + μ²/ρ), Ft = −μ·Fn·sgn v_t
// A point mass kept sliding at a constant speed v by an applied force equal
// to the friction (so that nothing else changes) rests where Fn = m·g:
//   k·p = m·g·(1 + μ²/ρ) − μ·c·v,   p/p₀ = 1 + μ²/ρ − μ·c·v/(m·g)  (p₀ = m·g/k),
// and leaves the ground (p = 0) above v = m·g·(1 + μ²/ρ)/(μ·c). With μ = 0.6,
// c = 200, ρ = 50, m = 1: 0.885, 0.640, 0.396 of p₀ at 0.01, 0.03, 0.05 m/s,
// airborne above 0.0823 m/s.
#include <gtest/gtest.h>

#include <cmath>

#include "benchmarks/rest.hpp"
#include "core/contact.hpp"
#include "core/contacts.hpp"
#include "core/divergence.hpp"
#include "core/dynamics.hpp"
#include "core/integrators.hpp"
#include "core/run.hpp"
#include "core/scene.hpp"

namespace contact2d {
namespace {

ContactParams cone(FrictionLaw law) {
  ContactParams p;
  p.k = 1e4;
  p.c = 200.0;
  p.mu = 0.6;
  p.damping = DampingLaw::KelvinVoigt;
  p.friction = law;
  p.cone_ratio = 50.0;
  return p;
}

TEST(SoftCone, StickIsViscousAndSlideCarriesThePush) {
  const ContactParams p = cone(FrictionLaw::SoftCone);
  const double aim = 10.0;  // F* = 10 N
  // Inside the cone: |b·v_t| = 1e4·1e-4 = 1 N ≤ μ·F* = 6 N.
  const ConeForce stick = soft_cone_force(p, aim, 1e-4, 0.0);
  EXPECT_DOUBLE_EQ(stick.fn, aim);
  EXPECT_DOUBLE_EQ(stick.ft, -p.cone_ratio * p.c * 1e-4);
  // On the cone, v_t = −0.02: push μ·c·|v_t| = 2.4 N, divisor 1 + 0.36/50.
  const ConeForce slide = soft_cone_force(p, aim, -0.02, 0.0);
  const double fn = (aim + p.mu * p.c * 0.02) / (1.0 + p.mu * p.mu / p.cone_ratio);
  EXPECT_NEAR(slide.fn, fn, 1e-14 * fn);
  EXPECT_NEAR(slide.ft, p.mu * fn, 1e-14 * fn);
  // A separating contact kept on by the push: F* = −1 N, μ·c·|v_t| = 12 N.
  const ConeForce pushed = soft_cone_force(p, -1.0, 0.1, 0.0);
  EXPECT_GT(pushed.fn, 0.0);
  // … and none once F* + μ·c·|v_t| ≤ 0.
  const ConeForce none = soft_cone_force(p, -13.0, 0.1, 0.0);
  EXPECT_EQ(none.fn, 0.0);
  EXPECT_EQ(none.ft, 0.0);
}

// The boundary b·s = μ²·F* is where the two branches meet: the force is
// continuous there (both give Fn = F*, Ft = μ·F*), for sliding and rolling
// alike. One ulp either side of the boundary the forces differ by rounding.
TEST(SoftCone, IsContinuousAcrossStickAndSlide) {
  ContactParams p = cone(FrictionLaw::SoftCone);
  p.mu_roll = 0.01;
  const double aim = 7.0;
  for (double spin : {0.0, 0.02}) {
    // s = √((μ·v_t)² + (μ_roll·ω)²) = μ²·F*/b at the boundary.
    const double s = p.mu * p.mu * aim / (p.cone_ratio * p.c);
    const double rolled = p.mu_roll * spin;
    ASSERT_LT(rolled, s);
    const double v_t = std::sqrt(s * s - rolled * rolled) / p.mu;
    const ConeForce below = soft_cone_force(p, aim, std::nextafter(v_t, 0.0), spin);
    const ConeForce above = soft_cone_force(p, aim, std::nextafter(v_t, 1.0), spin);
    EXPECT_NEAR(below.fn, above.fn, 1e-12 * aim) << "spin " << spin;
    EXPECT_NEAR(below.ft, above.ft, 1e-12 * aim) << "spin " << spin;
    EXPECT_NEAR(below.roll, above.roll, 1e-12 * aim) << "spin " << spin;
  }
}

// Sliding and rolling share one budget on the cone:
// (Ft/μ)² + (τ/μ_roll)² = Fn², whatever the split of the slip.
TEST(ViscousCone, SharesOneBudgetBetweenSlidingAndRolling) {
  ContactParams p = cone(FrictionLaw::ViscousCone);
  p.mu_roll = 0.01;
  const double fn = 9.81;
  for (double spin : {-20.0, 1.0, 50.0}) {
    const ConeForce f = viscous_cone_force(p, fn, 0.3, spin);
    EXPECT_DOUBLE_EQ(f.fn, fn);  // the normal law is untouched
    const double budget = std::hypot(f.ft / p.mu, f.roll / p.mu_roll);
    EXPECT_NEAR(budget, fn, 1e-13 * fn) << "spin " << spin;
  }
  // Inside the cone: viscous, slope b for sliding and b·(μ_roll/μ)² for rolling.
  const ConeForce in = viscous_cone_force(p, fn, 1e-5, 1e-3);
  EXPECT_DOUBLE_EQ(in.ft, -p.cone_ratio * p.c * 1e-5);
  EXPECT_NEAR(in.roll, -p.cone_ratio * p.c * (p.mu_roll / p.mu) * (p.mu_roll / p.mu) * 1e-3, 1e-18);
}

// The pipeline: a point mass held at a constant slip v by an applied force
// equal to μ·m·g (the friction once it rests), run to rest with
// semi-implicit Euler. At the fixed point of the step the force balance is
// exact (v' = v, q' = q + v·Δt with v_y = 0), so the depth is the closed form
// to rounding of the sums: the step's own error plays no part.
TEST(SoftCone, ASlidingPointMassSinksLessAsThePushGrows) {
  for (const auto& [v, fraction] :
       {std::pair{0.01, 0.885}, std::pair{0.03, 0.640}, std::pair{0.05, 0.396}}) {
    Scene scene = default_scene(Shape::PointMass);
    scene.contact = cone(FrictionLaw::SoftCone);
    scene.mass = 1.0;
    scene.half_height = 0.05;
    const double p0 = benchmarks::rest_depth(scene.mass, scene.sim.gravity, scene.contact.k, 1);
    const double mu2 = scene.contact.mu * scene.contact.mu;
    const double expected =
        1.0 + mu2 / scene.contact.cone_ratio -
        scene.contact.mu * scene.contact.c * v / (scene.mass * scene.sim.gravity);
    EXPECT_NEAR(expected, fraction, 5e-4);  // the numbers of the comment above
    Model model = make_model(scene);
    // Friction at the steady state is μ·Fn = μ·m·g: balance it.
    model.applied = Vec3(scene.contact.mu * scene.mass * scene.sim.gravity, 0.0, 0.0);
    State s;
    s.q = Vec3(0.0, scene.half_height - expected * p0, 0.0);
    s.v = Vec3(v, 0.0, 0.0);
    StepWorkspace ws(model);
    find_contacts(model, s.q, ws.contacts);
    for (int i = 0; i < 20000; ++i) step(model, Integrator::SemiImplicitEuler, 1e-4, s, ws);
    const double depth = scene.half_height - s.q.y();
    EXPECT_NEAR(depth / p0, expected, 1e-9) << "v = " << v;
    EXPECT_NEAR(s.v.x(), v, 1e-12) << "v = " << v;
  }
}

TEST(SoftCone, APointMassLeavesTheGroundAboveTheLiftOffSpeed) {
  Scene scene = default_scene(Shape::PointMass);
  scene.contact = cone(FrictionLaw::SoftCone);
  const double g = scene.sim.gravity;
  const double lift_off = scene.mass * g * (1.0 + 0.36 / 50.0) / (0.6 * 200.0);
  EXPECT_NEAR(lift_off, 0.0823, 5e-5);
  Model model = make_model(scene);
  ContactSet contacts(model);
  // A contact just touching (d → 0⁺, v_n = 0): Fn = μ·c·v/(1 + μ²/ρ), above
  // m·g beyond the lift-off speed.
  find_contacts(model, Vec3(0.0, scene.half_height - 1e-12, 0.0), contacts);
  ASSERT_EQ(contacts.size(), 1u);
  const Vec3 slow = acceleration(model, contacts, Vec3(0.99 * lift_off, 0.0, 0.0));
  const Vec3 fast = acceleration(model, contacts, Vec3(1.01 * lift_off, 0.0, 0.0));
  EXPECT_LT(slow.y(), 0.0);
  EXPECT_GT(fast.y(), 0.0);
}

// On the ground the soft cone acts halfway into the penetration, where
// MuJoCo puts the contact point: a spinning box corner at depth d slips at
// v_x − ω·(r_y + d/2) and the friction's lever is r_y + d/2.
TEST(SoftCone, ActsHalfwayIntoThePenetration) {
  Scene scene = default_scene(Shape::Box);
  scene.contact = cone(FrictionLaw::SoftCone);
  const Model model = make_model(scene);
  ContactSet contacts(model);
  const double h = 0.5 * scene.height, d = 2e-3;
  find_contacts(model, Vec3(0.0, h - d, 0.0), contacts);  // both bottom corners at depth d
  ASSERT_EQ(contacts.size(), 2u);
  const Vec3 v(0.4, 0.0, 3.0);
  const Vec3 a = acceleration(model, contacts, v);
  double fx = 0.0, fy = -scene.mass * scene.sim.gravity, torque = 0.0;
  for (const Contact& c : contacts) {
    const double ry = c.ry + 0.5 * d;
    const ConeForce f = soft_cone_force(
        model.contact, model.contact.k * d - model.contact.c * (v.y() + v.z() * c.rx),
        v.x() - v.z() * ry, 0.0);
    fx += f.ft;
    fy += f.fn;
    torque += c.rx * f.fn - ry * f.ft;
  }
  EXPECT_NEAR(a.x(), fx / scene.mass, 1e-12);
  EXPECT_NEAR(a.y(), fy / scene.mass, 1e-12);
  EXPECT_NEAR(a.z(), torque / make_body(scene).inertia, 1e-10);
}

// Implicit Euler under a cone law: the Newton solve (forward-difference
// Jacobian) converges to the implicit equation, and a box sliding to rest
// ends where semi-implicit Euler at a ten times smaller step does (first
// order: both within O(Δt) of the solution). The soft cone with c = 5: its
// push μ·c·v0 = 6 N stays below m·g, so the box never lifts off (a lift-off
// under the push makes the force jump at the surface while the point
// separates, where the implicit equation has no solution: the next test).
TEST(ConeLaws, ImplicitEulerRunsEveryConeLaw) {
  for (FrictionLaw law : {FrictionLaw::ViscousCone, FrictionLaw::SoftCone}) {
    Scene scene = default_scene(Shape::Box);
    scene.contact = cone(law);
    scene.contact.c = law == FrictionLaw::SoftCone ? 5.0 : 50.0;
    scene.initial.q = Vec3(0.0, 0.0995, 0.0);
    scene.initial.v = Vec3(2.0, 0.0, 0.0);
    scene.sim.duration = 1.0;
    Scene fine = scene;
    scene.sim.integrator = Integrator::ImplicitEuler;
    fine.sim.dt = 1e-5;
    const Trajectory a = simulate(scene);
    const Trajectory b = simulate(fine);
    ASSERT_FALSE(a.divergence);
    ASSERT_FALSE(b.divergence);
    // v0²/(2μg) = 0.34 m; the two first-order runs end within a millimetre
    // (their O(Δt) terms: ~1e-4 m per 1e-4 s of stopping-time error).
    EXPECT_NEAR(a.samples.back().state.q.x(), b.samples.back().state.q.x(), 1e-3)
        << friction_law_name(law);
    // Without the push the slide is Coulomb's, v0²/(2μg), plus the viscous
    // tail's m·g·μ·m²/(2·b²)-order term (1e-9 m here) and the pitch
    // (test_friction.cpp: ~1e-6 m at k = 1e4): within 1 mm.
    if (law == FrictionLaw::ViscousCone) {
      EXPECT_NEAR(b.samples.back().state.q.x(), 4.0 / (2.0 * 0.6 * 9.81), 1e-3);
    }
  }
}

// A box lifted off by the push (μ·c·v0 = 60 N > m·g) under implicit Euler:
// the run fails, and says why, instead of integrating a step that has no
// solution.
TEST(ConeLaws, ImplicitEulerSaysWhyThePushDefeatsIt) {
  Scene scene = default_scene(Shape::Box);
  scene.contact = cone(FrictionLaw::SoftCone);
  scene.contact.c = 50.0;
  scene.initial.q = Vec3(0.0, 0.0995, 0.0);
  scene.initial.v = Vec3(2.0, 0.0, 0.0);
  scene.sim.duration = 1.0;
  scene.sim.integrator = Integrator::ImplicitEuler;
  const Trajectory a = simulate(scene);
  ASSERT_TRUE(a.divergence);
  const std::string why = describe(*a.divergence, scene);
  EXPECT_NE(why.find("soft_cone"), std::string::npos) << why;
  EXPECT_NE(why.find("semi_implicit_euler"), std::string::npos) << why;
}

}  // namespace
}  // namespace contact2d
