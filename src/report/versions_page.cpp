// validation/report/versions.md: MuJoCo 3.14 beside MuJoCo 2.2.2
// (analysis/version_table.hpp): per scene and mapping the distance between
// the versions, what of MuJoCo 3's changes it would be without the model
// written for 3.x, each version against the reference, and MuJoCo 3's
// friction damper.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "io/table.hpp"
#include "report/numbers.hpp"
#include "report/pages.hpp"

namespace contact2d::report {
namespace {

std::string cell(double v) { return std::isnan(v) ? "—" : format_significant(v, 2); }

Table version_rows(const analysis::VersionTable& table, bool friction) {
  Table t{{"scene", "mapping", "2.2.2 ↔ 3.14 (m)", "tolerance left in", "gap left in",
           "2.2.2's model", "largest change", "ref ↔ 2.2.2", "ref ↔ 3.14", "ref ↔ 3.14 damper"},
          {}};
  for (const analysis::VersionRow& r : table.rows) {
    if (r.friction != friction) continue;
    add_row(t,
            {r.scene, r.mapping, cell(r.for_v3), cell(r.tolerance), cell(r.gap), cell(r.v2_model),
             analysis::version_cause(r), cell(r.ref_v2), cell(r.ref_v3), cell(r.ref_v3_damper)});
  }
  return t;
}

}  // namespace

std::string versions_page(const analysis::VersionTable& table) {
  std::string out = R"md(# MuJoCo 3.14 beside MuJoCo 2.2.2

Written by `contact2d report` (`src/analysis/version_table.cpp`; the same
table: `build/bench/contact2d_version_table`; docs/mujoco3.md explains the
engine `mujoco3`). The shipped scenes with the Kelvin–Voigt damper both
engines have, semi-implicit Euler at Δt = 1e-4 s; each number is the
largest distance between two runs' positions over the run.

)md";
  if (!table.not_run.empty()) {
    out += "**Not run here**: " + table.not_run + "\n";
    return out;
  }
  out += R"md(**The columns.** MuJoCo 2.2.2 runs the model written for it; MuJoCo 3.14
runs the model written for MuJoCo 3 (`contact2d generate --engine
mujoco3`): "2.2.2 ↔ 3.14". The next three run MuJoCo 3.14 with one of its
changes left in: the solver's tolerance removed (3.11's early exits), the
compensated corners starting at `gap` as on 2.2.2 instead of `margin`
(3.9's margin/gap), and 2.2.2's own model (all of them, and for the point
mass 3.0's effective mass of a body with only slide joints). "largest
change" names the one that matters most (or "none" when each stays within
10× of the first column). The last three are each version against the
reference, and MuJoCo 3 with its friction damper (`--friction damper`,
compensated only).

## With friction

)md";
  out += to_markdown(version_rows(table, true));
  out += "\n## Without friction\n\n";
  out += to_markdown(version_rows(table, false));
  double largest = 0.0, damper_best = std::numeric_limits<double>::infinity();
  std::string damper_scene;
  for (const analysis::VersionRow& r : table.rows) {
    largest = std::max(largest, r.for_v3);
    if (!std::isnan(r.ref_v3_damper) && r.ref_v3_damper < damper_best) {
      damper_best = r.ref_v3_damper;
      damper_scene = r.scene;
    }
  }
  out += "\nWith the model written for it, MuJoCo 3.14 follows 2.2.2 within " +
         format_significant(largest, 2) +
         " m on every row: the same contact law, two builds of one algorithm that part only "
         "by rounding.\n";
  out += R"md(
## Which version and mapping, for what

- **Without friction**, on either version: `--mapping compensated` gives the
  contact law of k and c (the rows above, "ref ↔" under compensated). On
  MuJoCo 3 write the model with `contact2d generate --engine mujoco3`: 2.2.2's
  model there moves by the amounts of the "left in" columns.
- **With friction** on MuJoCo 2.2.2 no setting removes the damper's push
  (friction.md). On MuJoCo 3 use `mujoco3:compensated:corners:damper`
  (`--friction damper`): the friction rows get a damper of their own, and a
  body sliding to rest stops where the reference's tanh law stops it; the
  landings keep the friction law's shape under load and MuJoCo's contact
  point (docs/mujoco3.md measures each).
)md";
  if (!damper_scene.empty())
    out += "\nClosest with the damper here: " + damper_scene + ", " +
           format_significant(damper_best, 2) + " m from the reference.\n";
  return out;
}

}  // namespace contact2d::report
