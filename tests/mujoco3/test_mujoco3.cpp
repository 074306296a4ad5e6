// MuJoCo 3 (the engine mujoco3: @mujoco/mujoco 3.14.0 under Node) against
// MuJoCo 2.2.2, the closed forms, and the ways its process can fail.
//
// The closed forms are held to the bounds MuJoCo 2.2.2 is held to
// (analysis/closed_forms.hpp): the models agree to rounding (test_versions.cpp).
#include <signal.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "analysis/closed_forms.hpp"
#include "core/format.hpp"
#include "core/input_error.hpp"
#include "core/run.hpp"
#include "engines/engines.hpp"
#include "io/scene_file.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/model.hpp"
#include "mujoco/stepper.hpp"
#include "mujoco3/stepper.hpp"
#include "mujoco3_test_util.hpp"

namespace contact2d {
namespace {

namespace fs = std::filesystem;
using test::other_drops;

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// MuJoCo 3 gives a body with only slide joints body_invweight0 = 1/m where
// 2.2.2 gives the mean of the diagonal (2/(3m) for an x–z pair): measured
// here on a hand-written model, and the generated point mass, which has the
// hinge "spin" for MuJoCo 3, gets 2.2.2's value from both.
TEST(Mujoco3, PointMassHasTheSameEffectiveMassOnBothVersions) {
  CONTACT2D_NEEDS_MUJOCO3();
  const double m = 1.5;
  const std::string slider =
      "<mujoco><worldbody><body pos=\"0 0 1\"><joint type=\"slide\" axis=\"1 0 0\"/>"
      "<joint type=\"slide\" axis=\"0 0 1\"/><geom type=\"sphere\" size=\"0.1\" mass=\"1.5\"/>"
      "</body></worldbody></mujoco>";
  const auto node = mujoco3::Node::of_this_thread();
  EXPECT_NEAR(node->load(slider, "slider").body_invweight0.at(2), 1.0 / m, 1e-15);
  EXPECT_NEAR(mujoco::load_model(slider, "slider")->body_invweight0[2], 2.0 / (3.0 * m), 1e-15);

  const Scene scene = other_drops(0.5).front();  // the point mass
  for (mujoco::Mapping mapping : mujoco::kAllMappings) {
    mujoco::MjcfOptions options;
    options.mapping = mapping;
    options.version = mujoco::Version::V3;
    const std::string xml = mujoco::generate_mjcf(scene, options).xml;
    const size_t body = mapping == mujoco::Mapping::Compensated ? 2 : 1;
    const double two = mujoco::load_model(xml, "v3 model")->body_invweight0[2 * body];
    const double three = node->load(xml, "v3 model").body_invweight0.at(2 * body);
    EXPECT_NEAR(three, two, 1e-12 * two) << mujoco::mapping_name(mapping);
  }
}

// The batches and the rewind on a change of force: a force that changes
// every 7 steps (the game's way) gives MuJoCo 2.2.2's step-by-step run.
TEST(Mujoco3, ChangingTheAppliedForceMidBatchIsExact) {
  CONTACT2D_NEEDS_MUJOCO3();
  const Scene scene = other_drops(0.6)[1];  // the box
  mujoco::MjcfOptions options;
  mujoco::MujocoStepper two(scene, options);
  mujoco3::Mujoco3Stepper three(scene, options);
  double largest = 0.0;
  for (int i = 0; i < 3000; ++i) {
    if (i % 7 == 0) {
      const Vec3 f(3.0 * std::sin(0.01 * i), 2.0 * std::cos(0.013 * i), 0.1 * std::sin(0.02 * i));
      two.set_applied(f);
      three.set_applied(f);
    }
    ASSERT_EQ(two.step(), StepStatus::Ok);
    ASSERT_EQ(three.step(), StepStatus::Ok);
    largest = std::max(largest, (two.state().q - three.state().q).norm());
  }
  EXPECT_LE(largest, 1e-9);
  std::printf("  force changed every 7 steps: %.3g m apart\n", largest);
  // A reset mid-batch starts again from the given state.
  three.plan(1000);
  for (int i = 0; i < 10; ++i) three.step();
  three.reset(initial_state(scene));
  two.reset(initial_state(scene));
  for (int i = 0; i < 500; ++i) {
    two.step();
    three.step();
  }
  EXPECT_LE((two.state().q - three.state().q).norm(), 1e-9);
}

TEST(Mujoco3, ClosedFormsHoldAsOnMujoco222) {
  CONTACT2D_NEEDS_MUJOCO3();
  const analysis::ClosedFormTable table = analysis::closed_form_table(0, "mujoco3");
  EXPECT_EQ(table.mujoco_engine.rfind("mujoco3 ", 0), 0u) << table.mujoco_engine;
  ASSERT_GE(table.rows.size(), 20u);
  for (const analysis::ClosedFormRow& r : table.rows) {
    const double error = std::abs(r.mujoco - r.quantity.closed_form);
    std::printf("  %-30s %-45s MuJoCo 3 %+.3g (bound %.3g)\n", r.case_id.c_str(),
                r.quantity.name.c_str(), r.mujoco - r.quantity.closed_form,
                r.quantity.mujoco_bound);
    EXPECT_LE(error, r.quantity.mujoco_bound) << r.case_id << ": " << r.quantity.name;
  }
}

// A body sliding to rest on MuJoCo 3 with the friction damper (friction =
// damper) against the reference's tanh law, on scenes the repository does
// not ship: a point mass and a box over masses, dampers, μ, α and speeds.
// Both take semi-implicit Euler steps of 1e-4 s from the rest height.
//  - where it stops: within 1e-4 m (the bound; the stick slope is
//    matched to tanh's stopping excess, mapping.hpp; measured ≤ 1.8e-5 m);
//  - along the way: the laws differ in shape below a slip of ~1/α (tanh
//    rises as tanh(α·v), the damper's friction as b·v up to μ·F_n), a
//    difference of position that scales as 1/(α²·μ·g): measured
//    0.094–0.11/(α²·μ·g) on these cases; held to 0.2/(α²·μ·g) + 1e-5 m,
//    below 1e-4 m for α ≥ 28 s/m at μ = 0.3. The 1e-5 m is what stays at
//    large α, where the shape term vanishes: MuJoCo's contact point sits
//    halfway into the penetration, so its friction tilts a box by a lever
//    longer by d/2 (measured 2.7e-6 m at α = 250).
// The shared damper (MuJoCo 2.2.2's) is printed beside it: its push
// μ·c·|v_t| lifts the body and moves it by 0.5–12 mm.
TEST(Mujoco3Friction, BodiesSlidingToRestStopWhereTheTanhLawDoes) {
  CONTACT2D_NEEDS_MUJOCO3();
  struct Case {
    const char* shape;
    double mass, c, mu, alpha, v0;
  };
  const Case cases[] = {{"point_mass", 0.5, 30, 0.3, 20, 0.8}, {"point_mass", 4, 150, 0.8, 300, 2},
                        {"point_mass", 1.5, 80, 0.5, 60, 1.2}, {"box", 0.6, 20, 0.4, 20, 0.7},
                        {"box", 3, 120, 0.7, 250, 1.8},        {"box", 1.2, 60, 0.25, 80, 1.1}};
  const double k = 2e4;
  for (const Case& c : cases) {
    const bool box = std::string(c.shape) == "box";
    const double half = box ? 0.06 : 0.03;
    // Rest height: the weight on one point (point mass) or two corners (box).
    const double y0 = half - c.mass * 9.81 / k / (box ? 2.0 : 1.0);
    const double duration = c.v0 / (c.mu * 9.81) + 0.3;
    const std::string toml =
        std::string("scene = \"") + c.shape + "\"\n[body]\nmass = " + format_shortest(c.mass) +
        (box ? "\nwidth = 0.25\nheight = 0.12\n" : "\nhalf_height = 0.03\n") +
        "[contact]\nk = 20000\nc = " + format_shortest(c.c) + "\nmu = " + format_shortest(c.mu) +
        "\nalpha = " + format_shortest(c.alpha) +
        "\ndamping = \"kelvin_voigt\"\n[initial]\ny = " + format_shortest(y0) +
        "\nvx = " + format_shortest(c.v0) +
        "\n[sim]\ndt = 1e-4\nduration = " + format_shortest(duration) + "\n";
    const Scene scene = parse_scene(toml, "slide");
    const Trajectory ref = simulate(scene);
    mujoco::MjcfOptions options;
    options.mapping = mujoco::Mapping::Compensated;
    mujoco3::Mujoco3Stepper shared(scene, options);
    options.friction_damper = true;
    mujoco3::Mujoco3Stepper damper(scene, options);
    const Trajectory a = simulate(shared, scene.sim), b = simulate(damper, scene.sim);
    ASSERT_FALSE(b.divergence.has_value());
    double apart = 0.0, shared_apart = 0.0;
    for (size_t i = 0; i < ref.samples.size(); ++i) {
      apart = std::max(apart, (ref.samples[i].state.q - b.samples[i].state.q).head<2>().norm());
      shared_apart =
          std::max(shared_apart, (ref.samples[i].state.q - a.samples[i].state.q).head<2>().norm());
    }
    const double stop = ref.samples.back().state.q.x() - b.samples.back().state.q.x();
    std::printf(
        "  %-10s m %-4g c %-4g mu %-4g alpha %-4g v0 %-4g: damper %.3g m apart (stop %+.3g), "
        "shared %.3g m\n",
        c.shape, c.mass, c.c, c.mu, c.alpha, c.v0, apart, stop, shared_apart);
    EXPECT_LE(std::abs(stop), 1e-4) << c.shape << " alpha " << c.alpha;
    EXPECT_LE(apart, 0.2 / (c.alpha * c.alpha * c.mu * 9.81) + 1e-5)
        << c.shape << " alpha " << c.alpha;
    // The body came to rest (the run is long enough to measure the stop).
    EXPECT_LE(std::abs(b.samples.back().state.v.x()), 1e-3) << c.shape;
  }
}

// The damper is MuJoCo 3's (solreffriction) over compensated: elsewhere a
// one-line error naming why.
TEST(Mujoco3Friction, TheDamperNeedsMujoco3AndCompensated) {
  const Scene scene = other_drops(0.5)[1];
  mujoco::MjcfOptions options;
  options.friction_damper = true;
  options.mapping = mujoco::Mapping::Compensated;
  EXPECT_THROW(mujoco::generate_mjcf(scene, options), InputError);  // 2.2.2
  options.version = mujoco::Version::V3;
  options.mapping = mujoco::Mapping::Calibrated;
  try {
    mujoco::generate_mjcf(scene, options);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("only over --mapping compensated"), std::string::npos);
  }
  options.mapping = mujoco::Mapping::Compensated;
  const std::string xml = mujoco::generate_mjcf(scene, options).xml;
  EXPECT_NE(xml.find("solreffriction="), std::string::npos);
  EXPECT_NE(xml.find("geom2=\"ground\""), std::string::npos);
}

TEST(Mujoco3, AModelMujoco3RefusesIsOneLine) {
  CONTACT2D_NEEDS_MUJOCO3();
  try {
    mujoco3::Node::of_this_thread()->load(
        "<mujoco><worldbody><geom type=\"sphere\" size=\"-1\"/></worldbody></mujoco>", "bad.xml");
    FAIL() << "loaded";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_EQ(what.rfind("bad.xml: MuJoCo 3.14.0 cannot load the model: ", 0), 0u) << what;
    EXPECT_NE(what.find("size"), std::string::npos) << what;
  }
}

TEST(Mujoco3, AKilledNodeIsAnEngineErrorAndTheNextRunStartsAnother) {
  CONTACT2D_NEEDS_MUJOCO3();
  const Scene scene = other_drops(0.6)[1];
  mujoco3::Mujoco3Stepper stepper(scene, {});
  for (int i = 0; i < 100; ++i) stepper.step();
  const int pid = mujoco3::Node::of_this_thread()->pid();
  ASSERT_EQ(::kill(pid, SIGKILL), 0);
  try {
    for (int i = 0; i < 100000; ++i) stepper.step();
    FAIL() << "stepped on";
  } catch (const EngineError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_NE(what.find("killed by signal 9"), std::string::npos) << what;
    EXPECT_NE(what.find("scripts/setup"), std::string::npos) << what;
  }
  mujoco3::Mujoco3Stepper again(scene, {});
  EXPECT_NE(mujoco3::Node::of_this_thread()->pid(), pid);
  EXPECT_EQ(again.step(), StepStatus::Ok);
}

// The lockfile pins the package by its integrity hash: the sha512 of the
// 3.14.0 tarball as the registry publishes it (npm view
// @mujoco/mujoco@3.14.0 dist.integrity), and what is installed is that.
TEST(Mujoco3, TheLockfilePinsTheRegistrysHashAndItIsInstalled) {
  const char* kIntegrity =
      "sha512-WPUYidu4Fx8+uM4hQv80SOA0ifpWGrsNJguKs8JBV8SCTxjKQ2/rqsh880nUH0/"
      "Vwa8vuefghvCQkkoed3bkUg==";
  const fs::path dir = fs::path(CONTACT2D_SOURCE_DIR) / "src/mujoco3";
  const std::string lock = read_file(dir / "package-lock.json");
  EXPECT_NE(lock.find("\"node_modules/@mujoco/mujoco\": {\n      \"version\": \"3.14.0\",\n      "
                      "\"integrity\": \"" +
                      std::string(kIntegrity) + "\""),
            std::string::npos)
      << lock;
  EXPECT_NE(read_file(dir / "package.json").find("\"@mujoco/mujoco\": \"3.14.0\""),
            std::string::npos);
  EXPECT_EQ(mujoco3::kVersion, "3.14.0");
  CONTACT2D_NEEDS_MUJOCO3();
  EXPECT_NE(read_file(dir / "node_modules/.package-lock.json").find(kIntegrity), std::string::npos);
}

}  // namespace
}  // namespace contact2d
