// The grazing-contact finder (analysis/grazing.hpp) on trajectories built by
// hand: the heights and distances below are the states' own, written out.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/grazing.hpp"
#include "core/scene.hpp"

namespace contact2d {
namespace {

// A run of `n` samples 1e-4 s apart, every one the state `s`.
Trajectory constant_run(const State& s, int n) {
  Trajectory t;
  for (int i = 0; i < n; ++i) t.samples.push_back({1e-4 * i, s});
  return t;
}

State at(double x, double y, double theta) {
  State s;
  s.q = Vec3(x, y, theta);
  return s;
}

// The default box (0.4 × 0.2 m) with its lower corners h above the ground.
Scene box_scene() { return default_scene(Shape::Box); }
double resting_y(const Scene& s, double h) { return 0.5 * s.height + h; }

TEST(Grazing, FindsTheFirstStepAtWhichOneRunTouchesAndTheOtherNot) {
  const Scene scene = box_scene();
  const Trajectory a = constant_run(at(0.0, resting_y(scene, 1e-12), 0.0), 10);
  Trajectory b = a;
  // From sample 5 on, b is 2e-12 m lower: its lower corners 1e-12 m into
  // the ground, a's 1e-12 m above it.
  for (int i = 5; i < 10; ++i) b.samples[i].state.q.y() = resting_y(scene, -1e-12);
  const auto g = analysis::grazing_contact(scene, a, b, 1e-9);
  ASSERT_TRUE(g.has_value());
  EXPECT_DOUBLE_EQ(g->t, 5e-4);
  EXPECT_NE(g->where.find("on the ground"), std::string::npos) << g->where;
  EXPECT_FALSE(g->touches_a);
  // y = 0.1 + 1e-12 and the corner −0.1 below it: the rounding of 0.1 (1.4e-17)
  // is all that separates these from ±1e-12.
  EXPECT_NEAR(g->height_a, 1e-12, 1e-16);
  EXPECT_NEAR(g->height_b, -1e-12, 1e-16);
  EXPECT_NEAR(g->apart, 2e-12, 1e-16);
}

TEST(Grazing, FindsNothingWhenTheRunsAgreeOnEveryContact) {
  const Scene scene = box_scene();
  const Trajectory a = constant_run(at(0.0, resting_y(scene, 1e-12), 0.0), 10);
  Trajectory b = a;
  for (Sample& s : b.samples) s.state.q.y() += 5e-13;  // both above the ground
  EXPECT_FALSE(analysis::grazing_contact(scene, a, b, 1e-9).has_value());
  EXPECT_FALSE(analysis::grazing_contact(scene, a, a, 1e-9).has_value());
}

TEST(Grazing, StopsAtTheDeparture) {
  const Scene scene = box_scene();
  const Trajectory a = constant_run(at(0.0, resting_y(scene, 1e-12), 0.0), 10);
  Trajectory b = a;
  // At sample 3 the runs are 1e-6 m apart (sideways): departed. The
  // contact that differs at sample 5 comes after it.
  for (int i = 3; i < 10; ++i) b.samples[i].state.q.x() = 1e-6;
  for (int i = 5; i < 10; ++i) b.samples[i].state.q.y() = resting_y(scene, -1e-12);
  EXPECT_DOUBLE_EQ(analysis::departure_time(scene, a, b, 1e-9), 3e-4);
  EXPECT_FALSE(analysis::grazing_contact(scene, a, b, 1e-9).has_value());
  // With a wider window the same switch is found.
  EXPECT_TRUE(std::isnan(analysis::departure_time(scene, a, b, 1e-3)));
  ASSERT_TRUE(analysis::grazing_contact(scene, a, b, 1e-3).has_value());
}

TEST(Grazing, ATurnOfTheBoxMovesOneCorner) {
  const Scene scene = box_scene();
  // Both lower corners 1e-12 m above the ground in a; in b the box turns by
  // 1e-11 rad about its centre, which lowers the corner at −w/2 by
  // (w/2)·1e-11 = 2e-12 m: 1e-12 m into the ground. The other rises.
  const Trajectory a = constant_run(at(0.0, resting_y(scene, 1e-12), 0.0), 4);
  const Trajectory b = constant_run(at(0.0, resting_y(scene, 1e-12), 1e-11), 4);
  const auto g = analysis::grazing_contact(scene, a, b, 1e-9);
  ASSERT_TRUE(g.has_value());
  EXPECT_DOUBLE_EQ(g->t, 0.0);
  EXPECT_NEAR(g->height_b, -1e-12, 1e-16);
  // Every corner is √((w/2)² + (h/2)²) from the centre and moves by that
  // times θ: 2.24e-12 m.
  EXPECT_NEAR(g->apart, std::hypot(0.2, 0.1) * 1e-11, 1e-16);
}

TEST(Grazing, ADiscsLowestPointStaysBelowItsCentre) {
  const Scene scene = default_scene(Shape::Circle);
  // A disc turned by 1 rad is no lower: only its centre's height counts.
  const Trajectory a = constant_run(at(0.0, scene.radius + 1e-12, 0.0), 4);
  const Trajectory b = constant_run(at(0.0, scene.radius + 1e-12, 1.0), 4);
  EXPECT_FALSE(analysis::grazing_contact(scene, a, b, 1e-9).has_value());
  const Trajectory c = constant_run(at(0.0, scene.radius - 1e-12, 0.0), 4);
  ASSERT_TRUE(analysis::grazing_contact(scene, a, c, 1e-9).has_value());
}

TEST(Grazing, AnObstacleTouchedInOneRunOnly) {
  Scene scene = box_scene();
  // A box obstacle whose top is at x ∈ [1, 2], y = 0.5; the body floats
  // above it (no ground contact), its lower corners 1e-12 m above the top
  // in a and 1e-12 m into it in b.
  scene.obstacles.push_back(make_box_obstacle(1.5, 0.25, 1.0, 0.5));
  const Trajectory a = constant_run(at(1.5, 0.5 + resting_y(scene, 1e-12), 0.0), 4);
  const Trajectory b = constant_run(at(1.5, 0.5 + resting_y(scene, -1e-12), 0.0), 4);
  const auto g = analysis::grazing_contact(scene, a, b, 1e-9);
  ASSERT_TRUE(g.has_value());
  EXPECT_EQ(g->where, "obstacle 0");
  EXPECT_FALSE(g->touches_a);
  EXPECT_TRUE(std::isnan(g->height_a));
  EXPECT_NEAR(g->height_b, -1e-12, 1e-15);
}

}  // namespace
}  // namespace contact2d
