#include "core/dynamics.hpp"

#include <algorithm>
#include <cmath>

namespace contact2d {
namespace {

// Rotation applied to the body-fixed points: R(θ) for most bodies, identity
// for a circle whose contact point stays below the centre.
struct PointFrame {
  double cos_t = 1.0;
  double sin_t = 0.0;
  Vec2 operator()(const Vec2& local) const {
    return {cos_t * local.x() - sin_t * local.y(), sin_t * local.x() + cos_t * local.y()};
  }
};

PointFrame point_frame(const RigidBody& body, double theta) {
  if (!body.points_rotate) return {};
  return {std::cos(theta), std::sin(theta)};
}

}  // namespace

Vec3 acceleration(const Model& model, const Vec3& q, const Vec3& v) {
  const RigidBody& body = model.body;
  const ContactParams& law = model.contact;
  const PointFrame rotate = point_frame(body, q.z());
  Vec2 force(model.applied.x(), model.applied.y() - body.mass * model.gravity);
  double torque = model.applied.z();

  for (const Vec2& local : body.points) {
    const Vec2 r = rotate(local);
    const double c_y = q.y() + r.y();
    if (c_y >= 0.0) continue;
    const double vc_x = v.x() - v.z() * r.y();
    const double vc_y = v.y() + v.z() * r.x();
    const double fn = normal_force(law, -c_y, vc_y);
    const double ft = friction_force(law, fn, vc_x);
    force += Vec2(ft, fn);
    torque += r.x() * fn - r.y() * ft + rolling_torque(law, fn, body.roll_radius, v.z());
  }
  if (!model.obstacles.empty())
    add_obstacle_forces(model.obstacles, body, law, q, v, force, torque);

  const double alpha = (body.rotates && body.inertia > 0.0) ? torque / body.inertia : 0.0;
  return {force.x() / body.mass, force.y() / body.mass, alpha};
}

double max_penetration(const Model& model, const Vec3& q) {
  const PointFrame rotate = point_frame(model.body, q.z());
  double deepest = 0.0;
  for (const Vec2& local : model.body.points) {
    const double depth = -(q.y() + rotate(local).y());
    if (depth > deepest) deepest = depth;
  }
  if (!model.obstacles.empty()) {
    deepest = std::max(deepest, obstacle_max_penetration(model.obstacles, model.body, q));
  }
  return deepest;
}

double energy(const Model& model, const State& s) {
  const RigidBody& body = model.body;
  const PointFrame rotate = point_frame(body, s.q.z());
  double e = 0.5 * body.mass * (s.v.x() * s.v.x() + s.v.y() * s.v.y()) +
             0.5 * body.inertia * s.v.z() * s.v.z() + body.mass * model.gravity * s.q.y();
  for (const Vec2& local : body.points) {
    const double depth = -(s.q.y() + rotate(local).y());
    if (depth > 0.0) e += 0.5 * model.contact.k * depth * depth;
  }
  if (!model.obstacles.empty())
    e += obstacle_spring_energy(model.obstacles, body, model.contact.k, s.q);
  return e;
}

}  // namespace contact2d
