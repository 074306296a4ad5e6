#include "core/contacts.hpp"

#include <algorithm>
#include <cmath>

#include "core/dynamics.hpp"

namespace contact2d {

ContactSet::ContactSet(const Model& model) {
  const size_t points = model.body.points.size();
  const size_t obstacles = model.obstacles.size();
  contacts_.reserve(points * (1 + obstacles) + obstacles);
}

void find_contacts(const Model& model, const Vec3& q, ContactSet& out) {
  out.clear();
  const RigidBody& body = model.body;
  const Vec2 p(q.x(), q.y());
  // One rotation of the body's points: R(θ), or the identity for a circle.
  const double ct = body.points_rotate ? std::cos(q.z()) : 1.0;
  const double st = body.points_rotate ? std::sin(q.z()) : 0.0;

  // Ground, the half-plane y < 0: d = −c_y, n = +y.
  for (const Vec2& local : body.points) {
    const Vec2 r(ct * local.x() - st * local.y(), st * local.x() + ct * local.y());
    const double c_y = q.y() + r.y();
    if (!(c_y >= 0.0)) out.add({-c_y, Vec2(0.0, 1.0), r});  // NaN stays visible
  }
  if (model.obstacles.empty()) return;

  // Obstacles: a disc meets them with its whole rim, other bodies with their points.
  ObstacleContact hit;
  if (body.roll_radius > 0.0) {
    for (const Obstacle& o : model.obstacles) {
      if (disc_contact(o, p, body.roll_radius, hit)) out.add({hit.depth, hit.normal, hit.r});
    }
    return;
  }
  for (const Vec2& local : body.points) {
    const Vec2 r(ct * local.x() - st * local.y(), st * local.x() + ct * local.y());
    const Vec2 c = p + r;
    for (const Obstacle& o : model.obstacles) {
      if (point_contact(o, c, hit)) out.add({hit.depth, hit.normal, r});
    }
  }
}

double max_penetration(const ContactSet& contacts) {
  double deepest = 0.0;
  for (const Contact& c : contacts) deepest = std::max(deepest, c.depth);
  return deepest;
}

}  // namespace contact2d
