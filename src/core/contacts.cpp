#include "core/contacts.hpp"

#include <algorithm>
#include <cmath>

#include "core/ellipse.hpp"

namespace contact2d {

ContactSet::ContactSet(const Model& model) {
  const size_t points = model.body.points.size();
  const size_t obstacles = model.obstacles.size();
  const size_t parts = model.body.parts.size();
  // Ground and body points against obstacles, a disc's one contact per
  // obstacle, and up to four obstacle vertices against every part.
  storage_.resize(points * (1 + obstacles) + obstacles + 4 * obstacles * parts);
}

void find_contacts(const Model& model, const Vec3& q, ContactSet& out) {
  const RigidBody& body = model.body;
  const Vec2 p(q.x(), q.y());
  // One rotation of the body's points: R(θ), or the identity for a disc,
  // whose point stays below the centre. At θ = ±0 (a point mass always,
  // which never turns) cos θ = 1 and sin θ = θ exactly, so the libm call is
  // skipped with the same bits.
  const bool disc = shape_features(body.shape).rolls;
  const bool turned = !disc && q.z() != 0.0;
  const double ct = turned ? std::cos(q.z()) : 1.0;
  const double st = turned ? std::sin(q.z()) : (disc ? 0.0 : q.z());
  const Vec2* const points = body.points.data();
  const size_t n_points = body.points.size();
  Contact* const first = out.storage_.data();  // room for every contact at once
  Contact* next = first;

  // A smooth outline (the ellipse): its support point, not a body point
  // (core/ellipse.hpp has the geometry).
  if (shape_features(body.shape).smooth) {
    const double a = body.semi_axes.x(), b = body.semi_axes.y();
    const Vec2 r = ellipse_lowest_point(a, b, q.z());
    const double c_y = q.y() + r.y();
    if (!(c_y >= 0.0)) *next++ = {-c_y, 0.0, 1.0, r.x(), r.y()};  // NaN stays visible
    out.ground_ = static_cast<size_t>(next - first);
    if (!model.obstacles.empty()) {
      const double ct = std::cos(q.z()), st = std::sin(q.z());
      ObstacleContact hit;
      for (size_t j = 0; j < model.obstacles.size(); ++j) {
        if (ellipse_obstacle_contact(model.obstacles[j], a, b, p, ct, st, hit))
          *next++ = {hit.depth, hit.normal.x(), hit.normal.y(),
                     hit.r.x(), hit.r.y(),      static_cast<int>(j)};
      }
    }
    out.size_ = static_cast<size_t>(next - first);
    return;
  }

  // Ground, the half-plane y < 0: d = −c_y, n = +y.
  for (size_t i = 0; i < n_points; ++i) {
    const double rx = ct * points[i].x() - st * points[i].y();
    const double ry = st * points[i].x() + ct * points[i].y();
    const double c_y = q.y() + ry;
    if (!(c_y >= 0.0)) *next++ = {-c_y, 0.0, 1.0, rx, ry};  // NaN stays visible
  }
  out.ground_ = static_cast<size_t>(next - first);

  // Obstacles: a disc meets them with its whole rim, other bodies with their points.
  if (!model.obstacles.empty()) {
    ObstacleContact hit;
    if (disc) {
      for (size_t j = 0; j < model.obstacles.size(); ++j) {
        if (disc_contact(model.obstacles[j], p, body.roll_radius, hit))
          *next++ = {hit.depth, hit.normal.x(), hit.normal.y(),
                     hit.r.x(), hit.r.y(),      static_cast<int>(j)};
      }
    } else {
      for (size_t i = 0; i < n_points; ++i) {
        const Vec2& local = points[i];
        const double rx = ct * local.x() - st * local.y();
        const double ry = st * local.x() + ct * local.y();
        const Vec2 c(p.x() + rx, p.y() + ry);
        for (size_t j = 0; j < model.obstacles.size(); ++j) {
          if (point_contact(model.obstacles[j], c, hit))
            *next++ = {hit.depth, hit.normal.x(), hit.normal.y(), rx, ry, static_cast<int>(j)};
        }
      }
      // Obstacle vertices (box corners, segment caps) against the body's edges.
      for (size_t j = 0; j < model.obstacles.size(); ++j) {
        const Obstacle& o = model.obstacles[j];
        Vec2 vertices[4];
        double radius = 0.0;
        const int n_vertices = obstacle_vertices(o, vertices, radius);
        for (int k = 0; k < n_vertices; ++k) {
          for (const PartOutline& part : body.parts) {
            if (vertex_part_contact(vertices[k], radius, p, ct, st, part, hit))
              *next++ = {hit.depth, hit.normal.x(), hit.normal.y(),
                         hit.r.x(), hit.r.y(),      static_cast<int>(j)};
          }
        }
      }
    }
  }
  out.size_ = static_cast<size_t>(next - first);
}

double max_penetration(const ContactSet& contacts) {
  double deepest = 0.0;
  for (const Contact& c : contacts) deepest = std::max(deepest, c.depth);
  return deepest;
}

}  // namespace contact2d
