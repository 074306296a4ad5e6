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

namespace {

// The title, the difference per scene and its three parts, and what keeps
// MuJoCo away.
std::string friction_difference_section(const std::vector<analysis::FrictionRow>& rows,
                                        double goal) {
  std::string out = R"md(# Friction: how close MuJoCo 2.2.2 gets, and what keeps it away

Written by `contact2d report` (`src/analysis/friction_table.cpp`); the same
numbers with the rolling coefficient and impratio variants:
`build/bench/contact2d_friction --variants`. Every scene is 1 kg,
Kelvin–Voigt, k = 1e4 N/m, Δt = 1e-4 s, semi-implicit Euler in both engines;
"difference" is the largest distance between the two bodies' positions over
the run.

## The difference, and what it is made of

The last three columns take the difference apart, each a measured distance
between two runs: **shape** is the reference's tanh law against the shape of
MuJoCo's cone without its push (`friction_law = "viscous_cone"`: viscous
inside the cone, μ·Fn on it, sliding and rolling under one budget);
**push** is that against MuJoCo's full effective law
(`friction_law = "soft_cone"`: the push, its divisor, the contact point
halfway into the penetration); **the rest** is the reference running the
soft cone against MuJoCo itself (compensated) — what is not the friction
law. Both cone laws run at compensated's impratio and rolling coefficient
(docs/physics.md). The compensated difference is at most the sum of the
three (triangle inequality).

)md";
  Table t{{"scene", "calibrated (m)", "compensated (m)", "MuJoCo's hop (m)", "shape (m)",
           "push (m)", "the rest (m)", "MuJoCo 3.14, damper (m)"},
          {}};
  int reached = 0, conforms = 0, push_larger = 0;
  int damper_ran = 0, damper_reached = 0, damper_better = 0;  // MuJoCo 3.14's damper
  double worst_rest = 0.0;
  for (const analysis::FrictionRow& r : rows) {
    const double best = std::min(r.calibrated.max_pos, r.compensated.max_pos);
    reached += best <= goal;
    conforms += r.conformance <= goal;
    worst_rest = std::max(worst_rest, r.conformance);
    push_larger += r.push > r.shape;
    add_row(t, {r.what + " (`" + r.name + "`)", format_significant(r.calibrated.max_pos, 3),
                format_significant(r.compensated.max_pos, 3),
                format_significant(r.compensated.hop, 3), format_significant(r.shape, 3),
                format_significant(r.push, 3), format_significant(r.conformance, 3),
                std::isnan(r.mujoco3_damper.max_pos)
                    ? std::string("not run")
                    : format_significant(r.mujoco3_damper.max_pos, 3)});
    if (!std::isnan(r.mujoco3_damper.max_pos)) {
      ++damper_ran;
      damper_reached += r.mujoco3_damper.max_pos <= goal;
      damper_better += r.mujoco3_damper.max_pos < best;
    }
  }
  out += to_markdown(t);
  out += "\n" + std::to_string(reached) + " of " + std::to_string(rows.size()) +
         " scenes are within " + format_significant(goal) +
         " m under the better of the two mappings. With the reference running MuJoCo's own "
         "law (the rest), " +
         std::to_string(conforms) + " of " + std::to_string(rows.size()) + " are, the largest " +
         format_significant(worst_rest, 3) +
         " m: what separates the engines is the friction law. Of it the " +
         "push is the larger part in " + std::to_string(push_larger) + " of " +
         std::to_string(rows.size()) + " scenes, the shape in the others.\n";
  if (damper_ran > 0)
    out +=
        "\nThe last column is MuJoCo 3.14 with the friction rows' own damper "
        "(`mujoco3:compensated:corners:damper`, versions.md, docs/mujoco3.md), which 2.2.2 "
        "cannot have: " +
        std::to_string(damper_reached) + " of " + std::to_string(damper_ran) + " scenes within " +
        format_significant(goal) +
        " m, closer than 2.2.2's better "
        "mapping in " +
        std::to_string(damper_better) + " of " + std::to_string(damper_ran) + ".\n";
  out += R"md(
**What keeps MuJoCo away: the push.** In MuJoCo 2.2.2's elliptic cone a
sliding contact's normal force is
`f_n = (k·p − c·v_n + c·√((μ·v_t)² + (μ_roll·ω)²))/(1 + μ²/impratio)`
(docs/mujoco.md derives it from `engine_solver.c` and the tests check it
against `mj_forward`): the damper, which MuJoCo shares between the normal
and the friction rows of a contact, pushes a sliding (or rolling) body up
by `μ·c·|v_t|`, and the body hops — the "hop" column is how far MuJoCo's
centre of mass rises above the reference's. No 2.2.2 setting removes the
term (the table below tries each): it does not depend on impratio, solimp,
condim or the cone; only `c` itself scales it. A friction reference of its
own, `solreffriction`, arrived in MuJoCo 2.3.6.
)md";
  return out;
}

// Every 2.2.2 setting that touches friction, each alone; the split; the
// rolling disc.
std::string friction_settings_section(const std::vector<analysis::FrictionRow>& rows) {
  std::string out = R"md(
## Every setting of MuJoCo 2.2.2 that touches friction, each alone

The calibrated model with one setting changed, its difference to the
reference (m); "—" where the setting does not apply (condim 6 on a scene
that has it). "split" is the measurement of the push
(below), on the compensated model.

)md";
  std::vector<std::string> columns{"scene", "calibrated"};
  for (analysis::FrictionKnob k : analysis::kFrictionKnobs)
    columns.push_back(analysis::knob_name(k));
  columns.emplace_back("split");
  Table knobs{columns, {}};
  for (const analysis::FrictionRow& r : rows) {
    std::vector<std::string> cells{"`" + r.name + "`", format_significant(r.calibrated.max_pos, 3)};
    for (double d : r.knobs)
      cells.push_back(std::isnan(d) ? "—" : std::isinf(d) ? "diverged" : format_significant(d, 3));
    cells.push_back(format_significant(r.split.max_pos, 3));
    add_row(knobs, cells);
  }
  out += to_markdown(knobs);
  out += R"md(
impratio moves only the divisor `1 + μ²/impratio` and the stiffness of
the viscous stick; the pyramidal cone's edges carry the same push
(`J_n ± μ·J_t` rows with `−B·(v_n ± μ·v_t)` in their reference) and make
the contact stiffer at rest; noslip leaves the pushed normal force alone
(it only removes the tangential slip); condim 6 adds torsion and rolling
rows that are idle in the plane; a margin with an equal gap finds
contacts earlier without making them active; an explicit `<pair>` carries
the same solref, solimp, condim and friction as the geoms (in 2.2.2 a pair
has no friction-specific reference either).

**The split** runs the same scene in MuJoCo with every contact geom split in
two at the same place: a frictionless one carrying the spring and most of
the damper, and a frictional one carrying
)md" + format_significant(100.0 * analysis::kSplitShare) +
         " % of the spring and " + format_significant(analysis::kSplitDamper) +
         R"md( of the damper, with μ
divided by that share so that the friction limit stays the scene's. The
push then nearly vanishes, but the split also takes the damper out of the
friction limit (μ·(k·p − ρ·v_n) instead of μ·(k·p − c·v_n)), which decides
landings and the start of rolling: it is a measurement, not a mapping. No
arrangement of 2.2.2 contacts at one point escapes this: a frictional
contact carrying the share w of the spring and a damper c_f bounds friction
by μ_f·(w·k·p − c_f·v_n) and pushes by μ_f·c_f·|v_t|; matching the
reference's bound μ·(k·p − c·v_n) needs μ_f = μ/w and c_f = w·c, and then the
push is μ·c·|v_t| again.

**The rolling disc** gains the most from `compensated`: MuJoCo's cone puts
the rolling torque and the tangential force a rolling disc needs under one
budget, `(f_t/μ)² + (τ/μ_roll)² ≤ f_n²`, and `compensated` raises the
cone's rolling coefficient to `μ_roll/√(1 − q²)`, `q = κ·μ_roll/(μ·R)`,
`κ = m·R²/(I + m·R²)`, which gives back the reference's torque during
steady rolling (docs/mujoco.md).
)md";
  return out;
}

}  // namespace

std::string friction_page(const std::vector<analysis::FrictionRow>& rows, double goal) {
  return friction_difference_section(rows, goal) + friction_settings_section(rows);
}

}  // namespace contact2d::report
