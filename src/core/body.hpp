// Planar rigid body: mass properties and the body-fixed contact points.
//
// The four scenes of the course (point mass, box, compound T, rolling circle)
// are one body type with different data, tagged with its Shape; what each
// shape has (turns, rolls, corners, parts) is `shape_features`
// (core/shape.hpp), and `rotates`, `points_rotate` are its turns and
// !rolls, set by the make_* functions:
//   point mass  rotates = false, one point (0, -h)
//   box         rotates = true,  four corners
//   compound    rotates = true,  every vertex of every part, relative to the COM
//   circle      rotates = true,  one point (0, -R) that stays below the centre
//               (points_rotate = false) plus rolling resistance
//   ellipse     rotates = true,  semi-axes (a, b); its contact point is the
//               rim's support point, computed from θ by the contact stage
//               (core/ellipse.hpp); `points` holds the lowest point at θ = 0,
//               (0, −b), for the code that only needs a point of the body
//
// A box and every part of a compound also keep their outline: an axis-aligned
// rectangle in the body frame (centre relative to the COM, half extents),
// rotated with the body by R(θ). The contact stage tests the obstacles'
// corners and round ends against these outlines (core/contacts.hpp). The
// point mass and the circle have none (no edges; the circle meets obstacles
// with its whole disc).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/shape.hpp"

namespace contact2d {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

// One rectangular part of a compound body; (x, y) is its centre in the
// body's construction frame (not necessarily the COM frame).
struct BoxPart {
  double width = 0.0;
  double height = 0.0;
  double x = 0.0;
  double y = 0.0;
  double mass = 0.0;
};

// The outline of one convex part: the rectangle |u_x| ≤ hx, |u_y| ≤ hy
// around `centre`, in the body frame with the COM at the origin.
struct PartOutline {
  Vec2 centre = Vec2::Zero();  // relative to the COM, body frame
  double hx = 0.0;             // half width
  double hy = 0.0;             // half height
};

struct RigidBody {
  Shape shape = Shape::Box;  // what the body has: shape_features(shape)
  double mass = 1.0;
  double inertia = 0.0;       // about the COM, kg·m² (0 when rotates = false)
  bool rotates = true;        // false: θ and ω stay 0 (point mass)
  bool points_rotate = true;  // false: points keep their world-frame offset (circle)
  double roll_radius = 0.0;   // the rolling tanh's length R (disc: its radius; ellipse: √(a·b))
  Vec2 semi_axes = Vec2::Zero();   // the ellipse's (a, b): a along the body's x; else 0
  std::vector<Vec2> points;        // contact points relative to the COM, body frame
  std::vector<PartOutline> parts;  // convex outlines with edges (box, compound); else empty
  Vec2 com_offset = Vec2::Zero();  // COM in the construction frame (compound only)
};

// Mass, COM and inertia about the COM of a set of box parts:
//   M = Σ m_j,  COM = Σ m_j p_j / M,  I = Σ (m_j (w_j² + h_j²)/12 + m_j |p_j − COM|²).
struct MassProperties {
  double mass = 0.0;
  Vec2 com = Vec2::Zero();
  double inertia = 0.0;
};
MassProperties compound_mass_properties(const std::vector<BoxPart>& parts);

RigidBody make_point_mass(double mass, double half_height);
RigidBody make_box(double mass, double width, double height);
RigidBody make_compound(const std::vector<BoxPart>& parts);
RigidBody make_circle(double mass, double radius);
// An ellipse of semi-axes a (body x) and b (body y); `inertia` about its
// centre (a uniform plate's m·(a² + b²)/4 unless the caller measured another).
RigidBody make_ellipse(double mass, double a, double b, double inertia);

// Smallest effective mass a single contact point can present along the
// normal, over all orientations: 1/m_eff = 1/m + |r|²/I. Used for stability
// bounds (ω = √(k/m_eff)) and diagnostics.
double min_effective_mass(const RigidBody& body);

// Largest distance of a contact point from the COM (a length scale of the body).
double body_extent(const RigidBody& body);

}  // namespace contact2d
