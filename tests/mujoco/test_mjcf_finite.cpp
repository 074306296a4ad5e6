// No generated model carries a number that is not finite (issue 49): with
// gravity 0 the friction damper's stick slope was 0 and its impratio
// 0/0, written as impratio="-nan", and MuJoCo 3 diverged at its first step.
// Every shipped scene (the four, the extreme ones, the game's, the report's
// random ones), on Earth and
// with gravity 0, under every mapping and geometry, for both versions, and
// for MuJoCo 3 with the friction damper where it applies: each model's
// every numeric token is finite.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "core/input_error.hpp"
#include "io/scene_file.hpp"
#include "mujoco/mjcf.hpp"

namespace contact2d {
namespace {

namespace fs = std::filesystem;
namespace mj = contact2d::mujoco;

// The tokens inside attribute values ("...") that read whole as a number
// and are not finite.
std::vector<std::string> non_finite_tokens(const std::string& xml) {
  std::vector<std::string> bad;
  for (size_t open = xml.find('"'); open != std::string::npos;) {
    const size_t close = xml.find('"', open + 1);
    if (close == std::string::npos) break;
    std::istringstream tokens(xml.substr(open + 1, close - open - 1));
    for (std::string token; tokens >> token;) {
      char* end = nullptr;
      const double v = std::strtod(token.c_str(), &end);
      if (end == token.c_str() + token.size() && !std::isfinite(v)) bad.push_back(token);
    }
    open = xml.find('"', close + 1);
  }
  return bad;
}

TEST(MjcfFinite, EveryGeneratedModelHasOnlyFiniteNumbers) {
  std::vector<fs::path> scenes;
  for (const char* dir : {"validation/scenes", "validation/report/random"})
    for (const auto& e : fs::recursive_directory_iterator(fs::path(CONTACT2D_SOURCE_DIR) / dir))
      if (e.path().extension() == ".toml") scenes.push_back(e.path());
  // The four, the extreme ones and the game's (17), the report's random 32.
  ASSERT_GE(scenes.size(), 49u);
  int models = 0;
  for (const fs::path& path : scenes) {
    for (const double gravity : {-1.0, 0.0}) {  // -1: the scene's own
      Scene scene;
      try {
        scene = load_scene(path.string());
      } catch (const InputError& e) {
        ADD_FAILURE() << path << ": " << e.what();
        continue;
      }
      if (gravity >= 0.0) scene.sim.gravity = gravity;
      if (scene.sim.integrator == Integrator::ExplicitEuler)
        scene.sim.integrator = Integrator::SemiImplicitEuler;  // MuJoCo has none
      for (const mj::Mapping mapping : {mj::Mapping::Seed, mj::Mapping::Exact,
                                        mj::Mapping::Calibrated, mj::Mapping::Compensated}) {
        for (const mj::Geometry geometry : {mj::Geometry::CornerSpheres, mj::Geometry::BoxGeoms}) {
          for (const mj::Version version : {mj::Version::V2, mj::Version::V3}) {
            for (const bool damper : {false, true}) {
              if (damper && (version != mj::Version::V3 || mapping != mj::Mapping::Compensated))
                continue;
              mj::MjcfOptions options;
              options.mapping = mapping;
              options.geometry = geometry;
              options.version = version;
              options.friction_damper = damper;
              std::string xml;
              try {
                xml = mj::generate_mjcf(scene, options).xml;
              } catch (const InputError& e) {
                // A mapping that cannot express a scene says so (seed and
                // exact need c > 0): not a model, not this test's subject,
                // unless it is the non-finite refusal itself.
                EXPECT_EQ(std::string(e.what()).find("not finite"), std::string::npos)
                    << path << " g=" << scene.sim.gravity << ": " << e.what();
                continue;
              }
              ++models;
              EXPECT_TRUE(non_finite_tokens(xml).empty())
                  << path << " g=" << scene.sim.gravity << " " << mj::mapping_name(mapping)
                  << (damper ? " damper" : "") << ": " << non_finite_tokens(xml).front();
            }
          }
        }
      }
    }
  }
  std::printf("%d generated models, every number finite\n", models);
  EXPECT_GT(models, 500);
}

}  // namespace
}  // namespace contact2d
