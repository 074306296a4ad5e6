#include "analysis/friction_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>
#include <stdexcept>

#include <tinyxml2.h>

#include "analysis/engine.hpp"
#include "analysis/trajectory_error.hpp"
#include "core/body.hpp"
#include "core/run.hpp"
#include "engines/engines.hpp"
#include "io/scene_file.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/stepper.hpp"
#include "mujoco3/node_mujoco.hpp"

namespace contact2d::analysis {

namespace {

std::string law(double c, double mu, double mu_roll, double alpha = 100) {
  return "[contact]\nk = 1e4\nc = " + std::to_string(c) + "\nmu = " + std::to_string(mu) +
         "\nmu_roll = " + std::to_string(mu_roll) + "\nalpha = " + std::to_string(alpha) +
         "\ndamping = \"kelvin_voigt\"\n";
}

std::string sim(double duration) {
  return "[sim]\ndt = 1e-4\nduration = " + std::to_string(duration) +
         "\nintegrator = \"semi_implicit_euler\"\n";
}

FrictionOutcome outcome(const Trajectory& reference, const Trajectory& mj) {
  FrictionOutcome out;
  const TrajectoryError e = error_between(reference, mj);
  out.max_pos = e.max_pos;
  out.max_angle = e.max_angle;
  const size_t n = std::min(reference.samples.size(), mj.samples.size());
  for (size_t i = 0; i < n; ++i)
    out.hop = std::max(out.hop, mj.samples[i].state.q.y() - reference.samples[i].state.q.y());
  return out;
}

// MuJoCo with a mapping, from the registry.
engines::EngineSpec mujoco_engine(mujoco::Mapping mapping) {
  return engines::parse_engine("mujoco:" + std::string(mujoco::mapping_name(mapping)));
}

FrictionOutcome measure(const Scene& scene, const Trajectory& reference, const std::string& xml) {
  mujoco::MujocoStepper stepper(scene, xml, "friction scene");
  return outcome(reference, simulate(stepper, scene.sim));
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
      {"point_slide", "point mass sliding to rest, c = 20",
       "scene = \"point_mass\"\n[body]\nmass = 1.0\nhalf_height = 0.05\n" + law(20, 0.6, 0, 500) +
           "[initial]\ny = 0.049019\nvx = 1.0\n" + sim(1.0)},
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
      {"backspin_bounce", "disc bouncing with backspin and rolling resistance",
       disc + law(200, 0.4, 0.004) + "[initial]\ny = 0.3\nvx = 1.5\nomega = 20\n" + sim(2.0)},
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
  const double a_t =
      shape_features(body.shape).turns ? 1.0 / body.mass + r * r / body.inertia : 1.0 / body.mass;
  double impratio = 1.0 / (w * rho * scene.sim.dt * a_t);
  if (shape_features(body.shape).rolls && scene.contact.mu_roll > 0.0) {
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
    const double mu_roll = mujoco::cone_mu_roll(scene, g.settings);
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

std::string friction_knob_xml(const Scene& scene, FrictionKnob knob) {
  mujoco::MjcfOptions options;
  options.mapping = mujoco::Mapping::Calibrated;
  const mujoco::GeneratedModel g = mujoco::generate_mjcf(scene, options);
  if (knob == FrictionKnob::ImpratioTenth || knob == FrictionKnob::ImpratioTen) {
    mujoco::SolverSettings s = g.settings;
    s.impratio *= knob == FrictionKnob::ImpratioTen ? 10.0 : 0.1;
    return mujoco::write_mjcf(scene, options, s);
  }
  tinyxml2::XMLDocument doc;
  doc.Parse(g.xml.c_str());
  tinyxml2::XMLElement* root = doc.FirstChildElement("mujoco");
  tinyxml2::XMLElement* option = root->FirstChildElement("option");
  tinyxml2::XMLElement* defaults = root->FirstChildElement("default")->FirstChildElement("geom");
  const int condim = defaults->IntAttribute("condim", 3);
  switch (knob) {
    case FrictionKnob::Pyramidal: option->SetAttribute("cone", "pyramidal"); break;
    case FrictionKnob::Noslip: option->SetAttribute("noslip_iterations", 10); break;
    case FrictionKnob::Condim:
      if (condim >= 6) return "";
      defaults->SetAttribute("condim", 6);
      break;
    case FrictionKnob::MarginGap:
      defaults->SetAttribute("margin", 1e-3);
      defaults->SetAttribute("gap", 1e-3);
      break;
    case FrictionKnob::Pair: {
      // Every colliding geom of the body (no contype attribute: the visual
      // ones have contype = 0) leaves the dynamic collisions and gets an
      // explicit pair with the ground carrying the default's values, with
      // friction's five coefficients written out.
      std::vector<std::string> names;
      std::vector<tinyxml2::XMLElement*> stack{root->FirstChildElement("worldbody")};
      while (!stack.empty()) {
        tinyxml2::XMLElement* e = stack.back();
        stack.pop_back();
        for (auto* b = e->FirstChildElement("body"); b; b = b->NextSiblingElement("body"))
          stack.push_back(b);
        if (std::string(e->Name()) != "body") continue;
        for (auto* geom = e->FirstChildElement("geom"); geom;
             geom = geom->NextSiblingElement("geom")) {
          if (geom->Attribute("contype")) continue;
          geom->SetAttribute("contype", 0);
          geom->SetAttribute("conaffinity", 0);
          names.emplace_back(geom->Attribute("name"));
        }
      }
      // The generated default's three coefficients (sliding, torsional,
      // rolling): all three are always written (mujoco/mjcf.cpp).
      double mu[3] = {0.0, 0.0, 0.0};
      const char* text = defaults->Attribute("friction");
      for (double& value : mu) {
        char* end = nullptr;
        value = text ? std::strtod(text, &end) : 0.0;
        if (!text || end == text)
          throw std::runtime_error(
              "friction split: the model's default friction is not three numbers");
        text = end;
      }
      char friction[160];
      std::snprintf(friction, sizeof friction, "%.17g %.17g %.17g %.17g %.17g", mu[0], mu[0],
                    std::max(mu[1], 1e-5), std::max(mu[2], 1e-5), std::max(mu[2], 1e-5));
      tinyxml2::XMLElement* contact = root->FirstChildElement("contact");
      if (!contact) {
        contact = doc.NewElement("contact");
        root->InsertAfterChild(root->FirstChildElement("worldbody"), contact);
      }
      for (const std::string& name : names) {
        tinyxml2::XMLElement* pair = doc.NewElement("pair");
        pair->SetAttribute("geom1", "ground");
        pair->SetAttribute("geom2", name.c_str());
        pair->SetAttribute("condim", condim);
        pair->SetAttribute("friction", friction);
        pair->SetAttribute("solref", defaults->Attribute("solref"));
        pair->SetAttribute("solimp", defaults->Attribute("solimp"));
        contact->InsertEndChild(pair);
      }
      break;
    }
    default: break;
  }
  tinyxml2::XMLPrinter printer;
  doc.Print(&printer);
  return printer.CStr();
}

Scene conformance_scene(const Scene& scene, FrictionLaw law, const std::string& mapping) {
  mujoco::MjcfOptions options;
  const std::optional<mujoco::Mapping> m = mujoco::parse_mapping(mapping);
  if (!m) throw std::invalid_argument("conformance_scene: no mapping " + mapping);
  options.mapping = *m;
  const mujoco::GeneratedModel g = mujoco::generate_mjcf(scene, options);
  Scene out = scene;
  out.contact.friction = law;
  out.contact.cone_ratio = g.settings.impratio;
  out.contact.mu_roll = mujoco::cone_mu_roll(scene, g.settings);
  // An obstacle with a law of its own has a coefficient of its own; one
  // without takes the scene's, set above.
  for (size_t i = 0; i < out.obstacles.size(); ++i) {
    ContactOverride& own = out.obstacles[i].contact;
    if (own.mu || own.mu_roll)
      own.mu_roll = mujoco::cone_mu_roll(scene, own.apply(scene.contact), g.settings);
  }
  return out;
}

FrictionParts friction_parts(const Scene& scene, const std::string& mapping, bool mujoco3) {
  FrictionParts p;
  const std::optional<mujoco::Mapping> m = mujoco::parse_mapping(mapping);
  if (!m) throw std::invalid_argument("friction_parts: no mapping " + mapping);
  const Trajectory mj = simulate(*engines::make_stepper(mujoco_engine(*m), scene), scene.sim);
  const Trajectory reference = simulate(scene);
  const Trajectory shape = simulate(conformance_scene(scene, FrictionLaw::ViscousCone, mapping));
  const Trajectory soft = simulate(conformance_scene(scene, FrictionLaw::SoftCone, mapping));
  p.ok = !mj.divergence && !reference.divergence && !shape.divergence && !soft.divergence;
  if (!p.ok) {
    p.total = p.shape = p.push = p.rest = std::numeric_limits<double>::quiet_NaN();
    return p;
  }
  p.total = error_between(reference, mj).max_pos;
  p.shape = error_between(reference, shape).max_pos;
  p.push = error_between(shape, soft).max_pos;
  p.rest = error_between(soft, mj).max_pos;
  if (mujoco3) {
    const Trajectory v3 = simulate(
        *engines::make_stepper(engines::parse_engine("mujoco3:" + mapping), scene), scene.sim);
    if (v3.divergence) return p;
    p.total_v3 = error_between(reference, v3).max_pos;
    p.rest_v3 = error_between(soft, v3).max_pos;
    p.apart_v3 = error_between(mj, v3).max_pos;
  }
  return p;
}

FrictionRow friction_row(const FrictionScene& s) {
  const Trajectory reference = simulate(s.scene);
  FrictionRow row;
  row.name = s.name;
  row.what = s.what;
  if (mujoco3::missing().empty()) {
    const engines::EngineSpec damper = engines::parse_engine("mujoco3:compensated:corners:damper");
    row.mujoco3_damper =
        outcome(reference, simulate(*engines::make_stepper(damper, s.scene), s.scene.sim));
    const engines::EngineSpec shared = engines::parse_engine("mujoco3:compensated");
    row.mujoco3_compensated =
        outcome(reference, simulate(*engines::make_stepper(shared, s.scene), s.scene.sim));
  }
  Trajectory compensated;
  for (mujoco::Mapping m : {mujoco::Mapping::Calibrated, mujoco::Mapping::Compensated}) {
    Trajectory mj = simulate(*engines::make_stepper(mujoco_engine(m), s.scene), s.scene.sim);
    const FrictionOutcome o = outcome(reference, mj);
    (m == mujoco::Mapping::Calibrated ? row.calibrated : row.compensated) = o;
    if (m == mujoco::Mapping::Compensated) compensated = std::move(mj);
  }
  row.split = measure(s.scene, reference,
                      friction_split_xml(s.scene, kSplitShare, kSplitDamper * s.scene.contact.c));
  const Trajectory shape = simulate(conformance_scene(s.scene, FrictionLaw::ViscousCone));
  const Trajectory soft = simulate(conformance_scene(s.scene, FrictionLaw::SoftCone));
  row.shape = error_between(reference, shape).max_pos;
  row.push = error_between(shape, soft).max_pos;
  const TrajectoryError conformance = error_between(soft, compensated);
  row.conformance = conformance.max_pos;
  row.conformance_angle = conformance.max_angle;
  for (FrictionKnob knob : kFrictionKnobs) {
    const std::string xml = friction_knob_xml(s.scene, knob);
    double d = std::numeric_limits<double>::quiet_NaN();
    if (!xml.empty()) {
      mujoco::MujocoStepper stepper(s.scene, xml, "friction scene, " + knob_name(knob));
      const Trajectory mj = simulate(stepper, s.scene.sim);
      d = mj.divergence ? std::numeric_limits<double>::infinity()
                        : error_between(reference, mj).max_pos;
    }
    row.knobs.push_back(d);
  }
  return row;
}

std::vector<FrictionRow> friction_table(unsigned threads) {
  const std::vector<FrictionScene> scenes = friction_scenes();
  std::vector<FrictionRow> rows(scenes.size());
  parallel_for(scenes.size(), threads, [&](size_t i) { rows[i] = friction_row(scenes[i]); });
  return rows;
}

}  // namespace contact2d::analysis
