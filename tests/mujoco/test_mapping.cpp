// The generated MJCF: joints, contact geoms, inertia, and each mapping's
// solref checked against its formula (mujoco/mapping.hpp) for a scene whose
// m, k and c are far from the defaults, so that no two formulas coincide
// (ζ = c/(2√(mk)) = 0.0213 here, not 1).
//
// Expected values are computed in the test from the formulas, and the
// compiled model is read back through MuJoCo itself; comparisons allow only
// the rounding of a decimal round trip (format_exact writes the shortest
// text that reads back as the same double, so relative 1e-15).
#include <cmath>

#include "mj_test_util.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/model.hpp"

namespace contact2d {
namespace {

using mujoco::Mapping;
constexpr double kRoundTrip = 1e-15;

// m = 2.7 kg (a box of 2.7 kg), k = 3.3e5 N/m, c = 40 N·s/m. No rolling
// resistance: a box has none (core/scene.hpp's validate).
Scene unusual_box() {
  return test::scene_from(
      "scene = \"box\"\n[body]\nmass = 2.7\nwidth = 0.3\nheight = 0.5\n"
      "[contact]\nk = 3.3e5\nc = 40\nmu = 0.7\nmu_torsion = 0.003\n"
      "[initial]\ny = 0.4\n[sim]\ndt = 2e-4\n");
}

struct Parsed {
  tinyxml2::XMLDocument doc;
  const tinyxml2::XMLElement* root() const { return doc.FirstChildElement("mujoco"); }
  const tinyxml2::XMLElement* body() const {
    return root()->FirstChildElement("worldbody")->FirstChildElement("body");
  }
  const tinyxml2::XMLElement* default_geom() const {
    return root()->FirstChildElement("default")->FirstChildElement("geom");
  }
};

void parse(const std::string& xml, Parsed& out) {
  ASSERT_EQ(out.doc.Parse(xml.c_str()), tinyxml2::XML_SUCCESS);
}

std::vector<double> numbers(const char* text) {
  std::vector<double> out;
  char* end = nullptr;
  for (const char* p = text; *p; p = end) {
    out.push_back(std::strtod(p, &end));
    if (end == p) break;
  }
  return out;
}

void expect_near_rel(double actual, double expected, double rel) {
  EXPECT_NEAR(actual, expected, rel * std::abs(expected)) << "expected " << expected;
}

TEST(Mapping, SeedSolrefIsTheSlidesFormula) {
  const Scene s = unusual_box();
  mujoco::MjcfOptions options;
  options.mapping = Mapping::Seed;
  Parsed p;
  parse(mujoco::generate_mjcf(s, options).xml, p);
  const auto solref = numbers(p.default_geom()->Attribute("solref"));
  ASSERT_EQ(solref.size(), 2u);
  expect_near_rel(solref[0], std::sqrt(2.7 / 3.3e5), kRoundTrip);
  expect_near_rel(solref[1], 40.0 / (2.0 * std::sqrt(2.7 * 3.3e5)), kRoundTrip);
}

TEST(Mapping, ExactSolrefIsTwoMOverC) {
  const Scene s = unusual_box();
  mujoco::MjcfOptions options;
  options.mapping = Mapping::Exact;
  Parsed p;
  parse(mujoco::generate_mjcf(s, options).xml, p);
  const auto solref = numbers(p.default_geom()->Attribute("solref"));
  ASSERT_EQ(solref.size(), 2u);
  expect_near_rel(solref[0], 2.0 * 2.7 / 40.0, kRoundTrip);
  expect_near_rel(solref[1], 40.0 / (2.0 * std::sqrt(2.7 * 3.3e5)), kRoundTrip);
}

// The body's approximate inverse mass, as MuJoCo computes it: the mean of
// the diagonal of J·M⁻¹·Jᵀ at the COM, with slide x, slide z (and a hinge at
// the COM that adds nothing there): (1/m + 0 + 1/m)/3 = 2/(3m).
TEST(Mapping, CalibratedSolrefIsKAndCTimesMujocosInverseMass) {
  const Scene s = unusual_box();
  const auto generated = mujoco::generate_mjcf(s, {});
  const mujoco::ModelPtr model = mujoco::load_model(generated.xml, "calibrated");
  const double inv_mass = model->body_invweight0[2];
  expect_near_rel(inv_mass, 2.0 / (3.0 * 2.7), 1e-12);
  Parsed p;
  parse(generated.xml, p);
  const auto solref = numbers(p.default_geom()->Attribute("solref"));
  ASSERT_EQ(solref.size(), 2u);
  expect_near_rel(solref[0], -3.3e5 * inv_mass, kRoundTrip);
  expect_near_rel(solref[1], -40.0 * inv_mass, kRoundTrip);
  // And MuJoCo's compiled contact parameters are those values, unmixed.
  for (int g = 0; g < model->ngeom; ++g) {
    expect_near_rel(model->geom_solref[2 * g], -3.3e5 * inv_mass, kRoundTrip);
    EXPECT_EQ(model->geom_solimp[5 * g], mujoco::kMinimalSolimp[0]);
    EXPECT_EQ(model->geom_solimp[5 * g + 1], mujoco::kMinimalSolimp[1]);
  }
  EXPECT_EQ(model->opt.cone, mjCONE_ELLIPTIC);
}

// impratio (mapping.hpp): the largest value at which MuJoCo's explicit
// viscous friction (slope impratio·c) does not reverse a slip within one
// step at the contact with the largest tangential inverse mass,
// A_t = 1/m + r_max²/I: impratio = 1/(c·Δt·A_t). Without friction it is
// MuJoCo's floor (1e-15), which switches off the 1e-5 friction MuJoCo keeps.
TEST(Mapping, CalibratedImpratioIsTheChatterFreeBound) {
  const Scene s = unusual_box();  // 0.3 × 0.5 box of 2.7 kg, c = 40, Δt = 2e-4
  const double m = 2.7, inertia = m * (0.3 * 0.3 + 0.5 * 0.5) / 12.0;
  const double r2 = 0.15 * 0.15 + 0.25 * 0.25;
  const double expected = 1.0 / (40.0 * 2e-4 * (1.0 / m + r2 / inertia));
  const auto settings = mujoco::solver_settings(s, Mapping::Calibrated, 1.0, 1);
  expect_near_rel(settings.impratio, expected, 1e-14);
  Scene frictionless = s;
  frictionless.contact.mu = 0.0;
  EXPECT_EQ(mujoco::solver_settings(frictionless, Mapping::Calibrated, 1.0, 1).impratio, 1e-15);
}

// MuJoCo's standard form gives K·d² = 1/(tc²ζ²) and B·d = 2/tc; with
// tc = 2m/c these are k/m and c/m, the direct form's (−k/m, −c/m). The
// seed form is off by 1/ζ² and 1/ζ.
TEST(Mapping, ExactEqualsTheDirectFormAndSeedDoesNotUnlessZetaIsOne) {
  const Scene s = unusual_box();
  const double m = 2.7, k = 3.3e5, c = 40.0;
  const double zeta = c / (2.0 * std::sqrt(m * k));
  const auto exact =
      mujoco::acceleration_gains(mujoco::solver_settings(s, Mapping::Exact, 0.0, 1).solref);
  expect_near_rel(exact.stiffness, k / m, 1e-14);
  expect_near_rel(exact.damping, c / m, 1e-14);
  const auto seed =
      mujoco::acceleration_gains(mujoco::solver_settings(s, Mapping::Seed, 0.0, 1).solref);
  expect_near_rel(seed.stiffness, k / m / (zeta * zeta), 1e-14);
  expect_near_rel(seed.damping, c / m / zeta, 1e-14);
}

// The same check in MuJoCo itself: the exact mapping and a hand-made direct
// form (−k/m, −c/m) step to the same states, to rounding.
TEST(Mapping, ExactAndDirectFormStepIdenticallyInMujoco) {
  Scene s = test::drop_scene(Shape::Box, 200.0, 0.5);
  s.sim.duration = 0.8;  // through the landing
  mujoco::MjcfOptions options;
  options.mapping = Mapping::Exact;
  mujoco::SolverSettings direct = mujoco::solver_settings(s, Mapping::Exact, 0.0, 1);
  direct.solref = {-s.contact.k / s.mass, -s.contact.c / s.mass};
  const auto a = test::run_mujoco(s, options);
  const auto b = test::run_mujoco_xml(s, mujoco::write_mjcf(s, options, direct), "direct");
  const auto e = analysis::error_between(a.trajectory, b.trajectory);
  EXPECT_EQ(e.samples, 801);
  EXPECT_LT(e.max_pos, 1e-12);  // rounding of K and B computed two ways
  EXPECT_LT(e.max_angle, 1e-12);
}

TEST(Mjcf, JointsPerScene) {
  for (Shape shape : {Shape::PointMass, Shape::Box, Shape::TShape, Shape::Circle}) {
    Parsed p;
    parse(mujoco::generate_mjcf(default_scene(shape), {}).xml, p);
    std::vector<std::string> joints;
    for (auto* j = p.body()->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) {
      joints.push_back(std::string(j->Attribute("type")) + " " + j->Attribute("axis"));
    }
    std::vector<std::string> expected = {"slide 1 0 0", "slide 0 0 1"};
    if (shape != Shape::PointMass) expected.push_back("hinge 0 -1 0");
    EXPECT_EQ(joints, expected) << shape_name(shape);
  }
}

// Every geom that can touch (contype or conaffinity non-zero) has condim 6
// and friction (μ, μ_torsion, μ_roll) in the compiled model, and so does
// the plane, so that MuJoCo's max/min mixing changes nothing. μ_roll is the
// circle's only (the others refuse one).
TEST(Mjcf, EveryContactGeomHasCondimSixAndTheSceneFriction) {
  const Scene s = unusual_box();
  for (Shape shape : {Shape::PointMass, Shape::Box, Shape::TShape, Shape::Circle}) {
    Scene scene = default_scene(shape);
    scene.contact = s.contact;
    const double mu_roll = shape == Shape::Circle ? 0.002 : 0.0;
    scene.contact.mu_roll = mu_roll;
    const mujoco::ModelPtr model =
        mujoco::load_model(mujoco::generate_mjcf(scene, {}).xml, "model");
    int contact_geoms = 0;
    for (int g = 0; g < model->ngeom; ++g) {
      if (model->geom_contype[g] == 0 && model->geom_conaffinity[g] == 0) continue;
      ++contact_geoms;
      EXPECT_EQ(model->geom_condim[g], 6) << shape_name(shape) << " geom " << g;
      EXPECT_EQ(model->geom_friction[3 * g], 0.7);
      EXPECT_EQ(model->geom_friction[3 * g + 1], 0.003);
      EXPECT_EQ(model->geom_friction[3 * g + 2], mu_roll);
    }
    // plane + one geom per 2D contact point
    EXPECT_EQ(contact_geoms, 1 + static_cast<int>(make_body(scene).points.size()))
        << shape_name(shape);
  }
}

// Inertia about the hinge (MuJoCo y) is the 2D value; the circle's other
// axes are those of a cylinder of length 2R (docs/mujoco.md).
TEST(Mjcf, InertiaFromTheTwoDimensionalModel) {
  for (Shape shape : {Shape::Box, Shape::TShape, Shape::Circle}) {
    const Scene scene = default_scene(shape);
    const mujoco::ModelPtr model =
        mujoco::load_model(mujoco::generate_mjcf(scene, {}).xml, "model");
    const RigidBody body = make_body(scene);
    expect_near_rel(model->body_mass[1], body.mass, kRoundTrip);
    expect_near_rel(model->body_inertia[3 + 1], body.inertia, 1e-14);  // y
    if (shape == Shape::Circle) {
      const double m = scene.mass, r = scene.radius;
      expect_near_rel(model->body_inertia[3 + 1], 0.5 * m * r * r, 1e-14);
      expect_near_rel(model->body_inertia[3 + 0], 0.25 * m * r * r + m * 4 * r * r / 12, 1e-14);
      expect_near_rel(model->body_inertia[3 + 2], 0.25 * m * r * r + m * 4 * r * r / 12, 1e-14);
    }
  }
}

TEST(Mjcf, SameSceneSameBytes) {
  const Scene s = unusual_box();
  for (Mapping mapping : mujoco::kAllMappings) {
    mujoco::MjcfOptions options;
    options.mapping = mapping;
    options.source = "x.toml";
    EXPECT_EQ(mujoco::generate_mjcf(s, options).xml, mujoco::generate_mjcf(s, options).xml);
  }
}

TEST(Mjcf, TimestepIntegratorAndGravityFromTheScene) {
  Scene s = unusual_box();
  s.sim.integrator = Integrator::RK4;
  s.sim.gravity = 3.5;
  const mujoco::ModelPtr model = mujoco::load_model(mujoco::generate_mjcf(s, {}).xml, "model");
  EXPECT_EQ(model->opt.timestep, 2e-4);
  EXPECT_EQ(model->opt.integrator, mjINT_RK4);
  EXPECT_EQ(model->opt.gravity[2], -3.5);
  s.sim.integrator = Integrator::ImplicitEuler;
  EXPECT_EQ(mujoco::load_model(mujoco::generate_mjcf(s, {}).xml, "model")->opt.integrator,
            mjINT_IMPLICIT);
}

TEST(Mjcf, ExplicitEulerHasNoMujocoCounterpart) {
  Scene s = unusual_box();
  s.sim.integrator = Integrator::ExplicitEuler;
  try {
    mujoco::generate_mjcf(s, {});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("sim.integrator = explicit_euler"), std::string::npos)
        << e.what();
  }
}

TEST(Mjcf, SeedAndExactNeedADamper) {
  Scene s = unusual_box();
  s.contact.c = 0.0;
  for (Mapping mapping : {Mapping::Seed, Mapping::Exact}) {
    mujoco::MjcfOptions options;
    options.mapping = mapping;
    try {
      mujoco::generate_mjcf(s, options);
      FAIL() << "no error";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("contact.c = 0 must be > 0"), std::string::npos)
          << e.what();
    }
  }
  EXPECT_NO_THROW(mujoco::generate_mjcf(s, {}));  // calibrated: direct form with c = 0
}

}  // namespace
}  // namespace contact2d
