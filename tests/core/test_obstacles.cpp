// Static obstacles (core/obstacles.hpp): the ground's contact law along the
// obstacle's normal. Each test has a closed form or an exact equivalence with
// the ground, and its tolerance says where it comes from.
#include <gtest/gtest.h>

#include <cmath>

#include "benchmarks/impact.hpp"
#include "benchmarks/rest.hpp"
#include "core/divergence.hpp"
#include "core/integrators.hpp"
#include "core/obstacles.hpp"
#include "core/run.hpp"
#include "core/scene.hpp"
#include "support/support.hpp"

namespace contact2d {
namespace {

// ---------------------------------------------------------------------------
// Resting on an obstacle: the spring carries the weight, d = m·g/k, exactly
// as on the ground. At rest a = 0 is a fixed point of every integrator, so
// the only error is the e^(−ω·t) transient after 2 s (ω = 100 rad/s, < 1e-80)
// plus rounding: tolerance 1e-9·d, as in tests/core/test_static.cpp.

class RestOnObstacle : public ::testing::TestWithParam<Integrator> {};

TEST_P(RestOnObstacle, BallOnBoxSinksByWeightOverStiffness) {
  Scene scene = test::resting_scene(Shape::Circle, GetParam());
  scene.contact.mu = 0.5;
  scene.contact.mu_roll = 0.01;
  const double top = 0.5;
  scene.obstacles = {
      make_box_obstacle(0.0, 0.5 * top, 1.0, top)};             // a table standing on the ground
  scene.initial.q = Vec3(0.1, top + scene.radius + 0.02, 0.0);  // dropped from 2 cm
  const double d = benchmarks::rest_depth(scene.mass, scene.sim.gravity, scene.contact.k, 1);
  const State s = test::final_state(scene);
  EXPECT_NEAR(top + scene.radius - s.q.y(), d, 1e-9 * d);
  EXPECT_NEAR(s.q.x(), 0.1, 1e-12) << "a vertical drop on a flat top has no sideways force";
}

TEST_P(RestOnObstacle, BallOnSegmentSinksByWeightOverStiffness) {
  Scene scene = test::resting_scene(Shape::Circle, GetParam());
  const double radius = 0.05, height = 0.4;  // a horizontal bar of thickness 0.1 at y = 0.4
  scene.obstacles = {make_segment_obstacle(Vec2(-1.0, height), Vec2(1.0, height), radius)};
  scene.initial.q = Vec3(0.3, height + radius + scene.radius, 0.0);
  const double d = benchmarks::rest_depth(scene.mass, scene.sim.gravity, scene.contact.k, 1);
  const State s = test::final_state(scene);
  EXPECT_NEAR(height + radius + scene.radius - s.q.y(), d, 1e-9 * d);
}

TEST_P(RestOnObstacle, FlatBoxOnBoxSinksByHalfTheWeightPerCorner) {
  // A body with contact points (not a disc): its two bottom corners sit on
  // the obstacle's top face.
  Scene scene = test::resting_scene(Shape::Box, GetParam());
  const double top = 0.3;
  scene.obstacles = {make_box_obstacle(0.0, 0.0, 2.0, 2.0 * top)};
  scene.initial.q = Vec3(0.0, top + 0.5 * scene.height, 0.0);
  const double d = benchmarks::rest_depth(scene.mass, scene.sim.gravity, scene.contact.k, 2);
  const State s = test::final_state(scene);
  EXPECT_NEAR(top + 0.5 * scene.height - s.q.y(), d, 1e-9 * d);
  EXPECT_NEAR(s.q.z(), 0.0, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(AllIntegrators, RestOnObstacle, ::testing::ValuesIn(kAllIntegrators),
                         [](const auto& info) { return std::string(integrator_name(info.param)); });

// ---------------------------------------------------------------------------
// Rebound from a wall, without gravity: the same closed forms as the ground
// (tests/core/test_rebound.cpp derives them):
//   compression  e = exp(−ζ·φ/√(1−ζ²)),  φ = atan(√(1−ζ²)/ζ)
//   Kelvin–Voigt e = e^(−ζω t_e)·|cos(ω_d t_e) − ζ/√(1−ζ²)·sin(ω_d t_e)|,
//                ω_d·t_e = π − atan2(2ζ√(1−ζ²), 1−2ζ²)
// The ball starts 1e-12 m into the wall so the first evaluation sees the
// contact (changes e by ~ω·1e-12/v0 = 1e-10). RK4 at ω·Δt = 1e-3: the
// damper's kink inside one step gives the 2·(ω·Δt)²·ζ = 2e-6·ζ tolerance of
// tests/core/test_rebound.cpp.

Scene wall_scene(DampingLaw law, double zeta) {
  Scene scene = test::impact_scene(Shape::Circle, law, zeta);
  scene.radius = 0.1;
  return scene;
}

struct ReboundCase {
  DampingLaw law;
  double zeta;
};

class WallRebound : public ::testing::TestWithParam<ReboundCase> {};

TEST_P(WallRebound, BallOffABoxWallMatchesClosedForm) {
  const auto [law, zeta] = GetParam();
  Scene scene = wall_scene(law, zeta);
  const double wall = 0.5, v0 = 1.0;
  scene.obstacles = {make_box_obstacle(wall + 0.5, 1.0, 1.0, 20.0)};  // face at x = 0.5
  scene.initial.q = Vec3(wall - scene.radius + 1e-12, 1.0, 0.0);
  scene.initial.v = Vec3(v0, 0.0, 0.0);
  const State end = test::final_state(scene);
  const double expected = law == DampingLaw::Compression
                              ? benchmarks::compression_restitution(zeta)
                              : benchmarks::kelvin_voigt_restitution(zeta);
  EXPECT_LT(end.q.x(), wall - scene.radius) << "still in contact at the end";
  EXPECT_NEAR(-end.v.x() / v0, expected, 2e-6 * zeta * expected);
  EXPECT_DOUBLE_EQ(end.v.y(), 0.0);
}

TEST_P(WallRebound, BallOffASlantedSegmentReflectsTheNormalComponent) {
  // A frictionless 30° slope (a thin segment): the velocity along the slope
  // is untouched and the normal component comes back scaled by e.
  const auto [law, zeta] = GetParam();
  Scene scene = wall_scene(law, zeta);
  const double slope = test::kPi / 6.0;
  const Vec2 along(std::cos(slope), std::sin(slope));
  const Vec2 n(-along.y(), along.x());  // the segment's upper normal
  const double thickness = 0.02;
  scene.obstacles = {make_segment_obstacle(-2.0 * along, 2.0 * along, thickness)};
  const Vec2 start = (scene.radius + thickness - 1e-12) * n;  // touching above the origin
  const Vec2 v0 = 0.8 * along - 1.0 * n;                      // 1 m/s into it, 0.8 m/s along
  scene.initial.q = Vec3(start.x(), start.y(), 0.0);
  scene.initial.v = Vec3(v0.x(), v0.y(), 0.0);
  const State end = test::final_state(scene);
  const Vec2 v(end.v.x(), end.v.y());
  const double expected = law == DampingLaw::Compression
                              ? benchmarks::compression_restitution(zeta)
                              : benchmarks::kelvin_voigt_restitution(zeta);
  EXPECT_NEAR(v.dot(n), expected, 2e-6 * zeta * expected);
  EXPECT_NEAR(v.dot(along), 0.8, 1e-12);
  EXPECT_NEAR(end.v.z(), 0.0, 1e-12) << "no friction, no spin";
}

INSTANTIATE_TEST_SUITE_P(Laws, WallRebound,
                         ::testing::Values(ReboundCase{DampingLaw::Compression, 0.05},
                                           ReboundCase{DampingLaw::Compression, 0.3},
                                           ReboundCase{DampingLaw::KelvinVoigt, 0.05},
                                           ReboundCase{DampingLaw::KelvinVoigt, 0.3}),
                         [](const auto& info) {
                           return std::string(info.param.law == DampingLaw::Compression
                                                  ? "compression"
                                                  : "kelvin_voigt") +
                                  "_zeta" +
                                  std::to_string(
                                      static_cast<int>(std::lround(info.param.zeta * 100)));
                         });

// ---------------------------------------------------------------------------
// Sliding and rolling on a box top is the ground's problem shifted up: the
// disc's closest point on a flat top face is the point below the centre, so
// the two runs agree to rounding (the depth is computed as R − (y − top)
// instead of R − y: a few ulps of 0.5 m per step, accumulated over 20 000
// steps stays below 1e-9 m).
TEST(ObstacleFriction, RollingOnABoxTopMatchesRollingOnTheGround) {
  Scene ground = default_scene(Shape::Circle);
  ground.contact.mu = 0.5;
  ground.contact.mu_roll = 0.01;
  ground.initial.q = Vec3(0.0, ground.radius - 1e-3, 0.0);
  ground.initial.v = Vec3(2.0, 0.0, 5.0);  // slides first (ω ≠ −v/R), then rolls
  ground.sim.duration = 2.0;
  Scene table = ground;
  const double top = 0.5;
  table.obstacles = {make_box_obstacle(0.0, 0.5 * top, 100.0, top)};
  table.initial.q.y() += top;
  const State a = test::final_state(ground);
  const State b = test::final_state(table);
  EXPECT_NEAR(b.q.x(), a.q.x(), 1e-9);
  EXPECT_NEAR(b.q.y() - top, a.q.y(), 1e-9);
  EXPECT_NEAR(b.q.z(), a.q.z(), 1e-8);
  EXPECT_NEAR(b.v.x(), a.v.x(), 1e-9);
  EXPECT_NEAR(b.v.z(), a.v.z(), 1e-8);
  EXPECT_GT(a.q.x(), 1.0) << "the ball must actually travel for the comparison to mean anything";
}

// ---------------------------------------------------------------------------
// Geometry of one contact, checked against a hand computation.
TEST(ObstacleGeometry, DiscAtABoxCornerIsPushedRadially) {
  const Obstacle box = make_box_obstacle(0.0, 0.0, 2.0, 2.0);  // corner at (1, 1)
  ObstacleContact contact;
  ASSERT_TRUE(disc_contact(box, Vec2(1.06, 1.08), 0.11, contact));  // 0.1 from the corner
  EXPECT_NEAR(contact.depth, 0.01, 1e-15);
  EXPECT_NEAR(contact.normal.x(), 0.6, 1e-15);
  EXPECT_NEAR(contact.normal.y(), 0.8, 1e-15);
  EXPECT_NEAR(contact.r.x(), -0.066, 1e-15);
  EXPECT_NEAR(contact.r.y(), -0.088, 1e-15);
  EXPECT_FALSE(disc_contact(box, Vec2(1.06, 1.08), 0.1 - 1e-12, contact));
}

TEST(ObstacleGeometry, DepthIsContinuousAsTheCentreCrossesTheFace) {
  const Obstacle box = make_box_obstacle(0.0, 0.0, 2.0, 2.0);  // top face y = 1
  ObstacleContact above, below;
  const double eps = 1e-6, radius = 0.1;
  ASSERT_TRUE(disc_contact(box, Vec2(0.3, 1.0 + eps), radius, above));
  ASSERT_TRUE(disc_contact(box, Vec2(0.3, 1.0 - eps), radius, below));
  EXPECT_NEAR(above.depth, radius - eps, 1e-15);
  EXPECT_NEAR(below.depth, radius + eps, 1e-15);
  EXPECT_EQ(above.normal, below.normal);
}

TEST(ObstacleGeometry, ForceAndTorqueOfOneContactFollowTheLaw) {
  // A disc pressed into the corner region, moving: normal force along n with
  // the damper on the normal velocity, friction along t = (n_y, −n_x), torque
  // r × F plus rolling resistance.
  Model model;
  model.body = make_circle(0.5, 0.11);
  model.gravity = 0.0;  // the contact force alone
  ContactParams& law = model.contact;
  law.k = 1e4;
  law.c = 30.0;
  law.mu = 0.4;
  law.alpha = 50.0;
  law.mu_roll = 0.02;
  model.obstacles = {make_box_obstacle(0.0, 0.0, 2.0, 2.0)};
  const Vec3 q(1.06, 1.08, 0.7);  // far above the ground
  const Vec3 v(-0.3, -0.2, 4.0);
  ContactSet contacts(model);
  find_contacts(model, q, contacts);
  ASSERT_EQ(contacts.size(), 1u);
  const Vec3 a = acceleration(model, contacts, v);
  const Vec2 force = model.body.mass * a.head<2>();
  const double torque = model.body.inertia * a.z();

  const Vec2 n(0.6, 0.8), t(0.8, -0.6), r = -0.11 * n;
  const Vec2 vc(v.x() - v.z() * r.y(), v.y() + v.z() * r.x());
  const double fn = law.k * 0.01 + law.c * std::max(0.0, -vc.dot(n));
  const double ft = -law.mu * fn * std::tanh(law.alpha * vc.dot(t));
  const Vec2 f = fn * n + ft * t;
  const double tau =
      r.x() * f.y() - r.y() * f.x() - law.mu_roll * fn * std::tanh(law.alpha * 0.11 * v.z());
  EXPECT_NEAR(force.x(), f.x(), 1e-12 * fn);
  EXPECT_NEAR(force.y(), f.y(), 1e-12 * fn);
  EXPECT_NEAR(torque, tau, 1e-12 * fn);
  EXPECT_GT(fn, 100.0) << "the case must have a real contact force";
}

TEST(ObstacleGeometry, PointInsideABoxLeavesThroughTheNearestFace) {
  const Obstacle box = make_box_obstacle(0.0, 0.0, 2.0, 1.0);  // x in [-1, 1], y in [-0.5, 0.5]
  ObstacleContact contact;
  ASSERT_TRUE(point_contact(box, Vec2(0.95, 0.1), contact));
  EXPECT_NEAR(contact.depth, 0.05, 1e-15);
  EXPECT_EQ(contact.normal, Vec2(1.0, 0.0));
  ASSERT_TRUE(point_contact(box, Vec2(-0.2, -0.45), contact));
  EXPECT_NEAR(contact.depth, 0.05, 1e-15);
  EXPECT_EQ(contact.normal, Vec2(0.0, -1.0));
  EXPECT_FALSE(point_contact(box, Vec2(1.01, 0.0), contact));
}

// ---------------------------------------------------------------------------
// Energy: without damping and friction the contact is a conservative spring,
// and energy() counts the obstacle's spring. At the deepest point all the
// energy is in the spring: without that term energy() would read ~0 there.
// The ball starts exactly at the face, so the force's kink at d = 0 falls on
// a step boundary and RK4 at ω·Δt = 1e-3 is smooth up to the deepest point:
// its error there is O((ω·Δt)⁴) ≈ 1e-12, below the 1e-9 relative tolerance.
// (After separation the kink falls inside a step: measured 3e-8 then.)
TEST(ObstacleEnergy, SpringEnergyIsCountedDuringAnElasticBounce) {
  Scene scene = wall_scene(DampingLaw::Compression, 0.0);
  scene.contact.c = 0.0;
  scene.obstacles = {make_box_obstacle(1.0, 1.0, 1.0, 20.0)};  // face at x = 0.5
  scene.initial.q = Vec3(0.5 - scene.radius, 1.0, 0.0);        // well above the ground
  scene.initial.v = Vec3(1.0, 0.0, 0.0);
  scene.sim.output_dt = scene.sim.dt;
  const Model model = make_model(scene);
  const double e0 = energy(model, initial_state(scene));
  double deepest = 0.0, energy_there = 0.0;
  ReferenceStepper stepper(scene);
  run(stepper, scene.sim, [&](const Sample& s) {
    const double depth = max_penetration(model, s.state.q);
    if (depth > deepest) {
      deepest = depth;
      energy_there = energy(model, s.state);
    }
  });
  // v0/ω, to within one step of travel at the turning point (v ≈ 0 there).
  EXPECT_NEAR(deepest, 1.0 / std::sqrt(scene.contact.k / scene.mass), 1e-8);
  EXPECT_NEAR(energy_there, e0, 1e-9 * e0);
}

// ---------------------------------------------------------------------------
// The divergence rule with a player: a constant push of F into a wall holds
// the ball at d = F/k, with work F·d done on it. With g = 0 and the ball at
// rest the scene alone holds (almost) no energy, so that depth is only
// explained by the applied work: the monitor must accept it with the work
// and flag it without.
TEST(ObstacleDivergence, AppliedWorkExplainsAPushIntoAWall) {
  Scene scene = wall_scene(DampingLaw::KelvinVoigt, 1.0);
  scene.obstacles = {make_box_obstacle(1.0, 1.0, 1.0, 20.0)};
  scene.initial.q = Vec3(0.5 - scene.radius, 1.0, 0.0);  // well above the ground
  scene.initial.v = Vec3::Zero();
  Model model = make_model(scene);
  const double push = 1000.0;
  model.applied = Vec3(push, 0.0, 0.0);
  State s = initial_state(scene);
  StepWorkspace ws(model);
  find_contacts(model, s.q, ws.contacts);
  const DivergenceMonitor monitor(model, s, ws.contacts);
  double work = 0.0;
  for (int i = 0; i < 20000; ++i) {  // 0.2 s = 20 periods of the critically damped contact
    const double x0 = s.q.x();
    step(model, Integrator::RK4, scene.sim.dt, s, ws);
    work += push * (s.q.x() - x0);
  }
  const double d = push / scene.contact.k;
  EXPECT_NEAR(max_penetration(model, s.q), d, 1e-6 * d);
  EXPECT_FALSE(monitor.check(s, ws.contacts, 0.2, work)) << "the push explains the depth";
  const auto flagged = monitor.check(s, ws.contacts, 0.2, 0.0);
  ASSERT_TRUE(flagged);
  EXPECT_NE(flagged->kind, DivergenceKind::NonFinite);
}

}  // namespace
}  // namespace contact2d
