// contact2d_version_table: what each of MuJoCo 3's changes does to the same
// scene, measured (docs/mujoco3.md prints its output). For each shipped
// scene (validation/scenes/*.toml) and the mappings calibrated and
// compensated, MuJoCo 2.2.2 runs the model written for it, and MuJoCo 3.14
// runs, in turn:
//   for 3.x       the model written for MuJoCo 3 (mujoco/mjcf.hpp, Version::V3)
//   tolerance     the same without its tolerance="1e-12" (3.11's early exits)
//   gap           the same with the compensated corners' gap = ε instead of
//                 margin = −ε (3.9's margin/gap; calibrated has neither)
//   2.2.2's MJCF  the model written for 2.2.2, unchanged (all three, and for
//                 the point mass no hinge "spin": 3.0's slide-only invweight)
// Each cell is the largest distance of the positions from 2.2.2's, over the
// scene's run, in metres, with friction as the scene has it and, in a second
// table, without (μ = μ_roll = 0).
//
//   build-dir/bench/contact2d_version_table
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include "core/run.hpp"
#include "io/scene_file.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/stepper.hpp"
#include "mujoco3/node_mujoco.hpp"
#include "mujoco3/stepper.hpp"

namespace {

using namespace contact2d;

double distance(const Trajectory& a, const Trajectory& b) {
  double d = 0.0;
  for (size_t i = 0; i < std::min(a.samples.size(), b.samples.size()); ++i)
    d = std::max(d, (a.samples[i].state.q - b.samples[i].state.q).head<2>().norm());
  return d;
}

std::string cell(double d) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2g", d);
  return text;
}

void table(bool friction) {
  std::printf(
      "\n%s\n\n| scene | mapping | for 3.x | tolerance | gap | 2.2.2's MJCF "
      "|\n|---|---|---|---|---|---|\n",
      friction ? "With the scenes' friction:" : "Without friction (mu = mu_roll = 0):");
  const std::string dir = std::string(CONTACT2D_SOURCE_DIR) + "/validation/scenes";
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".toml") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  for (const std::string& name : names) {
    std::vector<Override> overrides;
    if (!friction) overrides = {{"contact.mu", "0"}, {"contact.mu_roll", "0"}};
    const Scene scene = load_scene(dir + "/" + name + ".toml", overrides);
    for (mujoco::Mapping mapping : {mujoco::Mapping::Calibrated, mujoco::Mapping::Compensated}) {
      mujoco::MjcfOptions options;
      options.mapping = mapping;
      const mujoco::GeneratedModel two = mujoco::generate_mjcf(scene, options);
      options.version = mujoco::Version::V3;
      const mujoco::GeneratedModel three = mujoco::generate_mjcf(scene, options);
      mujoco::MujocoStepper native(scene, two.xml, name);
      const Trajectory base = simulate(native, scene.sim);
      const std::string variants[] = {
          three.xml, std::regex_replace(three.xml, std::regex(" tolerance=\"1e-12\""), ""),
          std::regex_replace(three.xml, std::regex("margin=\"-1e-09\""), "gap=\"1e-09\""), two.xml};
      std::printf("| %s | %s |", name.c_str(), std::string(mujoco::mapping_name(mapping)).c_str());
      for (const std::string& xml : variants) {
        mujoco3::Mujoco3Stepper wasm(scene, xml, name, three.settings);
        std::printf(" %s |", cell(distance(base, simulate(wasm, scene.sim))).c_str());
      }
      std::printf("\n");
    }
  }
}

}  // namespace

int main() {
  const std::string missing = mujoco3::missing();
  if (!missing.empty()) {
    std::fprintf(stderr, "contact2d_version_table: %s\n", missing.c_str());
    return 2;
  }
  std::printf("MuJoCo %s against MuJoCo 2.2.2: largest position distance (m) over each run\n",
              std::string(mujoco3::kVersion).c_str());
  table(true);
  table(false);
  return 0;
}
