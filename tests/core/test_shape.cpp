// The shape table (core/shape.hpp): each shape's features against what the
// physics of its scene does (a torque turns it or not, its contact point
// turns with θ or stays below the centre, it meets an obstacle with its rim,
// its mass comes from its parts), the body built from a scene carrying its
// shape, and the scene file's names read back.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "core/contacts.hpp"
#include "core/dynamics.hpp"
#include "core/scene.hpp"
#include "core/shape.hpp"

namespace contact2d {
namespace {

TEST(Shape, TableSaysWhatEachShapeHas) {
  const ShapeFeatures point = shape_features(Shape::PointMass);
  const ShapeFeatures box = shape_features(Shape::Box);
  const ShapeFeatures tshape = shape_features(Shape::TShape);
  const ShapeFeatures circle = shape_features(Shape::Circle);
  EXPECT_FALSE(point.turns);
  EXPECT_FALSE(point.rolls);
  EXPECT_FALSE(point.corners);
  EXPECT_FALSE(point.compound);
  EXPECT_TRUE(box.turns);
  EXPECT_FALSE(box.rolls);
  EXPECT_TRUE(box.corners);
  EXPECT_FALSE(box.compound);
  EXPECT_TRUE(tshape.turns);
  EXPECT_FALSE(tshape.rolls);
  EXPECT_TRUE(tshape.corners);
  EXPECT_TRUE(tshape.compound);
  EXPECT_TRUE(circle.turns);
  EXPECT_TRUE(circle.rolls);
  EXPECT_FALSE(circle.corners);
  EXPECT_FALSE(circle.compound);
  static_assert(shape_features(Shape::Circle).rolls, "the table is usable at compile time");
  // The ellipse: turns, its point slides over a smooth rim, rolling resistance.
  const ShapeFeatures ellipse = shape_features(Shape::Ellipse);
  EXPECT_TRUE(ellipse.turns);
  EXPECT_FALSE(ellipse.rolls);
  EXPECT_FALSE(ellipse.corners);
  EXPECT_FALSE(ellipse.compound);
  EXPECT_TRUE(ellipse.smooth);
  EXPECT_TRUE(ellipse.resists_rolling);
  EXPECT_TRUE(circle.resists_rolling);
  EXPECT_FALSE(circle.smooth);
  EXPECT_FALSE(box.resists_rolling || box.smooth || point.smooth || tshape.smooth);
}

TEST(Shape, BodyOfASceneCarriesItsShapeAndItsFlags) {
  for (Shape shape : kAllShapes) {
    SCOPED_TRACE(std::string(shape_name(shape)));
    const RigidBody body = make_body(default_scene(shape));
    const ShapeFeatures features = shape_features(shape);
    EXPECT_EQ(body.shape, shape);
    EXPECT_EQ(body.rotates, features.turns);
    EXPECT_EQ(body.points_rotate, !features.rolls && !features.smooth);
    EXPECT_EQ(body.roll_radius > 0.0, features.resists_rolling);
    // Smooth: the outline's semi-axes are set, and only then.
    EXPECT_EQ(body.semi_axes.x() > 0.0 && body.semi_axes.y() > 0.0, features.smooth);
    // Corners: the points are the four corners of each rectangular outline.
    EXPECT_EQ(!body.parts.empty(), features.corners);
    if (features.corners) {
      EXPECT_EQ(body.points.size(), 4 * body.parts.size());
    }
  }
}

// An applied torque, the body in the air: it turns exactly when θ is a
// degree of freedom.
TEST(Shape, TurnsIsWhetherATorqueTurnsTheBody) {
  for (Shape shape : kAllShapes) {
    SCOPED_TRACE(std::string(shape_name(shape)));
    Model model = make_model(default_scene(shape));
    model.applied = Vec3(0.0, 0.0, 1.0);
    const Vec3 a = acceleration(model, Vec3(0.0, 10.0, 0.0), Vec3::Zero());
    EXPECT_EQ(a.z() > 0.0, shape_features(shape).turns) << a.z();
  }
}

// The body turned by 0.5 rad with its COM on the ground: a rolling body's
// contact point stays where it is in the body frame (below the centre);
// every other turning body's contacts sit at rotated points.
TEST(Shape, RollsIsWhetherTheContactPointStaysBelowTheCentre) {
  for (Shape shape : kAllShapes) {
    if (!shape_features(shape).turns) continue;
    SCOPED_TRACE(std::string(shape_name(shape)));
    const Model model = make_model(default_scene(shape));
    ContactSet contacts(model);
    find_contacts(model, Vec3(0.0, 0.0, 0.5), contacts);
    ASSERT_GT(contacts.size(), 0u);
    bool all_unturned = true;
    for (const Contact& c : contacts) {
      bool unturned = false;
      for (const Vec2& r : model.body.points)
        unturned = unturned || (c.rx == r.x() && c.ry == r.y());
      all_unturned = all_unturned && unturned;
    }
    EXPECT_EQ(all_unturned, shape_features(shape).rolls);
  }
}

// A wall touching the circle's side, far from its one contact point: a
// rolling body meets obstacles with its whole rim.
TEST(Shape, TheCircleMeetsAnObstacleWithItsRim) {
  Scene scene = default_scene(Shape::Circle);
  const double r = scene.radius;
  scene.obstacles = {make_box_obstacle(r - 0.01 + 0.5, 1.0, 1.0, 1.0)};  // face at x = r − 0.01
  const Model model = make_model(scene);
  ContactSet contacts(model);
  find_contacts(model, Vec3(0.0, 1.0, 0.0), contacts);
  ASSERT_EQ(contacts.size() - contacts.ground_count(), 1u);
  const Contact& c = *(contacts.begin() + contacts.ground_count());
  EXPECT_NEAR(c.depth, 0.01, 1e-12);
  EXPECT_NEAR(c.nx, -1.0, 1e-12);
}

// Rolling resistance: the circle on the ground, spinning, no sliding
// friction and no damper (the normal force has no lever arm about the
// centre): only μ_roll brakes the spin.
TEST(Shape, TheCircleFeelsRollingResistance) {
  Scene scene = default_scene(Shape::Circle);
  scene.contact.mu = 0.0;
  scene.contact.c = 0.0;
  const Vec3 q(0.0, 0.9 * scene.radius, 0.0);
  const Vec3 v(0.0, 0.0, 5.0);
  scene.contact.mu_roll = 0.0;
  EXPECT_EQ(acceleration(make_model(scene), q, v).z(), 0.0);
  scene.contact.mu_roll = 0.01;
  EXPECT_LT(acceleration(make_model(scene), q, v).z(), 0.0);
}

// A compound body's mass is that of its parts, whatever the scene's mass.
TEST(Shape, CompoundIsWhetherTheMassComesFromTheParts) {
  for (Shape shape : kAllShapes) {
    SCOPED_TRACE(std::string(shape_name(shape)));
    Scene scene = default_scene(shape);
    scene.mass = 123.0;
    EXPECT_EQ(make_body(scene).mass != 123.0, shape_features(shape).compound);
  }
}

TEST(Shape, NamesReadBackAndAreDistinct) {
  std::set<std::string> names;
  for (Shape shape : kAllShapes) {
    const std::optional<Shape> back = parse_shape(shape_name(shape));
    ASSERT_TRUE(back.has_value()) << shape_name(shape);
    EXPECT_EQ(*back, shape);
    names.insert(std::string(shape_name(shape)));
  }
  EXPECT_EQ(names.size(), kAllShapes.size());
  EXPECT_EQ(shape_name(Shape::PointMass), "point_mass");
  EXPECT_EQ(shape_name(Shape::Circle), "circle");
  EXPECT_EQ(shape_name(Shape::Ellipse), "ellipse");
  static_assert(parse_shape("tshape") == Shape::TShape, "parse_shape is constexpr");
}

TEST(Shape, UnknownNamesAreRejected) {
  for (const char* name : {"capsule", "", "Box", "circle ", "point mass"}) {
    EXPECT_FALSE(parse_shape(name).has_value()) << '"' << name << '"';
  }
}

TEST(Shape, AllShapesListsEveryShapeOnceInOrder) {
  ASSERT_EQ(kAllShapes.size(), 5u);
  EXPECT_EQ(kAllShapes[4], Shape::Ellipse);
  EXPECT_EQ(kAllShapes[0], Shape::PointMass);
  EXPECT_EQ(kAllShapes[1], Shape::Box);
  EXPECT_EQ(kAllShapes[2], Shape::TShape);
  EXPECT_EQ(kAllShapes[3], Shape::Circle);
}

}  // namespace
}  // namespace contact2d
