// Static obstacles: fixed geometry the body touches with the ground's contact
// law (SPEC §2), applied along the obstacle's outward normal n instead of +y.
// This file is the geometry (depth and normal of one point or disc against one
// obstacle); core/contacts.hpp enumerates the contacts and core/dynamics.hpp
// applies the law to them.
//
// Two shapes, both general (the game's crossbar, goal roof and back wall are
// just boxes in its scene file):
//   box      axis-aligned, corners lo and hi
//   segment  the points within `radius` of the segment a–b (a capsule; a
//            round post when a = b)
//
// For one contact with penetration d > 0, outward normal n, tangent
// t = (n_y, −n_x) (t = +x on a floor facing up, as for the ground) and
// contact point c at offset r = c − p from the COM:
//   v_c = v + ω·(−r_y, r_x),  v_n = v_c·n,  v_t = v_c·t
//   Fn  = the ground's normal law with depth d and normal velocity v_n
//   Ft  = −μ·Fn·tanh(α·v_t)
//   F   = Fn·n + Ft·t,  τ += r × F,  and for a rolling body
//   τ  += −μ_roll·Fn·tanh(α·R·ω)   (the ground's regularised rolling resistance)
//
// Which points touch:
//   * a body with a rolling radius R (the circle) uses its true disc: the
//     closest point q of the obstacle to the centre, d = R − |p − q|,
//     n = (p − q)/|p − q|, c = p − R·n. (The ground keeps SPEC's single point
//     below the centre; against a flat top face the two agree exactly.) A
//     centre inside a box is pushed out through the nearest face, with
//     d = R + its distance to that face (continuous with the outside formula).
//   * every other body uses its contact points, like the ground: a point
//     inside a box is pushed out through the nearest face (d = distance to
//     it); a point within a segment's radius is pushed away from the segment.
//
// Penalty contact has no memory: a point that passes more than halfway
// through a thin box in one step is pushed out of the far side. The depth a
// body reaches is about v/√(k/m), so obstacles should be thicker than twice
// that at the speeds of the scene.
#pragma once

#include <string_view>
#include <vector>

#include "core/body.hpp"

namespace contact2d {

enum class ObstacleShape { Box, Segment };

struct Obstacle {
  ObstacleShape shape = ObstacleShape::Box;
  Vec2 a = Vec2::Zero();  // box: lower-left corner lo; segment: first end
  Vec2 b = Vec2::Zero();  // box: upper-right corner hi; segment: second end
  double radius = 0.0;    // segment: half thickness (≥ 0); box: unused
};

// A box from its centre and size (width, height > 0).
Obstacle make_box_obstacle(double x, double y, double width, double height);
// A segment (capsule) from its ends and half thickness.
Obstacle make_segment_obstacle(const Vec2& a, const Vec2& b, double radius);

std::string_view obstacle_shape_name(ObstacleShape shape);  // "box", "segment"

// One contact: penetration depth > 0, unit outward normal of the obstacle,
// and the contact point's offset from the COM (world frame).
struct ObstacleContact {
  double depth = 0.0;
  Vec2 normal = Vec2(0.0, 1.0);
  Vec2 r = Vec2::Zero();
};

// Contact of a disc (centre, radius) with the obstacle; false when apart.
bool disc_contact(const Obstacle& obstacle, const Vec2& centre, double radius,
                  ObstacleContact& out);
// Contact of a point at world position c with the obstacle (out.r is left
// for the caller); false when outside.
bool point_contact(const Obstacle& obstacle, const Vec2& c, ObstacleContact& out);

}  // namespace contact2d
