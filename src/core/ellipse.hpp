// The ellipse's contact geometry: where a smooth convex outline touches the
// ground or an obstacle (shape_features(Shape::Ellipse).smooth).
//
// The body frame's ellipse has semi-axis a along x and b along y:
//   e_b(φ) = (a·cos φ, b·sin φ),  world  e(φ) = p + R(θ)·e_b(φ).
// Unlike a box corner, no material point of the rim is "the" contact point:
// the rim rolls and slides over the surface, and the point it touches moves
// over the rim as the body turns.
//
// Ground (y = 0, normal +y). The lowest point of the rim is the support
// point in direction −y. With A = R·diag(a², b²)·Rᵀ, the support point of an
// ellipse in the unit direction u is p + A·u/√(uᵀA·u), so with u = −e_y,
// s = sin θ, c = cos θ:
//   h(θ)  = √(a²·s² + b²·c²)              height of the centre above its lowest point
//   r     = (−(a² − b²)·s·c / h, −h)       lever arm: lowest point − centre
//   d     = h(θ) − y                        depth (a contact when d > 0)
// The penalty energy ½·k·d² is a function of the configuration, and by the
// envelope theorem ∂d/∂θ = −r_x (the rim's own sliding is along the
// tangent, perpendicular to n): the force k·d·n at the point r has exactly
// the torque −∂(½·k·d²)/∂θ = r_x·k·d, so the spring is conservative and
// energy() counts it like every other. The contact point's velocity is the
// material velocity of the body at r, v_c = v + ω × r, as for a corner:
// friction acts on the slip of the body where it touches.
//
// For the converged reference (its switching function's rate), the lever
// arm's turn rate along θ (a point fixed in the body would give −r_y):
//   dr_x/dθ = −(a² − b²)·cos 2θ / h + r_x² / h,    dr_y/dθ = r_x.
//
// Obstacle. The contact is the rim's deepest point inside the obstacle:
// φ* minimises f(φ) = sd(e(φ)), the obstacle's signed distance
// (core/obstacles.hpp), and the contact has d = −f(φ*) > 0, normal n = the
// outward normal of the obstacle's surface nearest e(φ*), lever arm
// r = e(φ*) − p. The same envelope argument makes it conservative. The box
// and the capsule are convex, as is the ellipse, so the rim's part inside
// the obstacle is one arc and f has one minimum on it; it is found by
// sampling the rim at kRimSamples angles and narrowing the best sample's
// bracket by golden section to 1e-12 rad (f is only piecewise smooth inside
// a box, where the nearest face changes, so no derivative is used). An
// obstacle farther from the centre than max(a, b) is skipped at once.
// As for every penalty contact without memory, an obstacle thinner than
// twice the depth may be passed through.
#pragma once

#include "core/body.hpp"
#include "core/obstacles.hpp"

namespace contact2d {

// The rim samples of the obstacle search (see above).
inline constexpr int kRimSamples = 32;

// Lever arm r (lowest point − centre, world frame) of an ellipse with
// semi-axes a (body x), b (body y) at orientation θ; its depth below the
// ground is −(p_y + r_y).
Vec2 ellipse_lowest_point(double a, double b, double theta);

// dr_x/dθ of ellipse_lowest_point (dr_y/dθ is r_x).
double ellipse_lowest_point_turn_rate(double a, double b, double theta);

// Contact of the ellipse (semi-axes a, b; centre p; orientation (ct, st) =
// (cos θ, sin θ)) with one obstacle: the rim's deepest point inside it.
// False when the rim is nowhere inside.
bool ellipse_obstacle_contact(const Obstacle& obstacle, double a, double b, const Vec2& p,
                              double ct, double st, ObstacleContact& out);

// Inertia of a uniform elliptical plate about its centre: m·(a² + b²)/4.
double ellipse_plate_inertia(double mass, double a, double b);

}  // namespace contact2d
