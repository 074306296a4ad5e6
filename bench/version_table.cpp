// contact2d_version_table: what each of MuJoCo 3's changes does to the
// shipped scenes (with the Kelvin–Voigt damper both engines have), measured
// (analysis/version_table.hpp; docs/mujoco3.md prints its output). Each cell is the largest
// distance of the positions over the run, in metres: MuJoCo 2.2.2 on its model against MuJoCo 3.14
// on the model for 3.x, then with each change left in; and the reference against each version (with
// the friction damper on MuJoCo 3 where it applies).
//
//   build-dir/bench/contact2d_version_table
#include <cmath>
#include <cstdio>
#include <string>

#include "analysis/version_table.hpp"
#include "io/scene_file.hpp"

namespace {

using namespace contact2d;

std::string cell(double d) {
  if (std::isnan(d)) return "—";
  char text[32];
  std::snprintf(text, sizeof text, "%.2g", d);
  return text;
}

}  // namespace

int main() {
  std::vector<analysis::NamedScene> scenes;
  for (const char* name : {"point_mass", "box", "tshape", "circle"})
    scenes.push_back({name, load_scene(std::string(CONTACT2D_SOURCE_DIR) + "/validation/scenes/" +
                                           name + ".toml",
                                       {{"contact.damping", "kelvin_voigt"}})});
  const analysis::VersionTable table = analysis::version_table(scenes);
  if (!table.not_run.empty()) {
    std::fprintf(stderr, "contact2d_version_table: %s\n", table.not_run.c_str());
    return 2;
  }
  for (const bool friction : {true, false}) {
    std::printf(
        "\n%s\n\n| scene | mapping | for 3.x | tolerance | gap | 2.2.2's MJCF | cause | ref ↔ "
        "2.2.2 | "
        "ref ↔ 3.14 | ref ↔ 3.14 damper |\n|---|---|---|---|---|---|---|---|---|---|\n",
        friction ? "With the scenes' friction:" : "Without friction (mu = mu_roll = 0):");
    for (const analysis::VersionRow& r : table.rows) {
      if (r.friction != friction) continue;
      std::printf("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", r.scene.c_str(),
                  r.mapping.c_str(), cell(r.for_v3).c_str(), cell(r.tolerance).c_str(),
                  cell(r.gap).c_str(), cell(r.v2_model).c_str(), analysis::version_cause(r).c_str(),
                  cell(r.ref_v2).c_str(), cell(r.ref_v3).c_str(), cell(r.ref_v3_damper).c_str());
    }
  }
  return 0;
}
