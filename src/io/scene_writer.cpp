// Scene → TOML (io/scene_writer.hpp).
#include "io/scene_writer.hpp"

#include <sstream>

#include "core/format.hpp"

namespace contact2d {
namespace {

std::string n(double v) { return format_shortest(v); }

}  // namespace

std::string scene_to_toml(const Scene& s, const std::string& comment) {
  std::ostringstream o;
  if (!comment.empty()) {
    std::istringstream lines(comment);
    for (std::string line; std::getline(lines, line);) o << "# " << line << "\n";
  }
  o << "scene = \"" << shape_name(s.shape) << "\"\n\n[body]\n";
  switch (s.shape) {
    case Shape::PointMass:
      o << "mass = " << n(s.mass) << "\nhalf_height = " << n(s.half_height) << "\n";
      break;
    case Shape::Box:
      o << "mass = " << n(s.mass) << "\nwidth = " << n(s.width) << "\nheight = " << n(s.height)
        << "\n";
      break;
    case Shape::Circle: o << "mass = " << n(s.mass) << "\nradius = " << n(s.radius) << "\n"; break;
    case Shape::TShape: {
      const std::vector<BoxPart> parts = s.parts.empty() ? default_tshape_parts() : s.parts;
      o << "parts = [\n";
      for (const BoxPart& p : parts)
        o << "  { width = " << n(p.width) << ", height = " << n(p.height)
          << ", mass = " << n(p.mass) << ", x = " << n(p.x) << ", y = " << n(p.y) << " },\n";
      o << "]\n";
      break;
    }
  }
  const ContactParams& c = s.contact;
  o << "\n[contact]\nk = " << n(c.k) << "\nc = " << n(c.c) << "\nmu = " << n(c.mu)
    << "\nalpha = " << n(c.alpha) << "\nmu_roll = " << n(c.mu_roll)
    << "\nmu_torsion = " << n(c.mu_torsion) << "\ndamping = \""
    << (c.damping == DampingLaw::Compression ? "compression" : "kelvin_voigt") << "\"\n";
  if (c.friction != FrictionLaw::Tanh)
    o << "friction_law = \"" << friction_law_name(c.friction)
      << "\"\ncone_ratio = " << n(c.cone_ratio) << "\n";
  const State& x = s.initial;
  o << "\n[initial]\nx = " << n(x.q.x()) << "\ny = " << n(x.q.y());
  if (s.shape != Shape::PointMass) o << "\ntheta = " << n(x.q.z());
  o << "\nvx = " << n(x.v.x()) << "\nvy = " << n(x.v.y());
  if (s.shape != Shape::PointMass) o << "\nomega = " << n(x.v.z());
  o << "\n\n[sim]\ndt = " << n(s.sim.dt) << "\nduration = " << n(s.sim.duration)
    << "\noutput_dt = " << n(s.sim.output_dt) << "\nintegrator = \""
    << integrator_name(s.sim.integrator) << "\"\ngravity = " << n(s.sim.gravity) << "\n";
  for (const Obstacle& ob : s.obstacles) {
    o << "\n[[obstacle]]\n";
    if (ob.shape == ObstacleShape::Box) {
      o << "type = \"box\"\nx = " << n(0.5 * (ob.a.x() + ob.b.x()))
        << "\ny = " << n(0.5 * (ob.a.y() + ob.b.y())) << "\nwidth = " << n(ob.b.x() - ob.a.x())
        << "\nheight = " << n(ob.b.y() - ob.a.y()) << "\n";
    } else {
      o << "type = \"segment\"\nx1 = " << n(ob.a.x()) << "\ny1 = " << n(ob.a.y())
        << "\nx2 = " << n(ob.b.x()) << "\ny2 = " << n(ob.b.y()) << "\nradius = " << n(ob.radius)
        << "\n";
    }
  }
  return o.str();
}

}  // namespace contact2d
