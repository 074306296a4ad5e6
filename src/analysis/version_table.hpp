// MuJoCo 3.14 against MuJoCo 2.2.2 on the same scenes: the table of
// validation/report/versions.md, docs/mujoco3.md and
// bench/version_table.cpp (contact2d_version_table).
//
// Per scene and mapping (calibrated, compensated), with the scene's
// friction and without: MuJoCo 2.2.2 runs the model written for it, and
// MuJoCo 3.14 runs the model written for MuJoCo 3 (mujoco/mjcf.hpp,
// Version::V3) and, in turn, that model with one of MuJoCo 3's changes left
// in — its solver tolerance removed (3.11's early exits), its compensated
// corners starting at gap = ε instead of margin = −ε (3.9's margin/gap) —
// and 2.2.2's own model (all of them, and 3.0's slide-only invweight for a
// point mass). Each is the largest position distance from 2.2.2's run. With
// friction under compensated, the reference also meets MuJoCo 3 with its
// friction damper (friction = damper, mapping.hpp).
#pragma once

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "core/scene.hpp"

namespace contact2d::analysis {

struct VersionRow {
  std::string scene, mapping;
  bool friction = true;
  // 2.2.2 ↔ 3.14 (m) on: the model for 3.x; without its tolerance; with the
  // gap as 2.2.2's; 2.2.2's model.
  double for_v3 = 0.0, tolerance = 0.0, gap = 0.0, v2_model = 0.0;
  // The reference ↔ each (m): 2.2.2, 3.14 on its model, 3.14 with the
  // friction damper (NaN where it does not apply: calibrated, no friction).
  double ref_v2 = 0.0, ref_v3 = 0.0;
  double ref_v3_damper = std::numeric_limits<double>::quiet_NaN();
};

struct VersionTable {
  std::vector<VersionRow> rows;
  std::string not_run;  // why MuJoCo 3 did not run here (empty: it ran)
};

struct NamedScene {
  std::string name;
  Scene scene;
};

// Every scene with and without friction (μ = μ_roll = 0), under calibrated
// and compensated (threads: as parallel_for; one Node process per thread).
VersionTable version_table(const std::vector<NamedScene>& scenes, unsigned threads = 0);

// What a row's largest version effect is, in a few words: "3.0's
// slide-only invweight" (2.2.2's model 10× further than either other
// change), else "3.9's margin/gap" or "3.11's early exits", the larger; or
// "none" when each stays within 10× of the model for 3.x. (Header-only: the
// report's pages name it without linking MuJoCo.)
inline std::string version_cause(const VersionRow& row) {
  const double floor = std::max(10.0 * row.for_v3, 1e-12);
  const double largest = std::max({row.tolerance, row.gap, row.v2_model});
  if (largest <= floor) return "none";
  if (row.v2_model > 10.0 * std::max(row.gap, row.tolerance)) return "3.0's slide-only invweight";
  return row.gap >= row.tolerance ? "3.9's margin/gap" : "3.11's early exits";
}

}  // namespace contact2d::analysis
