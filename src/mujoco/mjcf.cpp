#include "mujoco/mjcf.hpp"

#include "core/format.hpp"

#include <tinyxml2.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <initializer_list>
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
};

struct Layout {
  double mass = 0.0;
  std::array<double, 3> inertia{};  // diaginertia about MuJoCo x, y (hinge), z
  bool hinge = true;
  std::vector<Geom> geoms;
  int max_contacts = 0;  // nconmax
};

std::vector<BoxPart> parts_of(const Scene& scene) {
  if (scene.shape == Shape::Box) return {BoxPart{scene.width, scene.height, 0.0, 0.0, scene.mass}};
  return scene.parts.empty() ? default_tshape_parts() : scene.parts;
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
    Geom part{"part" + std::to_string(i),
              "box",
              join({p.width / 2, depth / 2, p.height / 2}),
              dx,
              dz,
              geometry == Geometry::CornerSpheres};
    layout.geoms.push_back(part);
  }
  layout.inertia = loadable_inertia({ix, props.inertia, iz});
  if (geometry == Geometry::BoxGeoms) {
    layout.max_contacts = 4 * static_cast<int>(parts.size());
    return layout;
  }
  const RigidBody body = make_compound(parts);
  for (size_t i = 0; i < body.points.size(); ++i) {
    layout.geoms.push_back({"point" + std::to_string(i), "sphere", format_exact(kCornerRadius),
                            body.points[i].x(), body.points[i].y(), false});
  }
  layout.max_contacts = static_cast<int>(body.points.size());
  return layout;
}

Layout point_mass_layout(const Scene& scene) {
  const double rho = std::max(scene.half_height, kCornerRadius);
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
      {"point0", "sphere", format_exact(rho), 0.0, rho - scene.half_height, false});
  layout.max_contacts = 1;
  return layout;
}

Layout circle_layout(const Scene& scene) {
  const double m = scene.mass, r = scene.radius;
  const double side = 0.25 * m * r * r + m * (2 * r) * (2 * r) / 12.0;
  Layout layout;
  layout.mass = m;
  layout.inertia = {side, 0.5 * m * r * r, side};
  layout.geoms.push_back({"point0", "sphere", format_exact(r), 0.0, 0.0, false});
  layout.max_contacts = 1;
  return layout;
}

Layout make_layout(const Scene& scene, Geometry geometry) {
  switch (scene.shape) {
    case Shape::PointMass: return point_mass_layout(scene);
    case Shape::Circle: return circle_layout(scene);
    case Shape::Box:
    case Shape::TShape: return box_layout(scene, geometry);
  }
  return {};
}

std::string mapping_formula(const SolverSettings& s) {
  switch (s.mapping) {
    case Mapping::Seed:
      return "timeconst = sqrt(m/k), dampratio = c/(2 sqrt(m k)); MuJoCo's default solimp and cone";
    case Mapping::Exact:
      return "timeconst = 2m/c, dampratio = c/(2 sqrt(m k)) (= direct form -k/m, -c/m); "
             "MuJoCo's default solimp and cone";
    case Mapping::Calibrated:
      return "direct solref = (-k A/n, -c A/n) with A = body_invweight0 = " +
             format_exact(s.inv_mass) +
             " 1/kg read from the compiled model and n = " + std::to_string(s.split) +
             " contacts per 2D point; flat minimal solimp (impedance 1e-4); elliptic cone; "
             "impratio = mu m g alpha / c";
  }
  return "";
}

std::string header(const Scene& scene, const MjcfOptions& options, const SolverSettings& s,
                   const Layout& l) {
  const ContactParams& p = scene.contact;
  const State& x0 = scene.initial;
  auto f = [](double v) { return format_exact(v); };
  std::string text =
      "\n  contact2d MJCF, generated by `contact2d generate`: regenerate it, do not edit it.\n";
  text += "  scene file: " + (options.source.empty() ? std::string("(none)") : options.source) +
          " (" + std::string(shape_name(scene.shape)) + ")\n";
  text += "  mapping: " + std::string(mapping_name(s.mapping)) + ": " + mapping_formula(s) + "\n";
  text += "  geometry: " + std::string(geometry_name(options.geometry)) + "\n";
  text +=
      "  body: mass " + f(l.mass) + " kg, inertia about the hinge " + f(l.inertia[1]) + " kg m^2\n";
  text += "  contact: k " + f(p.k) + " N/m, c " + f(p.c) + " N s/m, damping " +
          (p.damping == DampingLaw::Compression ? "compression (MuJoCo's damper is Kelvin-Voigt)"
                                                : "kelvin_voigt") +
          ", mu " + f(p.mu) + ", alpha " + f(p.alpha) + " s/m, mu_roll " + f(p.mu_roll) +
          " m, mu_torsion " + f(p.mu_torsion) + "\n";
  text += "  initial: x " + f(x0.q.x()) + ", y " + f(x0.q.y()) + ", theta " + f(x0.q.z()) +
          ", vx " + f(x0.v.x()) + ", vy " + f(x0.v.y()) + ", omega " + f(x0.v.z()) + "\n";
  text += "  sim: dt " + f(scene.sim.dt) + " s, duration " + f(scene.sim.duration) +
          " s, integrator " + std::string(integrator_name(scene.sim.integrator)) + " (MuJoCo " +
          mujoco_integrator(scene.sim.integrator) + "), gravity " + f(scene.sim.gravity) +
          " m/s^2\n";
  if (s.refsafe_clamped) {
    text +=
        "  note: timeconst < 2 dt: MuJoCo raises it to 2 dt (refsafe), a softer contact than k\n";
  }
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
                 const Layout& l) {
  add(doc, root, "compiler", {{"angle", "radian"}, {"inertiafromgeom", "false"}});
  XMLElement* option = add(doc, root, "option",
                           {{"timestep", format_exact(scene.sim.dt)},
                            {"integrator", mujoco_integrator(scene.sim.integrator)},
                            {"gravity", join({0.0, 0.0, -scene.sim.gravity})}});
  if (s.elliptic) option->SetAttribute("cone", "elliptic");
  if (s.impratio != 1.0) option->SetAttribute("impratio", format_exact(s.impratio).c_str());
  // Rows per condim-6 contact: 6 (elliptic) or 2·(6 − 1) = 10 (pyramidal).
  add(doc, root, "size",
      {{"nconmax", std::to_string(l.max_contacts)},
       {"njmax", std::to_string(10 * l.max_contacts)}});
  XMLElement* defaults = add(doc, root, "default", {});
  const ContactParams& p = scene.contact;
  add(doc, defaults, "geom",
      {{"condim", "6"},
       {"friction", join({p.mu, p.mu_torsion, p.mu_roll})},
       {"solref", join(s.solref)},
       {"solimp", join(s.solimp)}});
}

void add_body(XMLDocument& doc, XMLElement* world, const Scene& scene, const Layout& l) {
  const Vec3& q0 = scene.initial.q;
  XMLElement* body =
      add(doc, world, "body", {{"name", "body"}, {"pos", join({q0.x(), 0.0, q0.y()})}});
  add(doc, body, "inertial",
      {{"pos", "0 0 0"}, {"mass", format_exact(l.mass)}, {"diaginertia", join(l.inertia)}});
  add(doc, body, "joint", {{"name", "x"}, {"type", "slide"}, {"axis", "1 0 0"}});
  add(doc, body, "joint", {{"name", "y"}, {"type", "slide"}, {"axis", "0 0 1"}});
  if (l.hinge) add(doc, body, "joint", {{"name", "theta"}, {"type", "hinge"}, {"axis", "0 -1 0"}});
  for (const Geom& g : l.geoms) {
    XMLElement* e =
        add(doc, body, "geom",
            {{"name", g.name}, {"type", g.type}, {"size", g.size}, {"pos", join({g.x, 0.0, g.z})}});
    if (g.visual) {
      e->SetAttribute("contype", "0");
      e->SetAttribute("conaffinity", "0");
      e->SetAttribute("group", "1");
    }
  }
}

void add_keyframe(XMLDocument& doc, XMLElement* root, const Scene& scene, const Layout& l) {
  const State& s = scene.initial;
  const std::string qpos = l.hinge ? join({0.0, 0.0, s.q.z()}) : join({0.0, 0.0});
  const std::string qvel = l.hinge ? join({s.v.x(), s.v.y(), s.v.z()}) : join({s.v.x(), s.v.y()});
  XMLElement* keyframe = add(doc, root, "keyframe", {});
  add(doc, keyframe, "key", {{"name", "initial"}, {"qpos", qpos}, {"qvel", qvel}});
}

double read_inv_mass(const Scene& scene, const MjcfOptions& options, int split) {
  // First pass: body_invweight0 depends only on the mass matrix and the
  // joints. The contact gets no spring and no damper (Â = 0): MuJoCo's
  // compiler takes a test step, and the scene's k, c at a wrong Â (it was 1)
  // made a heavy body resting on a stiff contact fail it (huge qacc).
  SolverSettings probe = solver_settings(scene, Mapping::Calibrated, 0.0, split);
  const ModelPtr model =
      load_model(write_mjcf(scene, options, probe), generated_origin(options.source));
  return model->body_invweight0[2];  // body 1 (2 entries per body), translational
}

}  // namespace

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
  const Layout layout = make_layout(scene, options.geometry);
  XMLDocument doc;
  doc.InsertEndChild(doc.NewComment(header(scene, options, settings, layout).c_str()));
  XMLElement* root = doc.NewElement("mujoco");
  root->SetAttribute("model", ("contact2d_" + std::string(shape_name(scene.shape))).c_str());
  doc.InsertEndChild(root);
  add_options(doc, root, scene, settings, layout);
  XMLElement* world = add(doc, root, "worldbody", {});
  add(doc, world, "geom", {{"name", "ground"}, {"type", "plane"}, {"size", "0 0 1"}});
  add_body(doc, world, scene, layout);
  add_keyframe(doc, root, scene, layout);
  tinyxml2::XMLPrinter printer;
  doc.Print(&printer);
  return printer.CStr();
}

GeneratedModel generate_mjcf(const Scene& scene, const MjcfOptions& options) {
  mujoco_integrator(scene.sim.integrator);  // explicit Euler: fail before any work
  if (!scene.obstacles.empty()) {
    throw InputError("[[obstacle]]: the MuJoCo model has the ground plane only; remove the " +
                     std::to_string(scene.obstacles.size()) +
                     " obstacle(s) to run the scene in MuJoCo");
  }
  const int split = contacts_per_point(scene.shape, options.geometry);
  const double inv_mass =
      options.mapping == Mapping::Calibrated ? read_inv_mass(scene, options, split) : 0.0;
  GeneratedModel out;
  out.settings = solver_settings(scene, options.mapping, inv_mass, split);
  out.xml = write_mjcf(scene, options, out.settings);
  load_model(out.xml, generated_origin(
                          options.source));  // never hand out a model MuJoCo rejects or warns on
  return out;
}

MjcfOptions mjcf_options(const std::string& mapping, const std::string& geometry,
                         const std::string& source) {
  MjcfOptions options;
  if (!mapping.empty()) {
    const auto parsed = parse_mapping(mapping);
    if (!parsed) throw InputError("mapping " + mapping + ": unknown (seed, exact, calibrated)");
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
