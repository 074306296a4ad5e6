#include "core/obstacles.hpp"

#include <algorithm>
#include <cmath>

namespace contact2d {

Obstacle make_box_obstacle(double x, double y, double width, double height) {
  Obstacle o;
  o.shape = ObstacleShape::Box;
  o.a = Vec2(x - 0.5 * width, y - 0.5 * height);
  o.b = Vec2(x + 0.5 * width, y + 0.5 * height);
  return o;
}

Obstacle make_segment_obstacle(const Vec2& a, const Vec2& b, double radius) {
  Obstacle o;
  o.shape = ObstacleShape::Segment;
  o.a = a;
  o.b = b;
  o.radius = radius;
  return o;
}

std::string_view obstacle_shape_name(ObstacleShape shape) {
  return shape == ObstacleShape::Box ? "box" : "segment";
}

namespace {

// Nearest face of a box to a point inside it: distance and outward normal.
// Ties go to the first face in the order top, bottom, left, right, so a
// point exactly at the centre of a square is pushed up.
void nearest_face(const Obstacle& box, const Vec2& c, double& distance, Vec2& normal) {
  distance = box.b.y() - c.y();
  normal = Vec2(0.0, 1.0);
  const double bottom = c.y() - box.a.y();
  if (bottom < distance) {
    distance = bottom;
    normal = Vec2(0.0, -1.0);
  }
  const double left = c.x() - box.a.x();
  if (left < distance) {
    distance = left;
    normal = Vec2(-1.0, 0.0);
  }
  const double right = box.b.x() - c.x();
  if (right < distance) {
    distance = right;
    normal = Vec2(1.0, 0.0);
  }
}

// Closest point of the segment a–b to c.
Vec2 closest_on_segment(const Vec2& a, const Vec2& b, const Vec2& c) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  if (len2 <= 0.0) return a;
  const double s = std::clamp((c - a).dot(ab) / len2, 0.0, 1.0);
  return a + s * ab;
}

// Unit vector from q to c; when they coincide, the segment's left normal
// (or +y for a point-like segment), so the push-out direction stays defined.
Vec2 away_from(const Vec2& c, const Vec2& q, const Obstacle& segment, double& distance) {
  const Vec2 delta = c - q;
  distance = delta.norm();
  if (distance > 0.0) return delta / distance;
  const Vec2 ab = segment.b - segment.a;
  const double len = ab.norm();
  return len > 0.0 ? Vec2(-ab.y() / len, ab.x() / len) : Vec2(0.0, 1.0);
}

bool inside_box(const Obstacle& box, const Vec2& c) {
  return c.x() > box.a.x() && c.x() < box.b.x() && c.y() > box.a.y() && c.y() < box.b.y();
}

}  // namespace

bool disc_contact(const Obstacle& o, const Vec2& centre, double radius, ObstacleContact& out) {
  if (o.shape == ObstacleShape::Box) {
    const Vec2 q(std::clamp(centre.x(), o.a.x(), o.b.x()),
                 std::clamp(centre.y(), o.a.y(), o.b.y()));
    const Vec2 delta = centre - q;
    const double d2 = delta.squaredNorm();
    if (d2 >= radius * radius) return false;
    if (d2 > 0.0) {
      const double distance = std::sqrt(d2);
      out.depth = radius - distance;
      out.normal = delta / distance;
    } else {  // centre inside (or on) the box
      double face = 0.0;
      nearest_face(o, centre, face, out.normal);
      out.depth = radius + face;
    }
  } else {
    const Vec2 q = closest_on_segment(o.a, o.b, centre);
    double distance = 0.0;
    const Vec2 n = away_from(centre, q, o, distance);
    const double depth = radius + o.radius - distance;
    if (depth <= 0.0) return false;
    out.depth = depth;
    out.normal = n;
  }
  out.r = -radius * out.normal;
  return true;
}

bool point_contact(const Obstacle& o, const Vec2& c, ObstacleContact& out) {
  if (o.shape == ObstacleShape::Box) {
    if (!inside_box(o, c)) return false;
    nearest_face(o, c, out.depth, out.normal);
    return out.depth > 0.0;
  }
  const Vec2 q = closest_on_segment(o.a, o.b, c);
  double distance = 0.0;
  const Vec2 n = away_from(c, q, o, distance);
  const double depth = o.radius - distance;
  if (depth <= 0.0) return false;
  out.depth = depth;
  out.normal = n;
  return true;
}

double signed_distance(const Obstacle& o, const Vec2& c, Vec2& normal) {
  if (o.shape == ObstacleShape::Box) {
    const Vec2 q(std::clamp(c.x(), o.a.x(), o.b.x()), std::clamp(c.y(), o.a.y(), o.b.y()));
    const Vec2 delta = c - q;
    const double d2 = delta.squaredNorm();
    if (d2 > 0.0) {
      const double distance = std::sqrt(d2);
      normal = delta / distance;
      return distance;
    }
    double face = 0.0;
    nearest_face(o, c, face, normal);
    return -face;
  }
  const Vec2 q = closest_on_segment(o.a, o.b, c);
  double distance = 0.0;
  normal = away_from(c, q, o, distance);
  return distance - o.radius;
}

int obstacle_vertices(const Obstacle& o, Vec2 (&vertices)[4], double& radius) {
  if (o.shape == ObstacleShape::Box) {
    radius = 0.0;
    vertices[0] = o.a;
    vertices[1] = Vec2(o.b.x(), o.a.y());
    vertices[2] = o.b;
    vertices[3] = Vec2(o.a.x(), o.b.y());
    return 4;
  }
  radius = o.radius;
  vertices[0] = o.a;
  vertices[1] = o.b;
  return o.a == o.b ? 1 : 2;  // a round post has one cap
}

bool vertex_part_contact(const Vec2& v, double radius, const Vec2& p, double ct, double st,
                         const PartOutline& part, ObstacleContact& out) {
  // The vertex in the part's frame: u = Rᵀ(v − p) − centre.
  const double wx = v.x() - p.x(), wy = v.y() - p.y();
  const double ux = ct * wx + st * wy - part.centre.x();
  const double uy = -st * wx + ct * wy - part.centre.y();
  const double ax = std::abs(ux) - part.hx;  // > 0: beyond a side edge
  const double ay = std::abs(uy) - part.hy;  // > 0: beyond the top or bottom edge
  // m: the outward normal of the part's touched edge, part frame; depth along it.
  double mx = 0.0, my = 0.0, depth = 0.0;
  if (ax < 0.0 && ay < 0.0) {  // inside: the nearest edge, top/bottom first on a tie
    if (ay >= ax) {
      my = uy >= 0.0 ? 1.0 : -1.0;
      depth = radius - ay;
    } else {
      mx = ux >= 0.0 ? 1.0 : -1.0;
      depth = radius - ax;
    }
  } else if (ax < 0.0) {  // above or below the part, within its width: that edge
    my = uy >= 0.0 ? 1.0 : -1.0;
    depth = radius - ay;
  } else if (ay < 0.0) {  // beside the part, within its height: that edge
    mx = ux >= 0.0 ? 1.0 : -1.0;
    depth = radius - ax;
  } else {
    return false;  // a corner region: the body's corner carries this contact
  }
  if (!(depth > 0.0)) return false;
  // n = −R·m (out of the obstacle's vertex, into the body's edge); the contact
  // point is the vertex's deepest point in the body, v + radius·n.
  const double nx = -(ct * mx - st * my);
  const double ny = -(st * mx + ct * my);
  out.depth = depth;
  out.normal = Vec2(nx, ny);
  out.r = Vec2(wx + radius * nx, wy + radius * ny);
  return true;
}

}  // namespace contact2d
