// The seeded random scenes (report/random_scenes.hpp) and their generator.
#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.hpp"
#include "report/random_scenes.hpp"

namespace contact2d::report {
namespace {

TEST(RandomScenes, SplitMix64ReferenceSequence) {
  // The first outputs of SplitMix64 from seed 0 (Vigna's reference splitmix64.c).
  std::uint64_t state = 0;
  EXPECT_EQ(contact2d::splitmix64(state), 0xE220A8397B1DCDAFull);
  EXPECT_EQ(contact2d::splitmix64(state), 0x6E789E6AA1B965F4ull);
  EXPECT_EQ(contact2d::splitmix64(state), 0x06C45D188009454Full);
}

TEST(RandomScenes, SameSeedSameScenesOtherSeedOthers) {
  const auto a = draw_random_scenes(20260101, 8);
  const auto b = draw_random_scenes(20260101, 8);
  const auto c = draw_random_scenes(7, 8);
  ASSERT_EQ(a.size(), 8u);
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].scene.contact.k, b[i].scene.contact.k);
    EXPECT_EQ(a[i].scene.initial.q, b[i].scene.initial.q);
    EXPECT_EQ(a[i].mass, b[i].mass);
  }
  EXPECT_NE(a[0].scene.contact.k, c[0].scene.contact.k);
}

TEST(RandomScenes, DistributionsAndValidity) {
  const Shape shapes[] = {Shape::PointMass, Shape::Box, Shape::TShape, Shape::Circle};
  const auto scenes = draw_random_scenes(20260101, 200);
  for (size_t i = 0; i < scenes.size(); ++i) {
    const Scene& s = scenes[i].scene;
    SCOPED_TRACE(scenes[i].name);
    EXPECT_EQ(s.shape, shapes[i % 4]);
    EXPECT_FALSE(validate(s));
    EXPECT_EQ(s.contact.damping, DampingLaw::KelvinVoigt);
    EXPECT_EQ(s.sim.dt, 1e-4);
    EXPECT_EQ(s.sim.duration, 1.5);
    EXPECT_GE(s.contact.k, 1e3);
    EXPECT_LE(s.contact.k, std::pow(10.0, 5.5));
    EXPECT_GE(s.contact.mu, 0.1);
    EXPECT_LE(s.contact.mu, 1.0);
    EXPECT_GE(s.initial.q.y(), 0.6);
    EXPECT_LE(s.initial.q.y(), 1.5);
    EXPECT_LE(std::abs(s.initial.v.x()), 1.5);
    if (s.shape == Shape::PointMass) {
      EXPECT_EQ(s.initial.q.z(), 0.0);
      EXPECT_EQ(s.initial.v.z(), 0.0);
    }
    if (s.shape == Shape::TShape) {
      EXPECT_GE(s.parts.size(), 1u);
      EXPECT_LE(s.parts.size(), 3u);
      double total = 0;
      for (const BoxPart& p : s.parts) total += p.mass;
      EXPECT_DOUBLE_EQ(scenes[i].mass, total);
    } else {
      EXPECT_GE(s.mass, 0.1 * (1 - 1e-6));
      EXPECT_LE(s.mass, 10 * (1 + 1e-6));
      // c = U(200, 1500)·√m, rounded to 6 digits
      EXPECT_GE(s.contact.c / std::sqrt(s.mass), 200 * (1 - 1e-5));
      EXPECT_LE(s.contact.c / std::sqrt(s.mass), 1500 * (1 + 1e-5));
    }
  }
}

}  // namespace
}  // namespace contact2d::report
