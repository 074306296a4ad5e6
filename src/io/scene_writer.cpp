// Scene → TOML (io/scene_writer.hpp).
#include "io/scene_writer.hpp"

#include <sstream>

#include "core/format.hpp"

namespace contact2d {
std::string scene_to_toml(const Scene& s, const std::string& comment) {
  std::ostringstream o;
  if (!comment.empty()) {
    std::istringstream lines(comment);
    for (std::string line; std::getline(lines, line);) o << "# " << line << "\n";
  }
  o << "scene = \"" << shape_name(s.shape) << "\"\n\n[body]\n";
  switch (s.shape) {
    case Shape::PointMass:
      o << "mass = " << format_shortest(s.mass)
        << "\nhalf_height = " << format_shortest(s.half_height) << "\n";
      break;
    case Shape::Box:
      o << "mass = " << format_shortest(s.mass) << "\nwidth = " << format_shortest(s.width)
        << "\nheight = " << format_shortest(s.height) << "\n";
      break;
    case Shape::Circle:
      o << "mass = " << format_shortest(s.mass) << "\nradius = " << format_shortest(s.radius)
        << "\n";
      break;
    case Shape::Ellipse:
      o << "mass = " << format_shortest(s.mass) << "\na = " << format_shortest(s.a)
        << "\nb = " << format_shortest(s.b) << "\n";
      if (s.inertia > 0.0) o << "inertia = " << format_shortest(s.inertia) << "\n";
      break;
    case Shape::TShape: {
      const std::vector<BoxPart> parts = s.parts.empty() ? default_tshape_parts() : s.parts;
      o << "parts = [\n";
      for (const BoxPart& p : parts)
        o << "  { width = " << format_shortest(p.width)
          << ", height = " << format_shortest(p.height) << ", mass = " << format_shortest(p.mass)
          << ", x = " << format_shortest(p.x) << ", y = " << format_shortest(p.y) << " },\n";
      o << "]\n";
      break;
    }
  }
  const ContactParams& c = s.contact;
  o << "\n[contact]\nk = " << format_shortest(c.k) << "\nc = " << format_shortest(c.c)
    << "\nmu = " << format_shortest(c.mu) << "\nalpha = " << format_shortest(c.alpha)
    << "\nmu_roll = " << format_shortest(c.mu_roll)
    << "\nmu_torsion = " << format_shortest(c.mu_torsion) << "\ndamping = \""
    << damping_law_name(c.damping) << "\"\n";
  if (c.friction != FrictionLaw::Tanh)
    o << "friction_law = \"" << friction_law_name(c.friction)
      << "\"\ncone_ratio = " << format_shortest(c.cone_ratio) << "\n";
  const State& x = s.initial;
  o << "\n[initial]\nx = " << format_shortest(x.q.x()) << "\ny = " << format_shortest(x.q.y());
  if (shape_features(s.shape).turns) o << "\ntheta = " << format_shortest(x.q.z());
  o << "\nvx = " << format_shortest(x.v.x()) << "\nvy = " << format_shortest(x.v.y());
  if (shape_features(s.shape).turns) o << "\nomega = " << format_shortest(x.v.z());
  o << "\n\n[sim]\ndt = " << format_shortest(s.sim.dt)
    << "\nduration = " << format_shortest(s.sim.duration)
    << "\noutput_dt = " << format_shortest(s.sim.output_dt) << "\nintegrator = \""
    << integrator_name(s.sim.integrator) << "\"\ngravity = " << format_shortest(s.sim.gravity)
    << "\n";
  for (const Obstacle& ob : s.obstacles) {
    o << "\n[[obstacle]]\n";
    if (ob.shape == ObstacleShape::Box) {
      o << "type = \"box\"\nx = " << format_shortest(0.5 * (ob.a.x() + ob.b.x()))
        << "\ny = " << format_shortest(0.5 * (ob.a.y() + ob.b.y()))
        << "\nwidth = " << format_shortest(ob.b.x() - ob.a.x())
        << "\nheight = " << format_shortest(ob.b.y() - ob.a.y()) << "\n";
    } else {
      o << "type = \"segment\"\nx1 = " << format_shortest(ob.a.x())
        << "\ny1 = " << format_shortest(ob.a.y()) << "\nx2 = " << format_shortest(ob.b.x())
        << "\ny2 = " << format_shortest(ob.b.y()) << "\nradius = " << format_shortest(ob.radius)
        << "\n";
    }
  }
  return o.str();
}

}  // namespace contact2d
