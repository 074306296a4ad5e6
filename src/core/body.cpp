#include "core/body.hpp"

#include <algorithm>
#include <cmath>

namespace contact2d {

MassProperties compound_mass_properties(const std::vector<BoxPart>& parts) {
  MassProperties props;
  for (const BoxPart& part : parts) {
    props.mass += part.mass;
    props.com += part.mass * Vec2(part.x, part.y);
  }
  if (props.mass <= 0.0) return props;
  props.com /= props.mass;
  for (const BoxPart& part : parts) {
    const double own = part.mass * (part.width * part.width + part.height * part.height) / 12.0;
    const double shift = part.mass * (Vec2(part.x, part.y) - props.com).squaredNorm();
    props.inertia += own + shift;
  }
  return props;
}

namespace {

// A body of `shape` with its feature flags set; the caller adds the data.
RigidBody shaped_body(Shape shape) {
  RigidBody body;
  body.shape = shape;
  body.rotates = shape_features(shape).turns;
  body.points_rotate = !shape_features(shape).rolls && !shape_features(shape).smooth;
  return body;
}

}  // namespace

RigidBody make_point_mass(double mass, double half_height) {
  RigidBody body = shaped_body(Shape::PointMass);
  body.mass = mass;
  body.inertia = 0.0;
  body.points = {Vec2(0.0, -half_height)};
  return body;
}

RigidBody make_compound(const std::vector<BoxPart>& parts) {
  const MassProperties props = compound_mass_properties(parts);
  RigidBody body = shaped_body(Shape::TShape);
  body.mass = props.mass;
  body.inertia = props.inertia;
  body.com_offset = props.com;
  for (const BoxPart& part : parts) {
    const double hx = 0.5 * part.width;
    const double hy = 0.5 * part.height;
    const Vec2 centre = Vec2(part.x, part.y) - props.com;
    body.parts.push_back(PartOutline{centre, hx, hy});
    for (const Vec2& corner : {Vec2(-hx, -hy), Vec2(hx, -hy), Vec2(hx, hy), Vec2(-hx, hy)}) {
      body.points.push_back(centre + corner);
    }
  }
  return body;
}

RigidBody make_box(double mass, double width, double height) {
  RigidBody body = make_compound({BoxPart{width, height, 0.0, 0.0, mass}});
  body.shape = Shape::Box;
  return body;
}

RigidBody make_circle(double mass, double radius) {
  RigidBody body = shaped_body(Shape::Circle);
  body.mass = mass;
  body.inertia = 0.5 * mass * radius * radius;
  body.roll_radius = radius;
  body.points = {Vec2(0.0, -radius)};
  return body;
}

RigidBody make_ellipse(double mass, double a, double b, double inertia) {
  RigidBody body = shaped_body(Shape::Ellipse);
  body.mass = mass;
  body.inertia = inertia;
  body.semi_axes = Vec2(a, b);
  body.roll_radius = std::sqrt(a * b);
  body.points = {Vec2(0.0, -b)};
  return body;
}

double body_extent(const RigidBody& body) {
  if (shape_features(body.shape).smooth) return std::max(body.semi_axes.x(), body.semi_axes.y());
  double extent = 0.0;
  for (const Vec2& r : body.points) extent = std::max(extent, r.norm());
  return extent;
}

double min_effective_mass(const RigidBody& body) {
  // A circle's point stays below the centre: the normal has no lever arm.
  const ShapeFeatures features = shape_features(body.shape);
  if (!features.turns || features.rolls || body.inertia <= 0.0) return body.mass;
  const double r = body_extent(body);
  return 1.0 / (1.0 / body.mass + r * r / body.inertia);
}

}  // namespace contact2d
