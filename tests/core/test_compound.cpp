// Compound-body assembly against values worked out by hand.
#include <gtest/gtest.h>

#include "support/support.hpp"

namespace contact2d {
namespace {

// The default T: bar 0.6 × 0.1, 0.6 kg at (0, 0.25); stem 0.1 × 0.4, 0.4 kg
// at (0, 0). By hand:
//   M = 1.0 kg,  COM = (0, 0.6·0.25/1.0) = (0, 0.15)
//   I_bar  = 0.6·(0.36 + 0.01)/12 = 0.0185,   + 0.6·0.10² = 0.006
//   I_stem = 0.4·(0.01 + 0.16)/12 = 0.0056667, + 0.4·0.15² = 0.009
//   I = 0.0391667 kg·m²
// Sums of a few products of short decimals: rounding ≤ 1e-15.
TEST(Compound, DefaultTeeMassComAndInertia) {
  const MassProperties p = compound_mass_properties(default_tshape_parts());
  EXPECT_NEAR(p.mass, 1.0, 1e-15);
  EXPECT_NEAR(p.com.x(), 0.0, 1e-15);
  EXPECT_NEAR(p.com.y(), 0.15, 1e-15);
  EXPECT_NEAR(p.inertia, 0.0185 + 0.006 + 0.4 * 0.17 / 12.0 + 0.009, 1e-15);
}

// An L: a 1.0 × 0.2 base (2 kg) at (0.5, 0.1) and a 0.2 × 0.6 post (1 kg) at
// (0.1, 0.5). By hand: M = 3, COM = ((1.0 + 0.1)/3, (0.2 + 0.5)/3)
// = (0.366667, 0.233333);
//   I = 2·(1.0 + 0.04)/12 + 2·((0.5−x̄)² + (0.1−ȳ)²)
//     + 1·(0.04 + 0.36)/12 + 1·((0.1−x̄)² + (0.5−ȳ)²)
//     = 0.173333 + 0.071111 + 0.033333 + 0.142222 = 0.42 kg·m².
TEST(Compound, AsymmetricEllMassComAndInertia) {
  const std::vector<BoxPart> ell = {{1.0, 0.2, 0.5, 0.1, 2.0}, {0.2, 0.6, 0.1, 0.5, 1.0}};
  const MassProperties p = compound_mass_properties(ell);
  EXPECT_NEAR(p.mass, 3.0, 1e-15);
  EXPECT_NEAR(p.com.x(), 1.1 / 3.0, 1e-15);
  EXPECT_NEAR(p.com.y(), 0.7 / 3.0, 1e-15);
  EXPECT_NEAR(p.inertia, 0.42, 1e-14);
}

TEST(Compound, ContactPointsAreEveryPartVertexRelativeToTheCom) {
  const RigidBody tee = make_compound(default_tshape_parts());
  ASSERT_EQ(tee.points.size(), 8u);
  // The stem's bottom corners: (±0.05, −0.2) in the construction frame,
  // (±0.05, −0.35) from the COM at y = 0.15.
  int feet = 0;
  for (const Vec2& p : tee.points) {
    if (std::abs(p.y() + 0.35) < 1e-15 && std::abs(std::abs(p.x()) - 0.05) < 1e-15) ++feet;
  }
  EXPECT_EQ(feet, 2);
}

TEST(Compound, SinglePartIsTheBox) {
  const RigidBody box = make_box(2.0, 0.4, 0.2);
  EXPECT_DOUBLE_EQ(box.inertia, 2.0 * (0.16 + 0.04) / 12.0);  // m(w² + h²)/12
  EXPECT_EQ(box.points.size(), 4u);
}

// A T standing on its stem, tilted 0.4 rad, tips over: its COM is 0.35 m
// above the 0.1 m wide foot, so any tilt beyond atan(0.05/0.35) = 0.14 rad
// falls. It comes to rest on the left foot corner (−0.05, −0.2) and the left
// bar end (−0.3, 0.2) (construction frame), whose joining line (−0.25, 0.4)
// lies flat at θ = π/2 − atan(0.25/0.4) = 1.012 rad. Penetrations of
// ~1e-3 m over the 0.47 m between the two points tilt that by ~2e-3 rad;
// tolerance 0.01 rad.
TEST(Compound, TeeTippedPastItsFootFallsOver) {
  Scene scene = default_scene(Shape::TShape);
  scene.contact.mu = 0.8;
  scene.initial.q = Vec3(0.0, 0.36, 0.4);
  scene.sim.duration = 2.0;
  const Trajectory t = simulate(scene);
  ASSERT_FALSE(t.divergence);
  const double resting = std::acos(-1.0) / 2.0 - std::atan(0.25 / 0.4);
  EXPECT_NEAR(t.samples.back().state.q.z(), resting, 0.01);
}

}  // namespace
}  // namespace contact2d
