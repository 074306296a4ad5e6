// validation/report/friction.md: MuJoCo with friction against the reference
// (analysis/friction_table.hpp), the best mapping per scene, and how much of
// what remains the damper's push in MuJoCo's friction cone makes.
#include <algorithm>
#include <cmath>
#include <string>

#include "io/table.hpp"
#include "report/numbers.hpp"
#include "report/pages.hpp"

namespace contact2d::report {

std::string friction_page(const std::vector<analysis::FrictionRow>& rows, double goal) {
  std::string out = R"md(# Friction: how close MuJoCo 2.2.2 gets, and what keeps it away

Written by `contact2d report` (`src/analysis/friction_table.cpp`); the same
scenes with more variants (impratio held at other values, the rolling
coefficient alone): `build/bench/contact2d_friction --variants`. Every scene
is 1 kg, Kelvin–Voigt, k = 1e4 N/m, α = 100, Δt = 1e-4 s, semi-implicit
Euler in both engines; "difference" is the largest distance between the
two bodies' positions over the run.

)md";
  Table t{{"scene", "calibrated (m)", "compensated (m)", "MuJoCo's hop, compensated (m)",
           "push removed (m)", "the push's share"},
          {}};
  int reached = 0;
  for (const analysis::FrictionRow& r : rows) {
    const double best = std::min(r.calibrated.max_pos, r.compensated.max_pos);
    reached += best <= goal;
    const double share = (r.compensated.max_pos - r.split.max_pos) / r.compensated.max_pos;
    add_row(t, {r.what + " (`" + r.name + "`)", g(r.calibrated.max_pos, 3),
                g(r.compensated.max_pos, 3), g(r.compensated.hop, 3), g(r.split.max_pos, 3),
                share >= 0.0 ? g(100.0 * share, 2) + " %"
                             : "none: the split is worse (" + g(r.split.max_pos, 3) + " m)"});
  }
  out += to_markdown(t);
  out += "\n" + std::to_string(reached) + " of " + std::to_string(rows.size()) +
         " scenes are within " + g(goal) + " m under the better of the two mappings.\n";
  out += R"md(
**What keeps MuJoCo away: the push.** In MuJoCo 2.2.2's elliptic cone a
sliding contact's normal force is
`f_n = (k·p − c·v_n + c·√((μ·v_t)² + (μ_roll·ω)²))/(1 + μ²/impratio)`
(docs/mujoco.md derives it from `engine_solver.c` and the tests check it
against `mj_forward`): the damper, which MuJoCo shares between the normal
and the friction rows of a contact, pushes a sliding (or rolling) body up
by `μ·c·|v_t|`, and the body hops — the "hop" column is how far MuJoCo's
centre of mass rises above the reference's. No 2.2.2 setting removes the
term: it does not depend on impratio, solimp, condim or the cone; only `c`
itself scales it (a separate friction reference, `solreffriction`, arrived
in MuJoCo 2.3.6).

**How the share is measured.** "push removed" runs the same scene in MuJoCo
with every contact geom split in two at the same place: a frictionless one
carrying the spring and most of the damper, and a frictional one carrying
)md" + g(100.0 * analysis::kSplitShare) +
         " % of the spring and " + g(analysis::kSplitDamper) + R"md( of the damper, with μ
divided by that share so that the friction limit stays the scene's. The
push then nearly vanishes. The split is a measurement, not a mapping: it
also takes the damper out of the friction limit (μ·(k·p − ρ·v_n) instead of
μ·(k·p − c·v_n)), which decides landings and the start of rolling, so it
makes some scenes worse (the rows marked "none"); there the push's share is
not measured by it.

**The rolling disc** gains the most from `compensated`: MuJoCo's cone puts
the rolling torque and the tangential force a rolling disc needs under one
budget, `(f_t/μ)² + (τ/μ_roll)² ≤ f_n²`, and `compensated` raises the
cone's rolling coefficient to `μ_roll/√(1 − q²)`, `q = κ·μ_roll/(μ·R)`,
`κ = m·R²/(I + m·R²)`, which gives back the reference's torque during
steady rolling (docs/mujoco.md).
)md";
  return out;
}

}  // namespace contact2d::report
