// The header comment of the generated MJCF states every derived value with
// the formula that computes it. Here each number is recomputed from the
// formula the header states, with the scene's own parameters and arithmetic
// written out in the test (nothing of src/mujoco/mapping.cpp is called), for
// every built-in scene (validation/scenes/*.toml) under every mapping (and,
// for the box and the T, both geometries), and for validation/scenes/extreme
// (frictionless, refsafe-clamped, RK4 and implicit scenes among them, under
// every mapping); the values the header gives are
// also the ones in the file. Which values depend on Δt is checked by
// regenerating at 10·Δt: only the lines that say "depends on Δt" (and the
// line of Δt itself) may change. Also here: condim per scene (only what the
// scene needs), and that the file's qpos0, what a viewer shows, is the
// scene's initial pose.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "mj_test_util.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/model.hpp"

namespace contact2d {
namespace {

using mujoco::Geometry;
using mujoco::Mapping;

constexpr double kRel = 1e-14;  // two orders of summation of a few terms

const char* const kScenes[] = {"point_mass", "box", "tshape", "circle"};
const char* const kExtremeScenes[] = {"heavy_damping_implicit",
                                      "heavy_damping_semi_implicit",
                                      "impact_50ms",
                                      "impact_50ms_coarse_step",
                                      "large_alpha",
                                      "large_mass",
                                      "long_rest",
                                      "rolling_to_rest",
                                      "stiff_k1e9",
                                      "stiff_k1e9_too_large_step",
                                      "tiny_mass",
                                      "tiny_mass_default_step"};

struct Case {
  std::string scene;
  Mapping mapping;
  Geometry geometry;
};

std::string case_name(const Case& c) {
  std::string scene = c.scene;
  std::replace(scene.begin(), scene.end(), '/', '_');
  return scene + "_" + std::string(mujoco::mapping_name(c.mapping)) + "_" +
         std::string(mujoco::geometry_name(c.geometry));
}

void PrintTo(const Case& c, std::ostream* os) { *os << case_name(c); }

std::string source_of(const std::string& scene) { return "validation/scenes/" + scene + ".toml"; }

Scene built_in(const std::string& scene) {
  return load_scene(test::source_dir() + "/" + source_of(scene));
}

std::string generate(const Scene& scene, const Case& c) {
  mujoco::MjcfOptions options;
  options.mapping = c.mapping;
  options.geometry = c.geometry;
  options.source = source_of(c.scene);
  return mujoco::generate_mjcf(scene, options).xml;
}

std::string header_of(const std::string& xml) {
  const size_t begin = xml.find("<!--"), end = xml.find("-->");
  if (begin == std::string::npos || end == std::string::npos) return "";
  return xml.substr(begin + 4, end - begin - 4);
}

// The number printed right after `label` (which includes the formula).
double after(const std::string& header, const std::string& label) {
  const size_t at = header.find(label);
  if (at == std::string::npos) {
    ADD_FAILURE() << "the header does not say \"" << label << "\":\n" << header;
    return NAN;
  }
  return std::strtod(header.c_str() + at + label.size(), nullptr);
}

bool says(const std::string& header, const std::string& text) {
  return header.find(text) != std::string::npos;
}

void expect_rel(double actual, double expected, const std::string& what) {
  EXPECT_NEAR(actual, expected, kRel * std::abs(expected)) << what;
}

// 2D mass properties, written out: a box, or the parts of a T.
struct Body2d {
  double m = 0.0;
  double inertia = 0.0;  // about the COM
  double r = 0.0;        // farthest contact point from the COM
  int points = 0;        // 2D contact points
  int parts = 0;
};

Body2d body_of(const Scene& s) {
  Body2d b;
  switch (s.shape) {
    case Shape::PointMass:
      b.m = s.mass;
      b.points = 1;
      return b;
    case Shape::Circle:
      b.m = s.mass;
      b.inertia = s.mass * s.radius * s.radius / 2.0;
      b.r = s.radius;
      b.points = 1;
      return b;
    case Shape::Ellipse:
      b.m = s.mass;
      b.inertia = s.inertia > 0.0 ? s.inertia : s.mass * (s.a * s.a + s.b * s.b) / 4.0;
      b.r = std::max(s.a, s.b);
      b.points = 1;
      return b;
    case Shape::Box:
      b.m = s.mass;
      b.inertia = s.mass * (s.width * s.width + s.height * s.height) / 12.0;
      b.r = std::hypot(s.width / 2.0, s.height / 2.0);
      b.points = 4;
      b.parts = 1;
      return b;
    case Shape::TShape: {
      double cx = 0.0, cy = 0.0;
      for (const BoxPart& p : s.parts) {
        b.m += p.mass;
        cx += p.mass * p.x;
        cy += p.mass * p.y;
      }
      cx /= b.m;
      cy /= b.m;
      for (const BoxPart& p : s.parts) {
        const double dx = p.x - cx, dy = p.y - cy;
        b.inertia +=
            p.mass * ((p.width * p.width + p.height * p.height) / 12.0 + dx * dx + dy * dy);
        for (double sx : {-0.5, 0.5}) {
          for (double sy : {-0.5, 0.5}) {
            b.r = std::max(b.r, std::hypot(dx + sx * p.width, dy + sy * p.height));
          }
        }
      }
      b.points = 4 * static_cast<int>(s.parts.size());
      b.parts = static_cast<int>(s.parts.size());
      return b;
    }
  }
  return b;
}

int expected_condim(const ContactParams& p) {
  if (p.mu_roll > 0.0 || p.mu_torsion > 0.0) return 6;
  return p.mu > 0.0 ? 3 : 1;
}

class Header : public ::testing::TestWithParam<Case> {};

TEST_P(Header, EveryNumberIsItsStatedFormula) {
  const Case& c = GetParam();
  const Scene s = built_in(c.scene);
  ASSERT_TRUE(c.scene != "tshape" || !s.parts.empty());  // the test reads the parts
  const std::string xml = generate(s, c);
  const std::string h = header_of(xml);
  tinyxml2::XMLDocument doc;
  ASSERT_EQ(doc.Parse(xml.c_str()), tinyxml2::XML_SUCCESS);
  const tinyxml2::XMLElement* root = doc.FirstChildElement("mujoco");
  const tinyxml2::XMLElement* option = root->FirstChildElement("option");
  const tinyxml2::XMLElement* size = root->FirstChildElement("size");
  const tinyxml2::XMLElement* geom = root->FirstChildElement("default")->FirstChildElement("geom");

  // The scene path as given, and the scene's own values as they are.
  EXPECT_TRUE(says(h, "scene file: " + source_of(c.scene) + " (as given)")) << h;
  const ContactParams& p = s.contact;
  EXPECT_EQ(after(h, "contact: k "), p.k);
  EXPECT_EQ(after(h, " N/m, c "), p.c);
  EXPECT_EQ(after(h, ", mu "), p.mu);
  EXPECT_EQ(after(h, ", alpha "), p.alpha);
  EXPECT_EQ(after(h, ", mu_roll "), p.mu_roll);
  EXPECT_EQ(after(h, ", mu_torsion "), p.mu_torsion);
  EXPECT_EQ(after(h, "sim: dt "), s.sim.dt);
  EXPECT_EQ(after(h, "duration "), s.sim.duration);
  EXPECT_EQ(after(h, "gravity "), s.sim.gravity);
  EXPECT_EQ(after(h, "initial: x "), s.initial.q.x());
  EXPECT_EQ(after(h, ", y "), s.initial.q.y());
  EXPECT_EQ(after(h, ", theta "), s.initial.q.z());
  EXPECT_EQ(after(h, ", vx "), s.initial.v.x());
  EXPECT_EQ(after(h, ", vy "), s.initial.v.y());
  EXPECT_EQ(after(h, ", omega "), s.initial.v.z());

  // Body.
  const Body2d b = body_of(s);
  const double m = b.m, k = p.k, cd = p.c, dt = s.sim.dt;
  expect_rel(after(h, "body: m "), m, "m");
  switch (s.shape) {
    case Shape::Box: expect_rel(after(h, "I = m (w^2 + h^2)/12 = "), b.inertia, "I"); break;
    case Shape::Circle: expect_rel(after(h, "I = m R^2/2 = "), b.inertia, "I"); break;
    case Shape::TShape:
      expect_rel(after(h,
                       "I = sum over parts of m_i ((w_i^2 + h_i^2)/12 + |p_i - COM|^2), "
                       "COM = sum m_i p_i / m = "),
                 b.inertia, "I");
      break;
    case Shape::Ellipse:
      expect_rel(after(h, "I = the scene's body.inertia, or a plate's m (a^2 + b^2)/4 = "),
                 b.inertia, "I");
      break;
    case Shape::PointMass: EXPECT_FALSE(says(h, "I = ")); break;
  }

  // Mapping.
  const bool compensated = c.mapping == Mapping::Compensated;
  const bool elliptic = c.mapping == Mapping::Calibrated || compensated;
  if (elliptic) {
    double a = 0.0, scale = 0.0;
    std::string solref_label;
    if (compensated) {
      // The lever L = sqrt(I (3 G A_max - 2/m)) of the massless body
      // "contacts", I about the hinge that turns it: the body's, or for the
      // point mass the hinge "spin" about MuJoCo z, whose inertia is the
      // generator's solid sphere 0.4 m max(h, 0.01)^2 (mjcf.cpp).
      const double r_sphere = std::max(s.half_height, 0.01);
      const double turning =
          s.shape == Shape::PointMass ? 0.4 * m * r_sphere * r_sphere : b.inertia;
      const bool lever_arm = s.shape == Shape::Box || s.shape == Shape::TShape;
      const double a_max = lever_arm ? 1.0 / m + b.r * b.r / turning : 1.0 / m;
      const double gain = mujoco::kCompensatingGain;
      expect_rel(after(h, "L = "), std::sqrt(turning * (3 * gain * a_max - 2.0 / m)), "L");
      a = after(h, "A = body_invweight0 of \"contacts\" = ");
      expect_rel(a, gain * a_max, "A = G A_max");
      scale = 1e-4 / m + (1 - 1e-4) * a;
      solref_label = "solref = (-k D/n, -c D/n) = (";
    } else {
      a = after(h, "A = body_invweight0 = ");
      expect_rel(a, 2.0 / (3.0 * m), "A: MuJoCo's 2/(3m)");
      scale = a;
      solref_label = "solref = (-k A/n, -c A/n) = (";
    }
    const double n = after(h, "n = ");
    const bool box_geoms = c.geometry == Geometry::BoxGeoms && b.parts > 0;
    EXPECT_EQ(n, box_geoms ? 2.0 : 1.0);
    const double solref0 = after(h, solref_label);
    const double solref1 = after(h, solref_label + mujoco::format_exact(solref0) + ", ");
    expect_rel(solref0, -k * scale / n, "solref[0]");
    expect_rel(solref1, -cd * scale / n, "solref[1]");
    std::istringstream file_solref(geom->Attribute("solref"));
    double f0 = 0.0, f1 = 0.0;
    file_solref >> f0 >> f1;
    EXPECT_EQ(f0, solref0);
    EXPECT_EQ(f1, solref1);
    EXPECT_STREQ(option->Attribute("cone"), "elliptic");
    if (expected_condim(p) == 1) {
      EXPECT_TRUE(says(h, "impratio: not written (condim 1")) << h;
      EXPECT_EQ(option->Attribute("impratio"), nullptr);
      EXPECT_FALSE(says(h, "(depends on Δt")) << h;  // no other value does
    } else if (!(cd > 0.0)) {
      EXPECT_TRUE(says(h, "impratio: not written (c = 0")) << h;
      EXPECT_EQ(option->Attribute("impratio"), nullptr);
    } else {
      ASSERT_TRUE(p.mu > 0.0 || (s.shape == Shape::Circle && p.mu_roll > 0.0)) << h;
      double a_t = 0.0;
      if (s.shape == Shape::PointMass) {
        a_t = 1.0 / m;
        expect_rel(after(h, "A_t = 1/m = "), a_t, "A_t");
      } else {
        expect_rel(after(h, "r = "), b.r, "r");
        a_t = 1.0 / m + b.r * b.r / b.inertia;
        expect_rel(after(h, "A_t = 1/m + r^2/I = "), a_t, "A_t");
      }
      double impratio = 0.0;
      std::string label;
      if (s.shape == Shape::Circle && p.mu_roll > 0.0) {
        const double mu = std::max(p.mu, 1e-5);
        label = "impratio = min(1/(c Δt A_t), I (max(mu, 1e-5)/mu_roll)^2/(c Δt)) = ";
        impratio = std::min(1.0 / (cd * dt * a_t),
                            b.inertia * (mu / p.mu_roll) * (mu / p.mu_roll) / (cd * dt));
      } else {
        label = "impratio = 1/(c Δt A_t) = ";
        impratio = 1.0 / (cd * dt * a_t);
      }
      impratio = std::clamp(impratio, 1e-15, 1e10);
      const double printed = after(h, label);
      expect_rel(printed, impratio, "impratio");
      EXPECT_TRUE(says(h, label + mujoco::format_exact(printed) + " (depends on Δt")) << h;
      EXPECT_EQ(option->DoubleAttribute("impratio", 1.0), printed);
    }
  } else {
    const double tc = c.mapping == Mapping::Seed ? std::sqrt(m / k) : 2.0 * m / cd;
    const double zeta = cd / (2.0 * std::sqrt(m * k));
    const std::string tc_label =
        c.mapping == Mapping::Seed ? "timeconst = sqrt(m/k) = " : "timeconst = 2m/c = ";
    const double tc_printed = after(h, tc_label);
    expect_rel(tc_printed, tc, "timeconst");
    expect_rel(after(h, "dampratio = c/(2 sqrt(m k)) = "), zeta, "dampratio");
    const std::string used_label = "MuJoCo uses timeconst max(timeconst, 2 Δt) = ";
    const double used = after(h, used_label);
    EXPECT_EQ(used, std::max(tc_printed, 2.0 * dt));
    EXPECT_TRUE(says(h, used_label + mujoco::format_exact(used) + " s (refsafe; depends on Δt"))
        << h;
    std::istringstream file_solref(geom->Attribute("solref"));
    double f0 = 0.0, f1 = 0.0;
    file_solref >> f0 >> f1;
    EXPECT_EQ(f0, tc_printed);
    EXPECT_EQ(option->Attribute("impratio"), nullptr);
    EXPECT_EQ(option->Attribute("cone"), nullptr);
  }

  // condim and the buffer sizes.
  const int condim = expected_condim(p);
  EXPECT_EQ(after(h, "  condim "), condim);
  EXPECT_EQ(geom->IntAttribute("condim"), condim);
  const int contacts = c.geometry == Geometry::BoxGeoms && b.parts > 0 ? 4 * b.parts : b.points;
  EXPECT_EQ(after(h, "size: P = "), contacts);
  const int nconmax = 2 * contacts + 10 * 4;
  EXPECT_EQ(after(h, "nconmax = 2 P + 40 = "), nconmax);
  const int rows = elliptic ? 6 : 2 * (6 - 1);
  EXPECT_EQ(after(h, "njmax = " + std::to_string(rows) + " nconmax = "), rows * nconmax);
  EXPECT_EQ(size->IntAttribute("nconmax"), nconmax);
  EXPECT_EQ(size->IntAttribute("njmax"), rows * nconmax);
}

// Regenerated at 10·Δt, the header changes only in the lines that say
// "depends on Δt" and in the line that gives Δt.
TEST_P(Header, OnlyTheValuesMarkedDependOnTheTimeStep) {
  const Case& c = GetParam();
  const Scene s = built_in(c.scene);
  Scene coarse = s;
  coarse.sim.dt = 10.0 * s.sim.dt;
  std::istringstream a(header_of(generate(s, c))), b(header_of(generate(coarse, c)));
  std::string la, lb;
  int changed = 0;
  while (std::getline(a, la) && std::getline(b, lb)) {
    if (la == lb) continue;
    ++changed;
    EXPECT_TRUE(la.rfind("  sim: dt ", 0) == 0 || says(la, "depends on Δt")) << la << "\n" << lb;
  }
  EXPECT_GE(changed, 1);
}

std::vector<Case> cases() {
  std::vector<Case> out;
  for (const char* scene : kScenes) {
    for (Mapping mapping : mujoco::kAllMappings) {
      out.push_back({scene, mapping, Geometry::CornerSpheres});
      const std::string name = scene;
      if (name == "box" || name == "tshape") out.push_back({scene, mapping, Geometry::BoxGeoms});
    }
  }
  for (const char* scene : kExtremeScenes) {
    for (Mapping mapping : mujoco::kAllMappings) {
      out.push_back({std::string("extreme/") + scene, mapping, Geometry::CornerSpheres});
    }
  }
  return out;
}

INSTANTIATE_TEST_SUITE_P(BuiltInScenes, Header, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           return case_name(info.param);
                         });

// condim is what the scene needs, in the compiled model on every geom that
// touches (the plane too, so that MuJoCo's max-mixing keeps it): the
// built-in scenes with their friction (the circle rolls: 6), without any
// friction (1), and with torsional or rolling friction only (6).
TEST(Mjcf, CondimPerScene) {
  struct Expect {
    const char* scene;
    int with_friction;
  };
  for (const Expect e :
       {Expect{"point_mass", 3}, Expect{"box", 3}, Expect{"tshape", 3}, Expect{"circle", 6}}) {
    const Scene s = built_in(e.scene);
    Scene none = s;
    none.contact.mu = none.contact.mu_roll = none.contact.mu_torsion = 0.0;
    Scene torsion = none;
    torsion.contact.mu_torsion = 0.01;
    Scene rolling = none;
    rolling.contact.mu_roll = 0.01;
    for (const auto& [scene, condim] : {std::pair<const Scene*, int>{&s, e.with_friction},
                                        {&none, 1},
                                        {&torsion, 6},
                                        {&rolling, 6}}) {
      EXPECT_EQ(mujoco::contact_condim(scene->contact), condim) << e.scene;
      const mujoco::ModelPtr model =
          mujoco::load_model(mujoco::generate_mjcf(*scene, {}).xml, e.scene);
      for (int g = 0; g < model->ngeom; ++g) {
        if (model->geom_contype[g] == 0 && model->geom_conaffinity[g] == 0) continue;
        EXPECT_EQ(model->geom_condim[g], condim) << e.scene << " geom " << g;
      }
    }
  }
}

// A viewer opened on the file shows qpos0: there, every contact geom of the
// built-in scenes is where the 2D initial pose puts its contact point, and
// keyframe 0 is qpos0 with the initial velocities.
TEST(Mjcf, QposZeroIsTheInitialPoseAndTheKeyframeAddsTheVelocities) {
  for (const char* name : kScenes) {
    const Scene s = built_in(name);
    const mujoco::ModelPtr model = mujoco::load_model(mujoco::generate_mjcf(s, {}).xml, name);
    const mujoco::DataPtr data = mujoco::make_data(model.get());
    mj_resetData(model.get(), data.get());  // qpos = qpos0
    mj_kinematics(model.get(), data.get());
    const RigidBody body = make_body(s);
    const Vec3 q0 = s.initial.q;
    const double th = body.rotates ? q0.z() : 0.0;
    const double co = std::cos(th), si = std::sin(th);
    int matched = 0;
    for (int g = 0; g < model->ngeom; ++g) {
      const std::string geom = mj_id2name(model.get(), mjOBJ_GEOM, g);
      if (geom.rfind("corner", 0) != 0) continue;
      const Vec2& r = body.points[std::stoul(geom.substr(6))];
      EXPECT_NEAR(data->geom_xpos[3 * g + 0], q0.x() + co * r.x() - si * r.y(), 1e-15) << name;
      EXPECT_NEAR(data->geom_xpos[3 * g + 1], 0.0, 1e-15) << name;
      EXPECT_NEAR(data->geom_xpos[3 * g + 2], q0.y() + si * r.x() + co * r.y(), 1e-15) << name;
      ++matched;
    }
    if (s.shape == Shape::Box || s.shape == Shape::TShape) {
      EXPECT_EQ(matched, static_cast<int>(body.points.size())) << name;
    }
    EXPECT_NEAR(data->xpos[3], q0.x(), 1e-15) << name;
    EXPECT_NEAR(data->xpos[5], q0.y(), 1e-15) << name;
    ASSERT_EQ(model->nkey, 1);
    for (int i = 0; i < model->nq; ++i) EXPECT_EQ(model->key_qpos[i], model->qpos0[i]) << name;
    EXPECT_EQ(model->key_qvel[0], s.initial.v.x()) << name;
    EXPECT_EQ(model->key_qvel[1], s.initial.v.y()) << name;
    if (body.rotates) {
      EXPECT_EQ(model->qpos0[2], q0.z()) << name;  // the hinge's qpos is θ itself
      EXPECT_EQ(model->key_qvel[2], s.initial.v.z()) << name;
    }
  }
}

}  // namespace
}  // namespace contact2d
