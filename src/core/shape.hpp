// The four shapes of a body and the one table of what each of them has.
//
// A scene names its body's shape (point_mass, box, tshape, circle, ellipse) and the
// body carries it (core/body.hpp). The code that treats shapes differently
// does not ask which shape it holds, nor infers it from a field's value (a
// radius > 0, an empty part list): it asks `shape_features(shape)` for the
// one property it depends on. `shape_features` is a switch with a case for
// every enumerator and no default, so a new shape does not compile without
// warnings (-Wswitch) until its row is written; the few places that need
// more than a feature (a shape's own keys in a scene file, its mass
// properties, its MuJoCo geoms) are switches without default too.
//
// The features, and where the code branches on them:
//
//   turns     θ is a degree of freedom: the body has an inertia about its
//             COM, the force stage turns torque into an angular
//             acceleration and the initial state may have θ, ω ≠ 0
//             (scene validation, the scene file's theta/omega keys, the
//             MuJoCo model's hinge, the converged reference's
//             dimension). A point mass does not turn.
//   rolls     the body is a disc: its one contact point stays below the
//             centre whatever θ is (the point does not turn with the body),
//             it meets obstacles with its whole rim (disc_contact, not
//             point_contact). Its rolling resistance is `resists_rolling`.
//   corners   the contact points are the corners of rectangular outlines
//             with edges, turning with the body: obstacles' corners and
//             round ends are tested against those edges, and MuJoCo can
//             model each outline as a box geom (--mapping …:boxes).
//   compound  the body is a list of parts ([[body.parts]] in a scene file):
//             its mass, COM and inertia come from the parts, not from the
//             scene's mass.
//   smooth    the outline is a smooth convex curve (the ellipse) whose
//             contact point is not fixed in the body: against the ground it
//             is the outline's support point, the lowest point of the rim at
//             the body's θ, which slides over the rim as the body turns;
//             against an obstacle it is the rim's deepest point inside it
//             (core/ellipse.hpp). The force stage and the converged
//             reference read the point from there, not from `points`.
//   resists_rolling
//             a law with μ_roll > 0 adds the rolling-resistance torque
//             −μ_roll·Fn·tanh(α·R·ω) at each contact (the disc and the
//             ellipse; R is the body's `roll_radius`), and MuJoCo models it
//             with condim 6.
#pragma once

#include <array>
#include <optional>
#include <string_view>

namespace contact2d {

enum class Shape { PointMass, Box, TShape, Circle, Ellipse };

inline constexpr std::array kAllShapes = {Shape::PointMass, Shape::Box, Shape::TShape,
                                          Shape::Circle, Shape::Ellipse};

struct ShapeFeatures {
  bool turns = false;
  bool rolls = false;
  bool corners = false;
  bool compound = false;
  bool smooth = false;
  bool resists_rolling = false;
};

constexpr ShapeFeatures shape_features(Shape shape) {
  switch (shape) {
    //                     turns  rolls  corners compound smooth resists_rolling
    case Shape::PointMass: return {false, false, false, false, false, false};
    case Shape::Box: return {true, false, true, false, false, false};
    case Shape::TShape: return {true, false, true, true, false, false};
    case Shape::Circle: return {true, true, false, false, false, true};
    case Shape::Ellipse: return {true, false, false, false, true, true};
  }
  return {};
}

// The scene file's name of a shape: "point_mass", "box", "tshape", "circle", "ellipse".
constexpr std::string_view shape_name(Shape shape) {
  switch (shape) {
    case Shape::PointMass: return "point_mass";
    case Shape::Box: return "box";
    case Shape::TShape: return "tshape";
    case Shape::Circle: return "circle";
    case Shape::Ellipse: return "ellipse";
  }
  return "?";
}

// The shape of a scene file's name; nothing for an unknown name.
constexpr std::optional<Shape> parse_shape(std::string_view name) {
  for (Shape shape : kAllShapes) {
    if (shape_name(shape) == name) return shape;
  }
  return std::nullopt;
}

}  // namespace contact2d
