// Static obstacles: fixed geometry the body touches with the ground's contact
// law (docs/physics.md) or with the obstacle's own k, c, μ, … (ContactOverride), applied along the
// normal n out of the touched surface instead of +y. This file is the geometry (depth and normal of
// one point or disc against one obstacle, of one obstacle vertex against one part of the body);
// core/contacts.hpp enumerates the contacts and core/dynamics.hpp
// applies the law to them.
//
// Two shapes, both general (the game's crossbar, goal roof and back wall are
// just boxes in its scene file):
//   box      axis-aligned, corners lo and hi
//   segment  the points within `radius` of the segment a–b (a capsule; a
//            round post when a = b)
//
// For one contact with penetration d > 0, normal n out of the touched
// surface, tangent t = (n_y, −n_x) (t = +x on a floor facing up, as for the
// ground) and contact point c at offset r = c − p from the COM:
//   v_c = v + ω·(−r_y, r_x),  v_n = v_c·n,  v_t = v_c·t
//   Fn  = the ground's normal law with depth d and normal velocity v_n
//   Ft  = −μ·Fn·tanh(α·v_t)
//   F   = Fn·n + Ft·t,  τ += r × F,  and for a rolling body
//   τ  += −μ_roll·Fn·tanh(α·R·ω)   (the ground's regularised rolling resistance)
//
// Which features touch:
//   * a body with a rolling radius R (the circle) uses its true disc: the
//     closest point q of the obstacle to the centre, d = R − |p − q|,
//     n = (p − q)/|p − q|, c = p − R·n. (The ground keeps the model's single point
//     below the centre; against a flat top face the two agree exactly.) A
//     centre inside a box is pushed out through the nearest face, with
//     d = R + its distance to that face (continuous with the outside formula).
//   * every other body uses its contact points, like the ground: a point
//     inside a box is pushed out through the nearest face (d = distance to
//     it); a point within a segment's radius is pushed away from the segment.
//   * and, both ways, the obstacle's vertices against the edges of a body
//     with an outline (a box, every part of a compound: core/body.hpp), so
//     that no edge passes a corner (a plank across a thin post). The vertices
//     are a box's four corners (radius ρ = 0) and a segment's two ends, round
//     caps of radius ρ = the segment's radius (one cap when a = b).
//
// An obstacle vertex v against one part, the rectangle |u_x| ≤ hx, |u_y| ≤ hy
// of the body frame around the part's centre c_j (relative to the COM):
//   u   = R(θ)ᵀ·(v − p) − c_j                     v in the part's frame
//   a_x = |u_x| − hx,  a_y = |u_y| − hy           > 0: beyond that pair of edges
//   inside (a_x, a_y < 0): the nearest edge, m = (0, sgn u_y) with
//           d = ρ − a_y when −a_y ≤ −a_x (top/bottom first on a tie), else
//           m = (sgn u_x, 0) with d = ρ − a_x
//   above/below the part (a_x < 0 ≤ a_y): m = (0, sgn u_y), d = ρ − a_y
//   beside it           (a_y < 0 ≤ a_x): m = (sgn u_x, 0), d = ρ − a_x
//   a corner region (a_x, a_y ≥ 0): no contact from v (see below)
// and a contact when d > 0. m is the outward normal of the touched edge in the
// part's frame. The force pushes the body away from the vertex, along −R·m,
// so the contact stores n = −R(θ)·m: the unit normal out of the touched
// surface (the vertex), exactly as for a body point in an obstacle. The
// contact point is the vertex's deepest point in the body, c = v + ρ·n, so
// r = c − p, and its velocity is the body's, v_c = v + ω·(−r_y, r_x) (the
// obstacle is static): the law above applies unchanged. Each such spring is
// conservative: ∂d/∂p = R·m and ∂d/∂θ = −(r × R·m), so −k·d·∇d is the force
// k·d·n at c with torque r × (k·d·n) (a shift of c along n does not change
// the torque), and energy() counts it as ½·k·d², like every contact.
//
// No double counting: each pair of overlapping features is one spring, and
// no pair is counted twice.
//   * A body corner inside an obstacle and an obstacle corner inside the
//     body (two boxes overlapping corner to corner, a box bridging a gap)
//     are two different pairs, the two ends of the overlap: each carries its
//     own spring. This is what the body's corners already do on a flat face
//     (each end of the contact patch carries a spring). When a body slides
//     over an obstacle's edge, the support passes from the obstacle's corner
//     (in the body) to the body's corner (in the obstacle) as the two corners
//     cross; both depths are continuous and 0 at the crossing (within a
//     static deflection of it the nearest edge of each is the side one, a
//     sideways push of at most k·d).
//   * A body corner within ρ of a cap's centre while the cap's centre lies in
//     that corner's region of the part is one pair (corner, cap): the body
//     corner's contact with the segment already carries it (same depth, same
//     normal when the cap is the closest part of the segment), so the cap
//     makes no contact in a corner region. The price: when the cap's centre
//     crosses from an edge's region into a corner's region, its edge spring
//     (depth ρ − the distance to the edge's line) stops at once while the
//     corner's spring goes on: a jump of at most k·ρ in the force, where a
//     body's end slides off a round end (a sharp corner, ρ = 0, has none).
//   * Each part of a compound is tested on its own: a vertex inside two
//     overlapping parts makes two springs, and an inner edge between parts
//     can be the nearest one (the body's own corners behave the same way).
//
// An edge cannot pass a corner: a plank dropped across a thin post
// rests on the post's corners or cap (tests/core/test_obstacle_edges.cpp).
// What still holds is the depth rule of any penalty contact without memory:
// a vertex that sinks more than halfway into a thin box, or into a body's
// thin part, finds the far edge nearer and is pushed out through it. The
// depth a body reaches is about v/√(k/m), so obstacles and bodies should be
// thicker than twice that at the speeds of the scene.
#pragma once

#include <string_view>
#include <vector>

#include <optional>

#include "core/body.hpp"
#include "core/contact.hpp"

namespace contact2d {

enum class ObstacleShape { Box, Segment };

// An obstacle's own contact law: each key it sets replaces the scene's
// [contact] value, each key it leaves unset follows the scene's (also when a
// sweep or --set changes the scene's), so a goal's net can be soft and
// absorbing while its crossbar keeps the scene's hard law.
struct ContactOverride {
  std::optional<double> k, c, mu, alpha, mu_roll, mu_torsion;
  std::optional<DampingLaw> damping;

  bool any() const { return k || c || mu || alpha || mu_roll || mu_torsion || damping; }
  ContactParams apply(ContactParams base) const {
    if (k) base.k = *k;
    if (c) base.c = *c;
    if (mu) base.mu = *mu;
    if (alpha) base.alpha = *alpha;
    if (mu_roll) base.mu_roll = *mu_roll;
    if (mu_torsion) base.mu_torsion = *mu_torsion;
    if (damping) base.damping = *damping;
    return base;
  }
};

struct Obstacle {
  ObstacleShape shape = ObstacleShape::Box;
  Vec2 a = Vec2::Zero();    // box: lower-left corner lo; segment: first end
  Vec2 b = Vec2::Zero();    // box: upper-right corner hi; segment: second end
  double radius = 0.0;      // segment: half thickness (≥ 0); box: unused
  ContactOverride contact;  // unset keys: the scene's [contact]
  // Kinematic (the game's keeper): a Stepper moves it between steps
  // (Stepper::move_obstacle); on MuJoCo it is a mocap body. Static otherwise.
  bool moves = false;
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

// Signed distance of the world point c from the obstacle's surface: < 0
// inside (minus the distance to the nearest face of a box, the depth into a
// capsule), > 0 outside; `normal` is the unit direction out of the surface
// nearest c (the gradient of the distance where it has one).
double signed_distance(const Obstacle& obstacle, const Vec2& c, Vec2& normal);

// The vertices an obstacle presses into a body's edges: a box's four corners
// (radius 0) or a segment's ends, round caps of the segment's radius (one cap
// when a = b). Returns how many of `vertices` it wrote.
int obstacle_vertices(const Obstacle& obstacle, Vec2 (&vertices)[4], double& radius);

// Contact of one obstacle vertex v (a cap of `radius`, 0 for a corner) with
// one part outline of a body at position p and orientation (ct, st) =
// (cos θ, sin θ); false when apart or when v lies in a corner region of the
// part. out.normal points out of the vertex into the body (−R·m), out.r is
// the contact point v + radius·n minus the COM. The math is in the header
// comment above.
bool vertex_part_contact(const Vec2& v, double radius, const Vec2& p, double ct, double st,
                         const PartOutline& part, ObstacleContact& out);

}  // namespace contact2d
