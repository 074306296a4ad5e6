// MuJoCo's own diagnosis of a divergence (mujoco/divergence.hpp): in its
// terms, never the reference solver's advice.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "engines/engines.hpp"
#include "mj_test_util.hpp"
#include "mujoco/divergence.hpp"

namespace contact2d {
namespace {

// A disc on the ground, k = 1e7 N/m, m = 1 kg: ω = √(k/m) = 3162 rad/s, so
// Δt = 2e-3 gives ω·Δt = 6.3, three times MuJoCo's Euler limit (≈ 2).
Scene stiff_disc(const std::string& integrator) {
  return test::scene_from(
      "scene = \"circle\"\n[body]\nmass = 1.0\nradius = 0.1\n"
      "[contact]\nk = 1e7\nc = 200\nmu = 0.5\nalpha = 100\ndamping = \"kelvin_voigt\"\n"
      "[initial]\ny = 0.3\nvx = 1.0\n"
      "[sim]\ndt = 2e-3\nduration = 0.5\nintegrator = \"" +
      integrator + "\"\n");
}

TEST(MujocoDivergence, SpeaksOfMujocosIntegratorAndNeverOfTheReferenceSolver) {
  for (const char* integrator : {"semi_implicit_euler", "implicit_euler"}) {
    SCOPED_TRACE(integrator);
    const engines::EngineRun run = engines::run_engine("mujoco", stiff_disc(integrator));
    ASSERT_TRUE(run.trajectory.divergence.has_value());
    const std::string& m = run.divergence_message;
    std::printf("%s\n", m.c_str());
    EXPECT_NE(m.find("MuJoCo diverged"), std::string::npos);
    EXPECT_NE(m.find("ω·Δt"), std::string::npos);
    EXPECT_NE(m.find("solref"), std::string::npos);
    // The reference's diagnosis would talk about its Newton iteration and
    // suggest its implicit Euler; neither exists in MuJoCo.
    EXPECT_EQ(m.find("Newton"), std::string::npos);
    EXPECT_EQ(m.find("implicit_euler"), std::string::npos);
    EXPECT_EQ(m.find("integrator semi_implicit"), std::string::npos);
  }
  // MuJoCo's implicit integrator has Euler's limit for contacts: the
  // message says so instead of calling it unconditionally stable.
  const engines::EngineRun implicit = engines::run_engine("mujoco", stiff_disc("implicit_euler"));
  EXPECT_NE(implicit.divergence_message.find("Euler's limit"), std::string::npos);
}

TEST(MujocoDivergence, TheReferenceKeepsItsOwnDiagnosis) {
  Scene scene = stiff_disc("semi_implicit_euler");
  const engines::EngineRun run = engines::run_engine("ref", scene);
  ASSERT_TRUE(run.trajectory.divergence.has_value());
  EXPECT_EQ(run.divergence_message.find("MuJoCo"), std::string::npos);
  EXPECT_NE(run.divergence_message.find("semi-implicit Euler"), std::string::npos);
}

// The calibrated mapping's contact as MuJoCo integrates it: with d = 1e-4,
// A = 1/m and Â = 2/(3m) (point mass), ω² = A·k·Â/(d·A + (1 − d)·Â) =
// (k/m)/(1 + d·(A/Â − 1)), i.e. √(k/m) to a relative d·(A/Â − 1)/2 = 2.5e-5;
// the same factor for ζ. Tolerance 1e-4: four times that, far below any
// error in the gains (which would be O(1)).
TEST(MujocoDivergence, ContactRegimeOfTheCalibratedMappingIsTheScenesOscillator) {
  Scene scene = test::drop_scene(Shape::PointMass, 50.0, 0.0);
  mujoco::MujocoStepper stepper(scene, mujoco::mjcf_options("calibrated", "", "test"));
  const double inv_weight = 2.0 / (3.0 * scene.mass);
  const mujoco::MujocoContactRegime r =
      mujoco::mujoco_contact_regime(scene, stepper.settings(), inv_weight);
  const double omega = std::sqrt(scene.contact.k / scene.mass);
  const double zeta = scene.contact.c / (2.0 * std::sqrt(scene.contact.k * scene.mass));
  EXPECT_NEAR(r.omega / omega, 1.0, 1e-4);
  EXPECT_NEAR(r.zeta / zeta, 1.0, 1e-4);
}

}  // namespace
}  // namespace contact2d
