#include "analysis/friction_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <tinyxml2.h>

#include "analysis/engine.hpp"
#include "analysis/trajectory_error.hpp"
#include "core/body.hpp"
#include "core/run.hpp"
#include "io/scene_file.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/stepper.hpp"

namespace contact2d::analysis {

namespace {

std::string law(double c, double mu, double mu_roll) {
  return "[contact]\nk = 1e4\nc = " + std::to_string(c) + "\nmu = " + std::to_string(mu) +
         "\nmu_roll = " + std::to_string(mu_roll) + "\nalpha = 100\ndamping = \"kelvin_voigt\"\n";
}

std::string sim(double duration) {
  return "[sim]\ndt = 1e-4\nduration = " + std::to_string(duration) +
         "\nintegrator = \"semi_implicit_euler\"\n";
}

FrictionOutcome measure(const Scene& scene, const Trajectory& reference, const std::string& xml) {
  mujoco::MujocoStepper stepper(scene, xml, "friction scene");
  const Trajectory mj = simulate(stepper, scene.sim);
  FrictionOutcome out;
  const TrajectoryError e = error_between(reference, mj);
  out.max_pos = e.max_pos;
  out.max_angle = e.max_angle;
  const size_t n = std::min(reference.samples.size(), mj.samples.size());
  for (size_t i = 0; i < n; ++i)
    out.hop = std::max(out.hop, mj.samples[i].state.q.y() - reference.samples[i].state.q.y());
  return out;
}

std::string pair_text(double a, double b) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g %.17g", a, b);
  return buf;
}

}  // namespace

std::vector<FrictionScene> friction_scenes() {
  const std::string box = "scene = \"box\"\n[body]\nmass = 1.0\nwidth = 0.4\nheight = 0.2\n";
  const std::string disc = "scene = \"circle\"\n[body]\nmass = 1.0\nradius = 0.1\n";
  const struct {
    const char* name;
    const char* what;
    std::string toml;
  } cases[] = {
      {"box_slide", "box sliding to rest, c = 50",
       box + law(50, 0.5, 0) + "[initial]\ny = 0.0995\nvx = 2.0\n" + sim(1.5)},
      {"box_slide_c200", "box sliding to rest, c = 200",
       box + law(200, 0.5, 0) + "[initial]\ny = 0.0995\nvx = 2.0\n" + sim(1.5)},
      {"tshape", "T landing on a corner and sliding",
       "scene = \"tshape\"\n" + law(200, 0.5, 0) + "[initial]\ny = 0.8\ntheta = 0.2\nvx = 0.3\n" +
           sim(2.0)},
      {"roll", "disc rolling with rolling resistance",
       disc + law(200, 0.5, 0.01) + "[initial]\ny = 0.099019\nvx = 2.0\nomega = -20\n" + sim(3.0)},
      {"slide_roll", "disc sliding into rolling",
       disc + law(200, 0.2, 0) + "[initial]\ny = 0.099019\nvx = 2.0\n" + sim(2.0)},
      {"backspin", "disc dropped with backspin",
       disc + law(200, 0.5, 0) + "[initial]\ny = 0.3\nvx = 1.0\nomega = 30\n" + sim(2.0)},
  };
  std::vector<FrictionScene> out;
  for (const auto& c : cases) out.push_back({c.name, c.what, parse_scene(c.toml, c.name)});
  return out;
}

// Every contact geom of the body "contacts" (the compensated model's) becomes
// two at the same place, priority 1 (their values win over the ground's): a
// frictional one carrying the share w of the spring, a damper of w·ρ and the
// friction coefficients divided by w, and a frictionless one (condim 1)
// carrying the rest, (1 − w)·k and c − w·ρ. impratio is the chatter-free rule
// (mapping.hpp) with the frictional damper w·ρ.
std::string friction_split_xml(const Scene& scene, double w, double rho) {
  mujoco::MjcfOptions options;
  options.mapping = mujoco::Mapping::Compensated;
  const mujoco::GeneratedModel g = mujoco::generate_mjcf(scene, options);
  tinyxml2::XMLDocument doc;
  doc.Parse(g.xml.c_str());
  tinyxml2::XMLElement* root = doc.FirstChildElement("mujoco");
  const double scale = mujoco::solref_scale(g.settings) / g.settings.split;
  const double k = scene.contact.k, c = scene.contact.c;
  const RigidBody body = make_body(scene);
  const double r = body_extent(body);
  const double a_t = body.rotates ? 1.0 / body.mass + r * r / body.inertia : 1.0 / body.mass;
  double impratio = 1.0 / (w * rho * scene.sim.dt * a_t);
  if (body.roll_radius > 0.0 && scene.contact.mu_roll > 0.0) {
    const double ratio = scene.contact.mu / scene.contact.mu_roll;
    impratio = std::min(impratio, body.inertia * ratio * ratio / (w * rho * scene.sim.dt));
  }
  root->FirstChildElement("option")->SetAttribute("impratio", impratio);
  tinyxml2::XMLElement* contacts = nullptr;
  for (auto* b = root->FirstChildElement("worldbody")
                     ->FirstChildElement("body")
                     ->FirstChildElement("body");
       b; b = b->NextSiblingElement("body")) {
    if (std::string(b->Attribute("name")) == "contacts") contacts = b;
  }
  if (!contacts) throw std::runtime_error("friction split: no 'contacts' body in the model");
  std::vector<tinyxml2::XMLElement*> geoms;
  for (auto* e = contacts->FirstChildElement("geom"); e; e = e->NextSiblingElement("geom"))
    geoms.push_back(e);
  for (tinyxml2::XMLElement* e : geoms) {
    auto* normal = e->DeepClone(&doc)->ToElement();
    normal->SetAttribute("name", (std::string(e->Attribute("name")) + "_n").c_str());
    normal->SetAttribute("priority", 1);
    normal->SetAttribute("condim", 1);
    normal->SetAttribute("solref", pair_text(-(1 - w) * k * scale, -(c - w * rho) * scale).c_str());
    contacts->InsertEndChild(normal);
    e->SetAttribute("priority", 1);
    e->SetAttribute("condim", scene.contact.mu_roll > 0.0 ? 6 : 3);
    // compensated's cone coefficient for rolling (mjcf.cpp), for the share w
    double mu_roll = scene.contact.mu_roll;
    if (scene.shape == Shape::Circle && mu_roll > 0.0 && scene.contact.mu > 0.0) {
      const double kappa = body.mass * scene.radius * scene.radius /
                           (body.inertia + body.mass * scene.radius * scene.radius);
      const double q = kappa * mu_roll / (scene.contact.mu * scene.radius);
      if (q < 1.0) mu_roll /= std::sqrt(1.0 - q * q);
    }
    char friction[128];
    std::snprintf(friction, sizeof friction, "%.17g %.17g %.17g", scene.contact.mu / w,
                  std::max(scene.contact.mu_torsion / w, 1e-5), std::max(mu_roll / w, 1e-5));
    e->SetAttribute("friction", friction);
    e->SetAttribute("solref", pair_text(-w * k * scale, -w * rho * scale).c_str());
  }
  tinyxml2::XMLPrinter printer;
  doc.Print(&printer);
  return printer.CStr();
}

FrictionRow friction_row(const FrictionScene& s) {
  const Trajectory reference = simulate(s.scene);
  FrictionRow row{s.name, s.what, {}, {}, {}};
  for (mujoco::Mapping m : {mujoco::Mapping::Calibrated, mujoco::Mapping::Compensated}) {
    mujoco::MjcfOptions options;
    options.mapping = m;
    const FrictionOutcome o =
        measure(s.scene, reference, mujoco::generate_mjcf(s.scene, options).xml);
    (m == mujoco::Mapping::Calibrated ? row.calibrated : row.compensated) = o;
  }
  row.split = measure(s.scene, reference,
                      friction_split_xml(s.scene, kSplitShare, kSplitDamper * s.scene.contact.c));
  return row;
}

std::vector<FrictionRow> friction_table(unsigned threads) {
  const std::vector<FrictionScene> scenes = friction_scenes();
  std::vector<FrictionRow> rows(scenes.size());
  parallel_for(scenes.size(), threads, [&](size_t i) { rows[i] = friction_row(scenes[i]); });
  return rows;
}

}  // namespace contact2d::analysis
