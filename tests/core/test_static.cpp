// Static penetration at rest: the contact spring carries the weight.
//   point mass   d = m·g/k               (one contact point)
//   flat box     d = m·g/(2k) per corner (two bottom corners share the load)
//   circle       d = m·g/k               (its single point below the centre)
// At rest a = 0 is a fixed point of every integrator, so the only error is
// the transient left after 2 s of critically damped decay, e^(−ω·t) with
// ω ≥ 100 rad/s (< 1e-80), plus rounding: tolerance 1e-9 relative to d.
#include <gtest/gtest.h>

#include "benchmarks/rest.hpp"
#include "support/support.hpp"

namespace contact2d {
namespace {

class StaticPenetration : public ::testing::TestWithParam<Integrator> {};

TEST_P(StaticPenetration, PointMassSinksByWeightOverStiffness) {
  Scene scene = test::resting_scene(Shape::PointMass, GetParam());
  scene.initial.q = Vec3(0.0, scene.half_height, 0.0);
  const double d = benchmarks::rest_depth(scene.mass, scene.sim.gravity, scene.contact.k, 1);
  const State s = test::final_state(scene);
  EXPECT_NEAR(scene.half_height - s.q.y(), d, 1e-9 * d);
}

TEST_P(StaticPenetration, FlatBoxSinksByHalfTheWeightPerCorner) {
  Scene scene = test::resting_scene(Shape::Box, GetParam());
  scene.initial.q = Vec3(0.0, 0.5 * scene.height, 0.0);
  const double d = benchmarks::rest_depth(scene.mass, scene.sim.gravity, scene.contact.k, 2);
  const State s = test::final_state(scene);
  EXPECT_NEAR(0.5 * scene.height - s.q.y(), d, 1e-9 * d);
  EXPECT_NEAR(s.q.z(), 0.0, 1e-12);
}

TEST_P(StaticPenetration, CircleSinksByWeightOverStiffness) {
  Scene scene = test::resting_scene(Shape::Circle, GetParam());
  scene.contact.mu_roll = 0.01;
  scene.initial.q = Vec3(0.0, scene.radius, 0.0);
  const double d = benchmarks::rest_depth(scene.mass, scene.sim.gravity, scene.contact.k, 1);
  const State s = test::final_state(scene);
  EXPECT_NEAR(scene.radius - s.q.y(), d, 1e-9 * d);
}

INSTANTIATE_TEST_SUITE_P(AllIntegrators, StaticPenetration, ::testing::ValuesIn(kAllIntegrators),
                         [](const auto& info) { return std::string(integrator_name(info.param)); });

}  // namespace
}  // namespace contact2d
