#include "mujoco/mjcf.hpp"

#include "core/format.hpp"

#include <tinyxml2.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <initializer_list>
#include <sstream>
#include <string>
#include <vector>

#include "core/input_error.hpp"
#include "mujoco/model.hpp"

namespace contact2d::mujoco {
namespace {

using tinyxml2::XMLDocument;
using tinyxml2::XMLElement;

std::string join(std::initializer_list<double> values) {
  std::string text;
  for (double v : values) text += (text.empty() ? "" : " ") + format_exact(v);
  return text;
}

template <size_t N>
std::string join(const std::array<double, N>& values) {
  std::string text;
  for (double v : values) text += (text.empty() ? "" : " ") + format_exact(v);
  return text;
}

// A geom in the body frame (MuJoCo x, z = 2D x, y).
struct Geom {
  std::string name;
  std::string type;  // "sphere" or "box"
  std::string size;
  double x = 0.0;
  double z = 0.0;
  bool visual = false;  // contype = conaffinity = 0: drawn, never touches
  bool corner = false;  // a corner sphere (its lowest point is kCornerRadius below the 2D point)
};

struct Layout {
  double mass = 0.0;
  std::array<double, 3> inertia{};  // diaginertia about MuJoCo x, y (hinge), z
  bool hinge = true;
  // compensated: the lever of the massless body "contacts" that carries the
  // contact geoms (0: none, the geoms are on the body itself), and for the
  // point mass a hinge about MuJoCo z ("spin") that turns that body; no
  // contact force has a moment about z, so it never moves.
  double lever = 0.0;
  bool spin = false;
  Version version = Version::V2;
  bool pairs_with_ground = false;  // the friction damper: the ground through <pair>s
  std::vector<Geom> geoms;
  int max_contacts = 0;      // P: contacts the body can make with the ground
  int obstacles = 0;         // N: static obstacles of the scene
  std::string contacts_why;  // how P is counted, for the header
};

std::vector<BoxPart> parts_of(const Scene& scene) {
  switch (scene.shape) {
    case Shape::Box: return {BoxPart{scene.width, scene.height, 0.0, 0.0, scene.mass}};
    case Shape::TShape: return scene.parts.empty() ? default_tshape_parts() : scene.parts;
    case Shape::PointMass:
    case Shape::Circle:
    case Shape::Ellipse: break;  // no rectangular outline
  }
  return {};
}

// MuJoCo rejects a moving body with a principal inertia below mjMINVAL or with
// A + B < C in any order (compared exactly). Only the hinge axis (MuJoCo y) is
// physics; the other two carry no joint and are raised just enough to pass: a
// thin part makes them smaller than mjMINVAL, and rounding can make the
// prism's Ix + Iz = Iy + Σ m·D²/6 fall short of Iy when D is small (exactly,
// Ix ≤ Iy and Iz ≤ Iy, so a larger value is rounding too).
std::array<double, 3> loadable_inertia(std::array<double, 3> inertia) {
  double& x = inertia[0];
  const double y = inertia[1];
  double& z = inertia[2];
  x = std::clamp(x, mjMINVAL, std::max(y, mjMINVAL));
  z = std::clamp(z, mjMINVAL, std::max(y, mjMINVAL));
  if (x + z < y) (x < z ? z : x) = y;
  return inertia;
}

// Prism of depth D: inertia about MuJoCo x (lever arms in z) and z (in x).
Layout box_layout(const Scene& scene, Geometry geometry) {
  const std::vector<BoxPart> parts = parts_of(scene);
  const MassProperties props = compound_mass_properties(parts);
  double depth = INFINITY;
  for (const BoxPart& p : parts) depth = std::min({depth, p.width, p.height});
  Layout layout;
  layout.mass = props.mass;
  double ix = 0.0, iz = 0.0;
  for (size_t i = 0; i < parts.size(); ++i) {
    const BoxPart& p = parts[i];
    const double dx = p.x - props.com.x(), dz = p.y - props.com.y();
    ix += p.mass * ((p.height * p.height + depth * depth) / 12.0 + dz * dz);
    iz += p.mass * ((p.width * p.width + depth * depth) / 12.0 + dx * dx);
    const bool visual = geometry == Geometry::CornerSpheres;
    Geom part{(visual ? "visual_part" : "part") + std::to_string(i) + "_box",
              "box",
              join({p.width / 2, depth / 2, p.height / 2}),
              dx,
              dz,
              visual};
    layout.geoms.push_back(part);
  }
  layout.inertia = loadable_inertia({ix, props.inertia, iz});
  if (geometry == Geometry::BoxGeoms) {
    layout.max_contacts = 4 * static_cast<int>(parts.size());
    layout.contacts_why = "4 per part box: MuJoCo's box-plane collision returns up to 4";
    return layout;
  }
  const RigidBody body = make_compound(parts);
  for (size_t i = 0; i < body.points.size(); ++i) {
    layout.geoms.push_back({"corner" + std::to_string(i), "sphere", format_exact(kCornerRadius),
                            body.points[i].x(), body.points[i].y(), false, true});
  }
  layout.max_contacts = static_cast<int>(body.points.size());
  layout.contacts_why = "one per corner sphere";
  return layout;
}

// The contact point (0, −h) is a sphere of radius ε = kCornerRadius whose
// lowest point it is, as a box's corners are: a sphere of radius h about the
// COM has the same lowest point on flat ground, but against a slope or an
// obstacle's edge it touches elsewhere than (0, −h) (on a 30° slope it
// started 6.7 mm inside, h = 5 cm; under a box's corner it struck where the
// 2D point passes). A visual sphere of radius h draws the body.
Layout point_mass_layout(const Scene& scene) {
  const double rho = kCornerRadius;
  // No hinge: the inertia is never used; it is a solid sphere's, of a radius
  // of at least 1 cm, and at least mjMINVAL (MuJoCo's check on moving bodies,
  // which a light mass, < 2.5e-11 kg, would fail).
  const double r_inertia = std::max(scene.half_height, 0.01);
  const double i = std::max(0.4 * scene.mass * r_inertia * r_inertia, mjMINVAL);
  Layout layout;
  layout.mass = scene.mass;
  layout.inertia = {i, i, i};
  layout.hinge = false;
  layout.geoms.push_back(
      {"contact_point", "sphere", format_exact(rho), 0.0, rho - scene.half_height, false});
  if (scene.half_height > rho)
    layout.geoms.push_back(
        {"visual_point", "sphere", format_exact(scene.half_height), 0.0, 0.0, true});
  layout.max_contacts = 1;
  layout.contacts_why = "one sphere";
  return layout;
}

Layout circle_layout(const Scene& scene) {
  const double m = scene.mass, r = scene.radius;
  const double side = 0.25 * m * r * r + m * (2 * r) * (2 * r) / 12.0;
  Layout layout;
  layout.mass = m;
  layout.inertia = {side, 0.5 * m * r * r, side};
  layout.geoms.push_back({"disc", "sphere", format_exact(r), 0.0, 0.0, false});
  layout.max_contacts = 1;
  layout.contacts_why = "one sphere";
  return layout;
}

// An ellipsoid of semi-axes a (MuJoCo x), min(a, b) (MuJoCo y, out of the
// plane: the body never tilts about x, so its lowest point and its contact
// with a plane lie in the x–z section whatever this axis is) and b (MuJoCo
// z). The inertia about the hinge is the scene's own, written explicitly
// (MuJoCo would compute a solid ellipsoid's m(a² + b²)/5 from the geom);
// the other two carry no joint and are only made loadable.
Layout ellipse_layout(const Scene& scene) {
  const RigidBody body = make_body(scene);
  const double m = scene.mass, a = scene.a, b = scene.b;
  Layout layout;
  layout.mass = m;
  layout.inertia = loadable_inertia({0.25 * m * b * b, body.inertia, 0.25 * m * a * a});
  layout.geoms.push_back(
      {"ellipse", "ellipsoid", join(std::array{a, std::min(a, b), b}), 0.0, 0.0, false});
  layout.max_contacts = 1;
  // The ground: mjc_PlaneConvex, one contact at the support point (exact,
  // as core/ellipse.hpp's; tests/mujoco/test_ellipse_mujoco.cpp). An
  // obstacle: MuJoCo's general convex collision, one contact per pair too,
  // but its point is approximate (at 5 mm into a box up to 2.0 mm off the
  // rim's deepest point on 2.2.2, 0.57 mm on 3.14).
  layout.contacts_why =
      "one ellipsoid: the plane gives one contact at its support point; an obstacle one per pair "
      "(MuJoCo's convex collision, whose point is approximate)";
  return layout;
}

Layout shape_layout(const Scene& scene, Geometry geometry) {
  switch (scene.shape) {
    case Shape::PointMass: return point_mass_layout(scene);
    case Shape::Circle: return circle_layout(scene);
    case Shape::Ellipse: return ellipse_layout(scene);
    case Shape::Box:
    case Shape::TShape: return box_layout(scene, geometry);
  }
  return {};
}

Layout make_layout(const Scene& scene, Geometry geometry, Mapping mapping, Version version) {
  Layout layout = shape_layout(scene, geometry);
  layout.obstacles = static_cast<int>(scene.obstacles.size());
  layout.version = version;
  // MuJoCo 3 gives a body with only slide joints body_invweight0 = 1/m
  // (engine_setconst.c, body_simple == 2), 2.2.2 the mean of the diagonal,
  // 2/(3m) for the x–z pair: the hinge "spin", which no contact force turns,
  // makes the point mass a general body on both, with 2.2.2's Â.
  if (version == Version::V3) layout.spin = !layout.hinge;
  if (mapping == Mapping::Compensated) {
    // The point mass gets a hinge about MuJoCo z (its inertia is inertia[2]);
    // the others turn the contacts' body with their own hinge (inertia[1]).
    layout.spin = !layout.hinge;
    const double turning = layout.spin ? layout.inertia[2] : layout.inertia[1];
    layout.lever =
        compensating_lever(layout.mass, turning, 1.0 / min_effective_mass(make_body(scene)));
  }
  return layout;
}

// Rows of the constraint Jacobian per contact of dimension `condim`: condim
// for the elliptic cone, 2·(condim − 1) for the pyramidal one (1 for a
// frictionless contact in either).
int rows_per_contact(int condim, bool elliptic) {
  if (condim == 1) return 1;
  return elliptic ? condim : 2 * (condim - 1);
}

// Room in the contact buffer for geoms a user adds to the file: this many
// geoms of up to kContactsPerAddedGeom contacts each (box–plane's maximum).
constexpr int kAddedGeoms = 10;
constexpr int kContactsPerAddedGeom = 4;

// Every contact geom of the body can touch the ground and each obstacle at
// once: P (1 + N), twice for headroom (a box geom meets a box obstacle with up
// to 8 contacts, the ground with 4).
int nconmax_of(const Layout& l) {
  return 2 * l.max_contacts * (1 + l.obstacles) + kAddedGeoms * kContactsPerAddedGeom;
}

// Rows per contact at condim 6, the most any contact needs: geoms a user
// adds may carry any condim.
int njmax_of(const Layout& l, const SolverSettings& s) {
  return rows_per_contact(6, s.elliptic) * nconmax_of(l);
}

int condim_of(const Scene& scene, const MjcfOptions& options) {
  return options.condim != 0 ? options.condim : contact_condim(scene.contact);
}

}  // namespace

// compensated's rolling coefficient for MuJoCo's elliptic cone, which
// shares one budget (f_t/μ)² + (τ/μ_roll)² ≤ f_n² between sliding and
// rolling where the reference bounds each alone: a disc rolling steadily
// against τ = μ_roll·F_n needs f_t = κ·τ/R (κ = m·R²/(I + m·R²)), so the
// torque MuJoCo leaves it is μ_roll'·F_n·√(1 − q²) with q = κ·μ_roll/(μ·R);
// μ_roll' = μ_roll/√(1 − q²) gives back μ_roll·F_n. q ≥ 1 (the disc cannot
// roll steadily: it slides) or no rolling: μ_roll as it is.
double cone_mu_roll(const Scene& scene, const SolverSettings& s) {
  return cone_mu_roll(scene, scene.contact, s);
}

double cone_mu_roll(const Scene& scene, const ContactParams& p, const SolverSettings& s) {
  // Under a cone law the scene's μ_roll is already MuJoCo's (the law is
  // MuJoCo's cone; what the diagnosis prints is μ_roll').
  if (p.friction != FrictionLaw::Tanh) return p.mu_roll;
  if (s.mapping != Mapping::Compensated || !shape_features(scene.shape).rolls ||
      !(p.mu_roll > 0.0) || !(p.mu > 0.0))
    return p.mu_roll;
  const RigidBody body = make_body(scene);
  const double r = body.roll_radius;
  const double kappa = body.mass * r * r / (body.inertia + body.mass * r * r);
  const double q = kappa * p.mu_roll / (p.mu * r);
  return q < 1.0 ? p.mu_roll / std::sqrt(1.0 - q * q) : p.mu_roll;
}

namespace {

// The 2D inertia formula of the scene's shape (the value is Layout::inertia[1]).
std::string inertia_formula(Shape shape) {
  switch (shape) {
    case Shape::Box: return "I = m (w^2 + h^2)/12";
    case Shape::TShape:
      return "I = sum over parts of m_i ((w_i^2 + h_i^2)/12 + |p_i - COM|^2), "
             "COM = sum m_i p_i / m";
    case Shape::Circle: return "I = m R^2/2";
    case Shape::Ellipse: return "I = the scene's body.inertia, or a plate's m (a^2 + b^2)/4";
    case Shape::PointMass: break;
  }
  return "";
}

std::string mapping_lines(const Scene& scene, const SolverSettings& s, int condim,
                          double model_dt) {
  const std::string in = "    ";
  std::string text = "  mapping " + std::string(mapping_name(s.mapping)) + ":\n";
  if (s.mapping == Mapping::Seed || s.mapping == Mapping::Exact) {
    text += in + (s.mapping == Mapping::Seed ? "timeconst = sqrt(m/k) = " : "timeconst = 2m/c = ") +
            format_exact(s.solref[0]) +
            " s, dampratio = c/(2 sqrt(m k)) = " + format_exact(s.solref[1]) +
            (s.mapping == Mapping::Seed
                 ? " (MuJoCo's spring (k/m)/dampratio^2 and damper (c/m)/dampratio: k/m, c/m "
                   "only at dampratio 1)\n"
                 : " (MuJoCo's spring k/m, damper c/m: the direct form -k/m, -c/m)\n");
    const double used = std::max(s.solref[0], 2.0 * scene.sim.dt);
    text += in + "MuJoCo uses timeconst max(timeconst, 2 Δt) = " + format_exact(used) +
            " s (refsafe; depends on Δt" +
            (s.refsafe_clamped ? ": here raised to 2 Δt, a softer contact than k)\n"
                               : ", here unchanged)\n");
    text += in + "solimp = " + join(s.solimp) +
            " (MuJoCo's default); cone pyramidal (MuJoCo's default); impratio 1 (MuJoCo's "
            "default)\n";
    return text;
  }
  const RigidBody body = make_body(scene);
  const ContactParams& p = scene.contact;
  if (s.mapping == Mapping::Compensated) {
    text += in + "L = " + format_exact(s.lever) +
            " m, the lever of the massless body \"contacts\" that carries the contact geoms: "
            "sqrt(I (3 G A_max - 2/m)) with G = " +
            format_exact(kCompensatingGain) +
            ", A_max = 1/m + r^2/I the largest inverse mass of a contact" +
            (!shape_features(scene.shape).turns ? " (I about the hinge \"spin\", MuJoCo z)" : "") +
            "\n";
    text += in + "A = body_invweight0 of \"contacts\" = " + format_exact(s.inv_mass) +
            " 1/kg, read from the compiled model ((2/m + L^2/I)/3 = G A_max)\n";
    text += in + "n = " + std::to_string(s.split) +
            " (MuJoCo contacts per 2D contact point: 1 for a sphere, 2 for a box geom's edge)\n";
    text += in +
            "D = d/m + (1 - d) A with d = 1e-4 (MuJoCo's divisor for a contact of inverse "
            "mass 1/m)\n";
    text += in + "solref = (-k D/n, -c D/n) = (" + format_exact(s.solref[0]) + ", " +
            format_exact(s.solref[1]) + ") (direct form)\n";
    if (cone_mu_roll(scene, s) != scene.contact.mu_roll) {
      text += in + "friction mu_roll' = mu_roll/sqrt(1 - q^2) = " +
              format_exact(cone_mu_roll(scene, s)) +
              " m, q = kappa mu_roll/(mu R), kappa = m R^2/(I + m R^2) (the elliptic cone's "
              "shared budget gives a steadily rolling disc mu_roll F_n back)\n";
    }
  } else {
    text += in + "A = body_invweight0 = " + format_exact(s.inv_mass) +
            " 1/kg, read from the compiled model (MuJoCo's mean over the three translation axes "
            "of the body's inverse mass: 2/(3m) for slides along x and z)\n";
    text += in + "n = " + std::to_string(s.split) +
            " (MuJoCo contacts per 2D contact point: 1 for a sphere, 2 for a box geom's edge)\n";
    text += in + "solref = (-k A/n, -c A/n) = (" + format_exact(s.solref[0]) + ", " +
            format_exact(s.solref[1]) + ") (direct form)\n";
  }
  text += in + "solimp = " + join(s.solimp) + " (flat minimal impedance d = 1e-4); cone elliptic\n";
  if (condim == 1) {
    text += in + "impratio: not written (condim 1 has no friction rows; MuJoCo's default 1)\n";
    return text;
  }
  const bool turns = shape_features(body.shape).turns;
  const bool rolls = shape_features(body.shape).resists_rolling && p.mu_roll > 0.0;
  if (!(p.c > 0.0)) {
    text += in + "impratio: not written (c = 0: MuJoCo's friction has no velocity term)\n";
    return text;
  }
  if (p.mu <= 0.0 && !rolls) {
    text += in +
            "impratio = 1e-15 (no sliding or rolling friction: MuJoCo's floor, which "
            "switches off the 1e-5 friction MuJoCo keeps)\n";
    return text;
  }
  if (turns) {
    text += in + "r = " + format_exact(body_extent(body)) +
            " m, the farthest contact point from the COM\n";
    text += in + "A_t = 1/m + r^2/I = ";
  } else {
    text += in + "A_t = 1/m = ";
  }
  const double r = body_extent(body);
  const double a_t = turns ? 1.0 / body.mass + r * r / body.inertia : 1.0 / body.mass;
  text += format_exact(a_t) + " 1/kg, the largest tangential inverse mass of a contact point\n";
  if (s.friction_ratio > 0.0) {
    text += in +
            "friction damper (MuJoCo 3's solreffriction on one <pair> per contact geom): N = " +
            std::to_string(resting_points(body)) +
            " points at rest, b = min(sqrt(6)/pi mu alpha m g/N, " +
            "1/(dt A_t)) = " + format_exact(s.stick_slope) +
            " N s/m per point (stick slope: the stop of tanh's law); phi = 1e3 A_t b/(R c) = " +
            format_exact(s.friction_ratio) +
            " (R = (1-d)/d A: R_t >= 1e3 A_t); impratio = b/(phi c) = " + format_exact(s.impratio) +
            "; solreffriction = (solref[0], phi solref[1]) per pair\n";
    return text;
  }
  if (p.friction != FrictionLaw::Tanh) {
    text += in + "impratio = contact.cone_ratio = " + format_exact(s.impratio) +
            " (the scene's friction law is MuJoCo's cone: its ratio is MuJoCo's impratio, and "
            "mu_roll is written as given)\n";
    return text;
  }
  text +=
      in +
      (rolls ? "impratio = min(1/(c Δt A_t), I (max(mu, 1e-5)/mu_roll)^2/(c Δt)) = "
             : "impratio = 1/(c Δt A_t) = ") +
      format_exact(s.impratio) +
      (largest_damping(scene) != p.c
           ? " with c = " + format_exact(largest_damping(scene)) +
                 " N s/m, the largest of the ground's and the obstacles' c"
           : std::string()) +
      (model_dt > 0.0 ? " with Δt = " + format_exact(model_dt) + " (--model-dt), not the timestep"
                      : std::string()) +
      " (depends on Δt; kept within [1e-15, 1e10]: the largest value at which MuJoCo's "
      "viscous friction does not reverse a slip within one step)\n";
  return text;
}

// One obstacle's contact as MuJoCo gets it: its own law (the scene's
// [contact] with the obstacle's keys applied) mapped like the ground's, set
// on an explicit <pair> with each contact geom of the body, so that MuJoCo's
// per-pair mixing of geom values plays no part.
struct ObstacleContactSettings {
  ContactParams law;
  std::array<double, 2> solref{};
  int condim = 1;
};

ObstacleContactSettings obstacle_settings(const Scene& scene, const Obstacle& o,
                                          const SolverSettings& s) {
  ObstacleContactSettings out;
  out.law = o.contact.apply(scene.contact);
  out.condim = contact_condim(out.law);
  if (s.mapping == Mapping::Calibrated || s.mapping == Mapping::Compensated) {
    const double scale = solref_scale(s);
    out.solref = {-out.law.k * scale / s.split, -out.law.c * scale / s.split};
  } else {
    Scene own = scene;
    own.contact = out.law;
    out.solref = solver_settings(own, s.mapping, s.inv_mass, s.split).solref;
  }
  return out;
}

// Half the depth (along MuJoCo y) of an obstacle's box: the body's geoms lie
// within |y| ≤ its farthest contact point (twice that, and at least 1 m).
double obstacle_half_depth(const Scene& scene) {
  return std::max(1.0, 2.0 * body_extent(make_body(scene)));
}

std::string obstacle_lines(const Scene& scene, const SolverSettings& s) {
  if (scene.obstacles.empty()) return "";
  std::string text =
      "  obstacles: geom obstacle<i> in the world body, contype = conaffinity = 0, touched only "
      "through one <contact><pair> with each contact geom of the body, which sets the pair's "
      "values exactly (no mixing); a box is a box geom of half-size (w/2, " +
      format_exact(obstacle_half_depth(scene)) +
      ", h/2) at (x, 0, y), a segment a capsule from (x1, 0, y1) to (x2, 0, y2) of its radius (a "
      "sphere when the ends coincide); each law is the scene's contact with the obstacle's own "
      "keys, mapped as above with the same A and n\n";
  for (size_t i = 0; i < scene.obstacles.size(); ++i) {
    const Obstacle& o = scene.obstacles[i];
    const ObstacleContactSettings os = obstacle_settings(scene, o, s);
    const ContactParams& p = os.law;
    text += "    obstacle" + std::to_string(i) + " (" + std::string(obstacle_shape_name(o.shape)) +
            (o.contact.any() ? ", own law" : ", the scene's law") + "): k " + format_exact(p.k) +
            " N/m, c " + format_exact(p.c) + " N s/m, damping " +
            std::string(damping_law_name(p.damping)) + ", mu " + format_exact(p.mu) + ", mu_roll " +
            format_exact(p.mu_roll) + " m, mu_torsion " + format_exact(p.mu_torsion) +
            "; solref = (" + format_exact(os.solref[0]) + ", " + format_exact(os.solref[1]) + ")" +
            (s.mapping == Mapping::Calibrated    ? " = (-k A/n, -c A/n)"
             : s.mapping == Mapping::Compensated ? " = (-k D/n, -c D/n)"
                                                 : "") +
            ", condim " + std::to_string(os.condim) +
            (cone_mu_roll(scene, p, s) != p.mu_roll
                 ? ", friction (mu, mu, mu_torsion, mu_roll', mu_roll'), mu_roll' = " +
                       format_exact(cone_mu_roll(scene, p, s)) + " m as above"
                 : std::string(", friction (mu, mu, mu_torsion, mu_roll, mu_roll)")) +
            "\n";
  }
  return text;
}

std::string header(const Scene& scene, const MjcfOptions& options, const SolverSettings& s,
                   const Layout& l) {
  const ContactParams& p = scene.contact;
  const State& x0 = scene.initial;
  const int condim = condim_of(scene, options);
  std::string text =
      "\n  contact2d MJCF, generated by `contact2d generate`: regenerate it, do not edit it.\n";
  text += "  scene file: " +
          (options.source.empty() ? std::string("(none)") : options.source + " (as given)") +
          ", shape " + std::string(shape_name(scene.shape)) + ", geometry " +
          std::string(geometry_name(options.geometry)) + "\n";
  if (options.version == Version::V3)
    text += "  for MuJoCo 3 (contact2d's engine mujoco3): solver tolerance " +
            format_exact(kV3Tolerance) +
            " (3.11's early exits off), compensated corners start at margin -eps (3.9's "
            "margin/gap), a point mass has the hinge \"spin\" (3.0's slide-only invweight)\n";
  text += "  contact: k " + format_exact(p.k) + " N/m, c " + format_exact(p.c) +
          " N s/m, damping " + std::string(damping_law_name(p.damping)) +
          (p.damping == DampingLaw::Compression ? " (MuJoCo's damper is Kelvin-Voigt)" : "") +
          ", mu " + format_exact(p.mu) + ", alpha " + format_exact(p.alpha) + " s/m, mu_roll " +
          format_exact(p.mu_roll) + " m, mu_torsion " + format_exact(p.mu_torsion) + "\n";
  text += "  sim: dt " + format_exact(scene.sim.dt) + " s (the timestep), duration " +
          format_exact(scene.sim.duration) + " s, integrator " +
          std::string(integrator_name(scene.sim.integrator)) + " (MuJoCo " +
          mujoco_integrator(scene.sim.integrator) + "), gravity " +
          format_exact(scene.sim.gravity) + " m/s^2\n";
  text += "  body: m " + format_exact(l.mass) + " kg";
  if (l.hinge) {
    text += ", " + inertia_formula(scene.shape) + " = " + format_exact(l.inertia[1]) +
            " kg m^2 (about the hinge)";
  }
  text += "\n";
  text += "  initial: x " + format_exact(x0.q.x()) + ", y " + format_exact(x0.q.y()) + ", theta " +
          format_exact(x0.q.z()) + ", vx " + format_exact(x0.v.x()) + ", vy " +
          format_exact(x0.v.y()) + ", omega " + format_exact(x0.v.z()) + "\n";
  if (l.hinge) {
    text +=
        "  pose: body pos (x, 0, y); unless theta = 0, body axisangle (0, -1, 0, theta), hinge "
        "ref theta, slide axes (cos theta, 0, -sin theta) and (sin theta, 0, cos theta) (MuJoCo x "
        "and z in the "
        "rotated body frame): qpos0, which a viewer shows, is the initial pose; "
        "qpos = (x - x0, y - y0, theta)\n";
  } else {
    text +=
        "  pose: body pos (x, 0, y): qpos0, which a viewer shows, is the initial pose; "
        "qpos = (x - x0, y - y0)\n";
  }
  text += "  keyframe \"initial\": qpos0 and qvel = (vx, vy" +
          std::string(l.hinge ? ", omega)" : ")") + "\n";
  text +=
      "  derived values: each is the formula stated, evaluated with the values above; only "
      "those marked \"depends on Δt\" change with the time step\n";
  text += mapping_lines(scene, s, condim, options.model_dt);
  text += obstacle_lines(scene, s);
  text += "  condim " + std::to_string(condim) +
          ": 1 without friction (mu = mu_roll = mu_torsion = 0), 3 with sliding friction only, "
          "6 with rolling or torsional friction\n";
  text += "  size: P = " + std::to_string(l.max_contacts) +
          " (contacts the body can make with the ground: " + l.contacts_why +
          (l.obstacles > 0 ? "), N = " + std::to_string(l.obstacles) +
                                 " (obstacles: each contact geom can touch the ground and every "
                                 "obstacle at once); nconmax = 2 P (1 + N) + "
                           : std::string("); nconmax = 2 P + ")) +
          std::to_string(kAddedGeoms * kContactsPerAddedGeom) + " = " +
          std::to_string(nconmax_of(l)) + " (twice P, and " + std::to_string(kAddedGeoms) +
          " added geoms of up to " + std::to_string(kContactsPerAddedGeom) +
          " contacts each); njmax = " + std::to_string(rows_per_contact(6, s.elliptic)) +
          " nconmax = " + std::to_string(njmax_of(l, s)) + " (" +
          (s.elliptic ? "an elliptic" : "a pyramidal") +
          " condim-6 contact's rows: added geoms may have any condim)\n";
  return text;
}

XMLElement* add(XMLDocument& doc, XMLElement* parent, const char* tag,
                std::initializer_list<std::pair<const char*, std::string>> attributes) {
  XMLElement* e = doc.NewElement(tag);
  for (const auto& [name, value] : attributes) e->SetAttribute(name, value.c_str());
  parent->InsertEndChild(e);
  return e;
}

void add_options(XMLDocument& doc, XMLElement* root, const Scene& scene, const SolverSettings& s,
                 const Layout& l, int condim) {
  add(doc, root, "compiler", {{"angle", "radian"}, {"inertiafromgeom", "false"}});
  XMLElement* option = add(doc, root, "option",
                           {{"timestep", format_exact(scene.sim.dt)},
                            {"integrator", mujoco_integrator(scene.sim.integrator)},
                            {"gravity", join({0.0, 0.0, -scene.sim.gravity})}});
  if (s.elliptic) option->SetAttribute("cone", "elliptic");
  if (l.version == Version::V3)
    option->SetAttribute("tolerance", format_exact(kV3Tolerance).c_str());
  // impratio scales the friction rows only: none at condim 1 (on every pair).
  int most = condim;
  for (const Obstacle& o : scene.obstacles)
    most = std::max(most, contact_condim(o.contact.apply(scene.contact)));
  if (most > 1 && s.impratio != 1.0)
    option->SetAttribute("impratio", format_exact(s.impratio).c_str());
  add(doc, root, "size",
      {{"nconmax", std::to_string(nconmax_of(l))}, {"njmax", std::to_string(njmax_of(l, s))}});
  XMLElement* defaults = add(doc, root, "default", {});
  const ContactParams& p = scene.contact;
  add(doc, defaults, "geom",
      {{"condim", std::to_string(condim)},
       {"friction", join({p.mu, p.mu_torsion, cone_mu_roll(scene, s)})},
       {"solref", join(s.solref)},
       {"solimp", join(s.solimp)}});
}

// The body starts in the initial pose (qpos0 is what a viewer shows): pos
// (x0, 0, y0) and, for a hinge, the body frame turned by θ0 about (0, −1, 0)
// with hinge ref = θ0, so that the hinge's qpos is θ itself (MuJoCo turns the
// body by qpos − ref from the frame it is given). Joint axes are in the body
// frame, so the slides' are MuJoCo x and z turned back by θ0.
// compensated: a corner sphere's contact is included from the 2D point's
// touching on (dist < −ε) and its spring measured from there: MuJoCo includes
// a contact while dist < includemargin and measures from includemargin, which
// is margin − gap on 2.2.2 (engine_collision_driver.c) and margin on 3.x (the
// margin/gap redesign of 3.9.0: gap only widens detection). So gap = ε on
// 2.2.2, margin = −ε on 3.x.
void set_start(XMLElement* e, const Layout& l) {
  e->SetAttribute(l.version == Version::V3 ? "margin" : "gap",
                  format_exact(l.version == Version::V3 ? -kCornerRadius : kCornerRadius).c_str());
}

void add_body(XMLDocument& doc, XMLElement* world, const Scene& scene, const Layout& l) {
  const Vec3& q0 = scene.initial.q;
  const double theta = l.hinge ? q0.z() : 0.0;
  XMLElement* body =
      add(doc, world, "body", {{"name", "body"}, {"pos", join({q0.x(), 0.0, q0.y()})}});
  std::string x_axis = "1 0 0", z_axis = "0 0 1";
  if (theta != 0.0) {
    body->SetAttribute("axisangle", join({0.0, -1.0, 0.0, theta}).c_str());
    const double c = std::cos(theta), sn = std::sin(theta);
    x_axis = join({c, 0.0, -sn});
    z_axis = join({sn, 0.0, c});
  }
  add(doc, body, "inertial",
      {{"pos", "0 0 0"}, {"mass", format_exact(l.mass)}, {"diaginertia", join(l.inertia)}});
  add(doc, body, "joint", {{"name", "x"}, {"type", "slide"}, {"axis", x_axis}});
  add(doc, body, "joint", {{"name", "y"}, {"type", "slide"}, {"axis", z_axis}});
  if (l.hinge) {
    XMLElement* hinge =
        add(doc, body, "joint", {{"name", "theta"}, {"type", "hinge"}, {"axis", "0 -1 0"}});
    if (theta != 0.0) hinge->SetAttribute("ref", format_exact(theta).c_str());
  }
  if (l.spin) add(doc, body, "joint", {{"name", "spin"}, {"type", "hinge"}, {"axis", "0 0 1"}});
  // compensated: the contact geoms on a massless body at the lever, each
  // placed back where it was (its position less the lever).
  XMLElement* contacts = nullptr;
  if (l.lever > 0.0) {
    contacts = add(doc, body, "body", {{"name", "contacts"}, {"pos", join({l.lever, 0.0, 0.0})}});
    // Massless, with its inertial frame at its own origin: without an
    // <inertial> MuJoCo 2.2.2 copies the body's pos into ipos and puts the
    // (massless) COM at twice the lever, which body_invweight0 would see.
    add(doc, contacts, "inertial", {{"pos", "0 0 0"}, {"mass", "0"}, {"diaginertia", "0 0 0"}});
  }
  for (const Geom& g : l.geoms) {
    const bool moved = contacts != nullptr && !g.visual;
    XMLElement* e = add(doc, moved ? contacts : body, "geom",
                        {{"name", g.name},
                         {"type", g.type},
                         {"size", g.size},
                         {"pos", join({moved ? g.x - l.lever : g.x, 0.0, g.z})}});
    // compensated: from the 2D point (set_start).
    if (moved && g.corner) set_start(e, l);
    // The friction damper: the ground touches them through pairs (add_pairs).
    if (l.pairs_with_ground && !g.visual) {
      e->SetAttribute("contype", "0");
      e->SetAttribute("conaffinity", "0");
    }
    if (g.visual) {
      e->SetAttribute("contype", "0");
      e->SetAttribute("conaffinity", "0");
      e->SetAttribute("group", "1");
    }
  }
}

// The static obstacles (mjcf.hpp): world-body geoms that touch only through
// the pairs of add_pairs. `moving`: only the moving ones (Obstacle::moves),
// each a geom at the origin of its own mocap body "obstacle<i>_body" placed
// where the scene puts the obstacle, written after the planar body so that
// the planar body stays body 1; otherwise only the static ones.
void add_obstacles(XMLDocument& doc, XMLElement* world, const Scene& scene, bool moving) {
  const double depth = obstacle_half_depth(scene);
  for (size_t i = 0; i < scene.obstacles.size(); ++i) {
    const Obstacle& o = scene.obstacles[i];
    if (o.moves != moving) continue;
    const std::string name = "obstacle" + std::to_string(i);
    XMLElement* e = nullptr;
    if (moving) {
      if (o.shape != ObstacleShape::Box)
        throw InputError("obstacle " + std::to_string(i) +
                         ": only a box obstacle can move on MuJoCo (a mocap body)");
      const Vec2 c = 0.5 * (o.a + o.b), half = 0.5 * (o.b - o.a);
      XMLElement* body =
          add(doc, world, "body",
              {{"name", name + "_body"}, {"mocap", "true"}, {"pos", join({c.x(), 0.0, c.y()})}});
      e = add(doc, body, "geom",
              {{"name", name}, {"type", "box"}, {"size", join({half.x(), depth, half.y()})}});
    } else if (o.shape == ObstacleShape::Box) {
      const Vec2 c = 0.5 * (o.a + o.b), half = 0.5 * (o.b - o.a);
      e = add(doc, world, "geom",
              {{"name", name},
               {"type", "box"},
               {"size", join({half.x(), depth, half.y()})},
               {"pos", join({c.x(), 0.0, c.y()})}});
    } else {
      // MuJoCo needs a radius above mjMINVAL: a zero-thickness segment gets
      // the corner spheres' radius.
      const double radius = std::max(o.radius, kCornerRadius);
      if (o.a == o.b) {
        e = add(doc, world, "geom",
                {{"name", name},
                 {"type", "sphere"},
                 {"size", format_exact(radius)},
                 {"pos", join({o.a.x(), 0.0, o.a.y()})}});
      } else {
        e = add(doc, world, "geom",
                {{"name", name},
                 {"type", "capsule"},
                 {"size", format_exact(radius)},
                 {"fromto", join({o.a.x(), 0.0, o.a.y(), o.b.x(), 0.0, o.b.y()})}});
      }
    }
    e->SetAttribute("contype", "0");
    e->SetAttribute("conaffinity", "0");
  }
}

// One explicit pair per (contact geom of the body, obstacle) with the
// obstacle's own law.
void add_pairs(XMLDocument& doc, XMLElement* root, const Scene& scene, const SolverSettings& s,
               const Layout& l) {
  if (scene.obstacles.empty() && !l.pairs_with_ground) return;
  XMLElement* contact = add(doc, root, "contact", {});
  // The friction rows' own damper φ·D_ (solref = (−S, −D_)), φ chosen per
  // law so that impratio·φ·c is the stick slope b (mapping.hpp).
  auto set_damper = [&](XMLElement* pair, const std::array<double, 2>& solref, double c) {
    if (s.friction_ratio <= 0.0 || !(c > 0.0)) return;
    const double phi = s.stick_slope / (s.impratio * c);
    pair->SetAttribute("solreffriction", join({solref[0], phi * solref[1]}).c_str());
  };
  if (l.pairs_with_ground) {
    const ContactParams& p = scene.contact;
    for (const Geom& g : l.geoms) {
      if (g.visual) continue;
      XMLElement* pair =
          add(doc, contact, "pair",
              {{"geom1", g.name},
               {"geom2", "ground"},
               {"condim", std::to_string(contact_condim(p))},
               {"friction",
                join({p.mu, p.mu, p.mu_torsion, cone_mu_roll(scene, s), cone_mu_roll(scene, s)})},
               {"solref", join(s.solref)},
               {"solimp", join(s.solimp)}});
      if (l.lever > 0.0 && g.corner) set_start(pair, l);
      set_damper(pair, s.solref, p.c);
    }
  }
  for (size_t i = 0; i < scene.obstacles.size(); ++i) {
    const ObstacleContactSettings os = obstacle_settings(scene, scene.obstacles[i], s);
    const ContactParams& p = os.law;
    for (const Geom& g : l.geoms) {
      if (g.visual) continue;
      XMLElement* pair = add(
          doc, contact, "pair",
          {{"geom1", g.name},
           {"geom2", "obstacle" + std::to_string(i)},
           {"condim", std::to_string(os.condim)},
           {"friction",
            join({p.mu, p.mu, p.mu_torsion, cone_mu_roll(scene, p, s), cone_mu_roll(scene, p, s)})},
           {"solref", join(os.solref)},
           {"solimp", join(s.solimp)}});
      // compensated: as the corner geoms' own gap (add_body); a pair uses its own
      if (l.lever > 0.0 && g.corner) set_start(pair, l);
      set_damper(pair, os.solref, p.c);
    }
  }
}

// qpos0 (the hinge's ref is θ0) and the initial velocities.
void add_keyframe(XMLDocument& doc, XMLElement* root, const Scene& scene, const Layout& l) {
  const State& s = scene.initial;
  const std::string qpos =
      l.hinge ? join({0.0, 0.0, s.q.z()}) : (l.spin ? join({0.0, 0.0, 0.0}) : join({0.0, 0.0}));
  const std::string qvel = l.hinge  ? join({s.v.x(), s.v.y(), s.v.z()})
                           : l.spin ? join({s.v.x(), s.v.y(), 0.0})
                                    : join({s.v.x(), s.v.y()});
  XMLElement* keyframe = add(doc, root, "keyframe", {});
  add(doc, keyframe, "key", {{"name", "initial"}, {"qpos", qpos}, {"qvel", qvel}});
}

double read_inv_mass(const Scene& scene, const MjcfOptions& options, int split) {
  // First pass: body_invweight0 depends only on the mass matrix and the
  // joints. The contact gets no spring and no damper (Â = 0): MuJoCo's
  // compiler takes a test step, and the scene's k, c at a wrong Â (it was 1)
  // made a heavy body resting on a stiff contact fail it (huge qacc).
  SolverSettings probe = solver_settings(scene, Mapping::Calibrated, 0.0, split);
  probe.mapping = options.mapping;  // compensated: with the contacts' body
  const ModelPtr model =
      load_model(write_mjcf(scene, options, probe), generated_origin(options.source));
  // 2 entries per body, translational first: body 1 is the moving body,
  // body 2 compensated's "contacts"
  return model->body_invweight0[options.mapping == Mapping::Compensated ? 4 : 2];
}

// No number that is not finite goes into a model (MuJoCo reads "nan" and
// runs it, diverging at the first step): every attribute's every token
// that reads whole as a number is checked. InputError names the element,
// the attribute and its value.
void refuse_non_finite(const XMLElement* element) {
  for (const tinyxml2::XMLAttribute* a = element->FirstAttribute(); a; a = a->Next()) {
    std::istringstream tokens(a->Value());
    for (std::string token; tokens >> token;) {
      char* end = nullptr;
      const double v = std::strtod(token.c_str(), &end);
      if (end == token.c_str() + token.size() && !std::isfinite(v))
        throw InputError("the model would have " + std::string(a->Name()) + "=\"" + a->Value() +
                         "\" on <" + element->Name() +
                         ">: a number that is not finite, which MuJoCo would run (a scene value "
                         "out of what this mapping can express)");
    }
  }
  for (const XMLElement* child = element->FirstChildElement(); child;
       child = child->NextSiblingElement())
    refuse_non_finite(child);
}

}  // namespace

int contact_condim(const ContactParams& contact) {
  if (contact.mu_roll > 0.0 || contact.mu_torsion > 0.0) return 6;
  return contact.mu > 0.0 ? 3 : 1;
}

std::string generated_origin(const std::string& source) {
  return (source.empty() ? std::string("the scene") : source) + " (its generated MJCF)";
}

std::string format_exact(double value) {
  if (value == std::trunc(value) &&
      std::abs(value) < 1e15) {  // integers as integers: 10000, not 1e+04
    return format_number("%.0f", value);
  }
  return format_shortest(value);
}

std::string write_mjcf(const Scene& scene, const MjcfOptions& options,
                       const SolverSettings& settings) {
  Layout layout = make_layout(scene, options.geometry, settings.mapping, options.version);
  layout.pairs_with_ground = settings.friction_ratio > 0.0;
  XMLDocument doc;
  doc.InsertEndChild(doc.NewComment(header(scene, options, settings, layout).c_str()));
  XMLElement* root = doc.NewElement("mujoco");
  root->SetAttribute("model", ("contact2d_" + std::string(shape_name(scene.shape))).c_str());
  doc.InsertEndChild(root);
  add_options(doc, root, scene, settings, layout, condim_of(scene, options));
  XMLElement* world = add(doc, root, "worldbody", {});
  add(doc, world, "geom", {{"name", "ground"}, {"type", "plane"}, {"size", "0 0 1"}});
  add_obstacles(doc, world, scene, false);
  add_body(doc, world, scene, layout);
  add_obstacles(doc, world, scene, true);
  add_pairs(doc, root, scene, settings, layout);
  add_keyframe(doc, root, scene, layout);
  refuse_non_finite(root);
  tinyxml2::XMLPrinter printer;
  doc.Print(&printer);
  return printer.CStr();
}

GeneratedModel generate_mjcf(const Scene& scene, const MjcfOptions& options) {
  mujoco_integrator(scene.sim.integrator);  // explicit Euler: fail before any work
  const int split = contacts_per_point(scene.shape, options.geometry);
  const double inv_mass =
      options.mapping == Mapping::Calibrated || options.mapping == Mapping::Compensated
          ? read_inv_mass(scene, options, split)
          : 0.0;
  GeneratedModel out;
  Scene model_scene = scene;  // the Δt the Δt-dependent values are for
  if (options.model_dt > 0.0) model_scene.sim.dt = options.model_dt;
  out.settings = solver_settings(model_scene, options.mapping, inv_mass, split);
  if (options.mapping == Mapping::Compensated)
    out.settings.lever =
        make_layout(scene, options.geometry, options.mapping, options.version).lever;
  if (options.friction_damper) {
    if (options.version != Version::V3)
      throw InputError(
          "friction damper: MuJoCo 2.2.2 has no solreffriction; it is for MuJoCo 3 (the engine "
          "mujoco3)");
    set_friction_damper(out.settings, scene.contact, make_body(scene), model_scene.sim.dt,
                        scene.sim.gravity);
  }
  // refsafe is MuJoCo's, at the real timestep.
  out.settings.refsafe_clamped =
      out.settings.solref[0] > 0.0 && out.settings.solref[0] < 2.0 * scene.sim.dt;
  // What MuJoCo uses: impratio is not written at condim 1 (no friction rows).
  if (condim_of(scene, options) == 1) out.settings.impratio = 1.0;
  out.xml = write_mjcf(scene, options, out.settings);
  // MuJoCo 3's model is loaded and checked by MuJoCo 3 (mujoco3/stepper.cpp).
  if (options.version == Version::V2)
    load_model(out.xml, generated_origin(
                            options.source));  // never hand out a model MuJoCo rejects or warns on
  return out;
}

MjcfOptions mjcf_options(const std::string& mapping, const std::string& geometry,
                         const std::string& source) {
  MjcfOptions options;
  if (!mapping.empty()) {
    const auto parsed = parse_mapping(mapping);
    if (!parsed)
      throw InputError("mapping " + mapping + ": unknown (seed, exact, calibrated, compensated)");
    options.mapping = *parsed;
  }
  if (!geometry.empty()) {
    const auto parsed = parse_geometry(geometry);
    if (!parsed) throw InputError("geometry " + geometry + ": unknown (corners, boxes)");
    options.geometry = *parsed;
  }
  options.source = source;
  return options;
}

}  // namespace contact2d::mujoco
