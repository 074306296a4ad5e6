// The contact stage (core/contacts.hpp): which points touch, how deep, along
// which normal, at which lever arm — against hand-computed geometry. The
// tolerances are a few ulps of the lengths involved (a handful of flops on
// numbers of order 0.1–1 m).
#include <gtest/gtest.h>

#include <cmath>

#include "core/contacts.hpp"
#include "core/dynamics.hpp"
#include "core/scene.hpp"

namespace contact2d {
namespace {

constexpr double kUlps = 1e-15;

Model box_model(double width, double height) {
  Model model;
  model.body = make_box(1.0, width, height);
  return model;
}

// A 0.4 × 0.2 box tilted by 30° with its COM at y = 0.1: only the corner
// (−0.2, −0.1) is below the ground. R(30°)·(−0.2, −0.1) =
// (−0.1·√3 + 0.05, −0.1 − 0.05·√3), so d = −(0.1 + r_y) = 0.05·√3.
TEST(ContactStage, TiltedBoxTouchesWithItsLowestCornerOnly) {
  const Model model = box_model(0.4, 0.2);
  const double theta = std::acos(-1.0) / 6.0;
  ContactSet contacts(model);
  find_contacts(model, Vec3(0.3, 0.1, theta), contacts);
  ASSERT_EQ(contacts.size(), 1u);
  const Contact& c = *contacts.begin();
  const double root3 = std::sqrt(3.0);
  EXPECT_NEAR(c.depth, 0.05 * root3, kUlps);
  EXPECT_EQ(c.normal(), Vec2(0.0, 1.0));
  EXPECT_NEAR(c.r().x(), -0.1 * root3 + 0.05, kUlps);
  EXPECT_NEAR(c.r().y(), -0.1 - 0.05 * root3, kUlps);
  EXPECT_NEAR(max_penetration(contacts), 0.05 * root3, kUlps);
}

// A circle's contact point stays below its centre whatever θ (it rolls).
TEST(ContactStage, CirclePointStaysBelowTheCentre) {
  Model model;
  model.body = make_circle(1.0, 0.1);
  ContactSet contacts(model);
  find_contacts(model, Vec3(2.0, 0.09, 1.0), contacts);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_NEAR(contacts.begin()->depth, 0.01, kUlps);
  EXPECT_EQ(contacts.begin()->r(), Vec2(0.0, -0.1));
}

// Ground contacts come first, then obstacles, in the order the force stage
// sums them. A point 1 cm below the ground, inside a box that fills
// y ∈ [−1, 0]: the ground (d = 0.01, n = +y) and the box's top face
// (its nearest face, d = 0.01, n = +y).
TEST(ContactStage, GroundFirstThenEveryObstacle) {
  Model model;
  model.body = make_point_mass(1.0, 0.05);
  model.obstacles = {make_box_obstacle(0.0, -0.5, 4.0, 1.0),
                     make_box_obstacle(5.0, 0.0, 1.0, 1.0)};  // far away: no contact
  ContactSet contacts(model);
  find_contacts(model, Vec3(0.0, 0.04, 0.0), contacts);
  ASSERT_EQ(contacts.size(), 2u);
  for (const Contact& c : contacts) {
    EXPECT_NEAR(c.depth, 0.01, kUlps);
    EXPECT_EQ(c.normal(), Vec2(0.0, 1.0));
    EXPECT_EQ(c.r(), Vec2(0.0, -0.05));
  }
}

TEST(ContactStage, NothingTouchesInFlight) {
  const Model model = box_model(0.4, 0.2);
  ContactSet contacts(model);
  find_contacts(model, Vec3(0.0, 1.0, 0.7), contacts);
  EXPECT_TRUE(contacts.empty());
  EXPECT_EQ(max_penetration(contacts), 0.0);
}

// The set is sized once for the model: the deepest configuration (all four
// corners of a flat 0.4 × 0.2 box 0.15 m deep, below the ground and inside
// an obstacle) fits
// without reallocating, so a step never allocates.
TEST(ContactStage, CapacityCoversEveryContactAtOnce) {
  Model model = box_model(0.4, 0.2);
  model.obstacles = {make_box_obstacle(0.0, -0.5, 4.0, 1.0)};
  ContactSet contacts(model);
  const size_t capacity = contacts.capacity();
  ASSERT_GE(capacity, 8u);
  find_contacts(model, Vec3(0.0, -0.15, 0.0), contacts);
  EXPECT_EQ(contacts.size(), 8u);  // 4 ground + 4 obstacle
  EXPECT_EQ(contacts.capacity(), capacity);
}

// The force stage sees q only through the contacts: with none, the body
// falls freely even when q is below the ground.
TEST(ContactStage, ForceStageReadsOnlyTheContacts) {
  const Model model = box_model(0.4, 0.2);
  const ContactSet none(model);
  const Vec3 a = acceleration(model, none, Vec3(0.3, -0.2, 0.5));
  EXPECT_EQ(a, Vec3(0.0, -model.gravity, 0.0));
  ContactSet found(model);
  find_contacts(model, Vec3(0.0, -0.15, 0.0), found);  // all four corners below
  EXPECT_EQ(found.size(), 4u);
  EXPECT_GT(acceleration(model, found, Vec3::Zero()).y(), 0.0) << "the springs push it out";
}

}  // namespace
}  // namespace contact2d
