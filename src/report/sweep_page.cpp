// validation/report/sweep.md: the converged reference, work–precision
// tables, observed orders, the cheapest run per accuracy, MuJoCo against the
// reference and the per-step cost (report/pages.hpp).
#include <algorithm>
#include <cmath>
#include <string>

#include "io/table.hpp"
#include "report/numbers.hpp"
#include "report/pages.hpp"

namespace contact2d::report {
namespace {

// A number as the analysis CSV spells it ("%.9g"): tolerances, steps and
// order ranges on the page are written the way the runs were configured.
std::string csv(double x) { return format_significant(x, 9); }
std::string ms(double seconds) { return format_significant(seconds * 1e3); }

const SceneSweep* find_sweep(const SweepData& d, const std::string& name) {
  for (const SceneSweep& s : d.sweeps) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

const StudyRow* study_at(const SceneSweep* sweep, double tol) {
  if (!sweep) return nullptr;
  for (const StudyRow& row : sweep->study) {
    if (csv(row.tol) == csv(tol)) return &row;
  }
  return nullptr;
}

std::string reference_table(const SweepData& d, const std::vector<double>& tols) {
  Table t{{"tol"}, {}};
  for (const std::string& s : d.scenes) t.columns.push_back(s);
  for (double tol : tols) {
    std::vector<std::string> row{csv(tol)};
    for (const std::string& s : d.scenes) {
      const StudyRow* r = study_at(find_sweep(d, s), tol);
      row.push_back(r && r->ok ? format_significant(r->max_pos, 2) + " m, " + ms(r->seconds) + " ms"
                               : "–");
    }
    add_row(t, row);
  }
  return to_markdown(t);
}

std::string run_key(const SweepRun& r) {
  return (r.engine == "ref" ? "" : r.engine + " ") + r.integrator;
}

std::string error_table(const SceneSweep& s) {
  std::vector<std::string> keys;
  std::vector<double> dts;
  for (const SweepRun& r : s.runs) {
    if (r.integrator == "dopri5_events") continue;
    if (std::find(keys.begin(), keys.end(), run_key(r)) == keys.end()) keys.push_back(run_key(r));
    if (std::find(dts.begin(), dts.end(), r.dt) == dts.end()) dts.push_back(r.dt);
  }
  std::stable_sort(dts.begin(), dts.end(), [](double a, double b) { return a > b; });
  Table t{{"engine / integrator"}, {}};
  for (double dt : dts) t.columns.push_back("dt = " + csv(dt));
  t.columns.push_back("ms at 1e-4");
  for (const std::string& key : keys) {
    std::vector<std::string> row{key};
    std::string time = "–";
    for (double dt : dts) {
      std::string cell = "–";
      for (const SweepRun& r : s.runs) {
        if (r.integrator == "dopri5_events" || run_key(r) != key || r.dt != dt) continue;
        cell = r.status == "ok"         ? format_significant(r.max_pos, 2)
               : r.status == "diverged" ? "diverged"
                                        : "failed";
        if (csv(r.dt) == "0.0001" && r.status == "ok") time = ms(r.seconds);
      }
      row.push_back(cell);
    }
    row.push_back(time);
    add_row(t, row);
  }
  return to_markdown(t);
}

std::string dopri_line(const SceneSweep& s) {
  std::string out;
  for (const SweepRun& r : s.runs) {
    if (r.integrator != "dopri5_events" || r.status != "ok") continue;
    out += (out.empty() ? "" : "; ") + std::string("tol ") + csv(r.tol) + ": " +
           format_significant(r.max_pos, 2) + " m in " + ms(r.seconds) + " ms";
  }
  return out;
}

std::string orders_table(const SweepData& d) {
  Table t{{"scene", "engine", "integrator", "against", "nominal", "observed", "dt range (runs)",
           "why below nominal"},
          {}};
  for (const SceneSweep& s : d.sweeps) {
    for (const OrderRow& o : s.orders) {
      add_row(t, {s.scene, o.engine, o.integrator, o.against, csv(o.nominal),
                  o.observed ? fixed(*o.observed, 2) + " ± " + fixed(o.observed_stderr, 2) : "–",
                  o.observed
                      ? csv(o.dt_min) + "–" + csv(o.dt_max) + " (" + std::to_string(o.points) + ")"
                      : "–",
                  o.note});
    }
  }
  return to_markdown(t);
}

// The cheapest (wall clock) run of each kind whose largest position error
// stays at or below each target.
std::string accuracy_table(const SweepData& d) {
  Table t{{"scene", "target (max position error)", "cheapest fixed-step reference run",
           "adaptive DOPRI5 + events", "cheapest MuJoCo run"},
          {}};
  const std::pair<double, const char*> targets[] = {
      {1e-2, "1e-2"}, {1e-3, "1e-3"}, {1e-4, "1e-4"}, {1e-6, "1e-6"}};
  for (const std::string& name : d.scenes) {
    const SceneSweep* s = find_sweep(d, name);
    if (!s) continue;
    for (const auto& [target, target_text] : targets) {
      const SweepRun *ref = nullptr, *dense = nullptr, *mujoco = nullptr;
      for (const SweepRun& r : s->runs) {
        if (r.status != "ok" || r.max_pos > target) continue;
        const SweepRun*& best = r.integrator == "dopri5_events" ? dense
                                : r.engine == "ref"             ? ref
                                                                : mujoco;
        if (!best || r.seconds < best->seconds) best = &r;
      }
      auto fixed_step = [](const SweepRun* r) {
        return r ? r->integrator + " at dt = " + csv(r->dt) + ": " + ms(r->seconds) + " ms"
                 : std::string("none of the runs");
      };
      add_row(t, {name, std::string(target_text) + " m", fixed_step(ref),
                  dense ? "tol " + csv(dense->tol) + ": " + ms(dense->seconds) + " ms" : "none",
                  fixed_step(mujoco)});
    }
  }
  return to_markdown(t);
}

// The smallest MuJoCo error against the reference over a sweep's runs.
const SweepRun* mujoco_floor(const SceneSweep& s) {
  const SweepRun* floor = nullptr;
  for (const SweepRun& r : s.runs) {
    if (r.status != "ok" || r.engine != "mujoco") continue;
    if (!floor || r.max_pos < floor->max_pos) floor = &r;
  }
  return floor;
}

std::string mujoco_floor_table(const SweepData& d) {
  Table t{{"scene", "smallest MuJoCo error against the reference (any integrator, dt)",
           "MuJoCo Euler against its own dt = 1e-4 run, at dt = 1e-3 / 2e-4",
           "reference semi-implicit Euler at dt = 1e-4"},
          {}};
  for (const SceneSweep& s : d.sweeps) {
    std::string own1 = "–", own4 = "–", ref = "–";
    for (const SweepRun& r : s.runs) {
      if (r.status != "ok") continue;
      const bool euler = r.integrator == "semi_implicit_euler";
      if (r.engine == "mujoco" && euler && csv(r.dt) == "0.001" && r.self_max_pos)
        own1 = format_significant(*r.self_max_pos, 2);
      if (r.engine == "mujoco" && euler && csv(r.dt) == "0.0002" && r.self_max_pos)
        own4 = format_significant(*r.self_max_pos, 2);
      if (r.engine == "ref" && euler && csv(r.dt) == "0.0001")
        ref = format_significant(r.max_pos, 2) + " m";
    }
    const SweepRun* floor = mujoco_floor(s);
    add_row(t, {s.name,
                floor ? format_significant(floor->max_pos, 2) + " m (" + floor->integrator +
                            ", dt = " + csv(floor->dt) + ")"
                      : "–",
                own1 + " m / " + own4 + " m", ref});
  }
  return to_markdown(t);
}

// The bench's per-step table (CPU time and wall clock per step, and their
// ratio), then the libm floors; "-" where MuJoCo did not run.
std::string bench_block(const Bench& b) {
  if (!b.ran) return "(contact2d_bench was not built)";
  auto ns = [](double x, int decimals) { return fixed(x, decimals) + "ns"; };
  Table t{{"scene", "integrator", "ref cpu", "mj cpu", "ratio", "ref wall", "mj wall"}, {}};
  for (const BenchRow& r : b.rows) {
    const bool mj = r.mj_cpu_ns.has_value();
    add_row(t, {r.scene, r.integrator, ns(r.ref_cpu_ns, 1), mj ? ns(*r.mj_cpu_ns, 0) : "-",
                mj ? fixed(*r.mj_cpu_ns / r.ref_cpu_ns, 0) + "x" : "-", ns(r.ref_real_ns, 1),
                mj ? ns(*r.mj_real_ns, 0) : "-"});
  }
  return "per step at each scene's dt; MuJoCo: models/<scene>.calibrated.xml (its Euler is "
         "semi-implicit).\n"
         "ratio = mj_step / reference step, on CPU time (robust to other load on the machine) and "
         "wall clock\n" +
         to_text(t) + "\nfloor (CPU, each call feeding the next): sincos " + ns(b.sincos_ns, 1) +
         ", tanh " + ns(b.tanh_ns, 1) + ", a step with no contact points " +
         ns(b.free_flight_ns, 1);
}

// A bench ratio as the table prints it (whole numbers).
double printed_ratio(const BenchRow& r) { return std::round(*r.mj_cpu_ns / r.ref_cpu_ns); }
std::string whole(double x) { return fixed(x, 0); }

std::string per_step_budget(const Bench& b) {
  std::string out;
  for (const BenchRow& r : b.rows) {
    if (r.integrator != "semi_implicit_euler" || !r.mj_cpu_ns) continue;
    out +=
        (out.empty() ? "" : ", ") + r.scene + " " + whole(std::round(*r.mj_cpu_ns) / 100.0) + " ns";
  }
  return out;
}

// The 100× and 30× budgets of this run set against the libm links a step in
// contact carries (the floors of the same run): a tanh for a slowly slipping
// contact, and a sincos before it for a body whose contact points turn
// (Bench::turning); implicit Euler twice that (the Newton step from the
// predictor, then the residual its convergence test reads). Names the scenes
// whose budget is below their chain. Empty when the bench did not time its
// floors.
std::string budget_against_floors(const Bench& b) {
  if (b.tanh_ns <= 0.0 || b.sincos_ns <= 0.0) return "";
  std::string semi, implicit;
  for (const BenchRow& r : b.rows) {
    if (!r.mj_cpu_ns) continue;
    const bool turns = std::find(b.turning.begin(), b.turning.end(), r.scene) != b.turning.end();
    const double chain = b.tanh_ns + (turns ? b.sincos_ns : 0.0);
    const char* links = turns ? "sincos + tanh" : "tanh";
    std::string* list = nullptr;
    double budget = 0.0, need = 0.0;
    if (r.integrator == "semi_implicit_euler") {
      list = &semi;
      budget = *r.mj_cpu_ns / 100.0;
      need = chain;
    } else if (r.integrator == "implicit_euler") {
      list = &implicit;
      budget = *r.mj_cpu_ns / 30.0;
      need = 2.0 * chain;
    }
    if (list == nullptr || budget >= need) continue;
    *list += (list->empty() ? "" : ", ") + r.scene + " (budget " + fixed(budget, 0) + " ns, " +
             (list == &implicit ? "2 × (" + std::string(links) + ")" : std::string(links)) + " " +
             fixed(need, 1) + " ns)";
  }
  std::string out = "In this run one tanh (contact2d's bounded_tanh) takes " + fixed(b.tanh_ns, 1) +
                    " ns and a sincos " + fixed(b.sincos_ns, 1) + " ns.";
  out += semi.empty()
             ? " No scene's 100× budget is below its sincos and tanh chain."
             : " The sincos and tanh chain of a step whose contact slips slower than 22/α is alone "
               "longer than the whole 100× budget of " +
                   semi + ".";
  out += implicit.empty()
             ? " No scene's 30× budget for implicit Euler (two force stages a step in contact: "
               "the Newton step from the predictor, then the residual its convergence test "
               "reads) is below twice its chain."
             : " Implicit Euler in contact evaluates the force stage twice a step (the Newton "
               "step from the predictor, then the residual its convergence test reads), and "
               "twice the chain is longer than the 30× budget of " +
                   implicit + ".";
  return out;
}

std::string targets(const SweepData& d) {
  std::string out;
  double worst = 0.0;
  bool any = false;
  for (const std::string& s : d.scenes) {
    if (const StudyRow* r = study_at(find_sweep(d, s), 1e-12)) {
      worst = any ? std::max(worst, r->seconds) : r->seconds;
      any = true;
    }
  }
  if (any) {
    out += "- Converged reference (tol 1e-12) under 100 ms per built-in scene: slowest " +
           ms(worst) + " ms — " + (worst < 0.1 ? "met" : "not met") + ".\n";
  }
  std::vector<double> euler, all;
  for (const BenchRow& r : d.bench.rows) {
    if (!r.mj_cpu_ns) continue;
    all.push_back(printed_ratio(r));
    if (r.integrator == "semi_implicit_euler") euler.push_back(printed_ratio(r));
  }
  const auto e = range_of(euler), a = range_of(all);
  if (d.bench.ran && e && a) {
    out +=
        "- Reference step ≥ 100× cheaper than mj_step: semi-implicit Euler against MuJoCo Euler " +
        whole(e->lo) + "–" + whole(e->hi) + "× (CPU time), all integrators " + whole(a->lo) + "–" +
        whole(a->hi) + "× — " + (e->lo >= 100 ? "met" : "not met on every scene (section 6)") +
        ".\n";
  }
  return out;
}

// The standard errors of the reference's observed orders on the bouncing
// scenes (every scene but the rolling disc), "0.01…0.3".
std::string bouncing_stderr(const SweepData& d) {
  std::vector<double> errors;
  for (const std::string& name : d.scenes) {
    const SceneSweep* s = find_sweep(d, name);
    if (!s || name == "circle") continue;
    for (const OrderRow& o : s->orders) {
      if (o.engine == "ref" && o.against == "reference" && o.observed)
        errors.push_back(o.observed_stderr);
    }
  }
  const auto range = range_of(errors);
  if (!range) return "–";
  auto one = [](double x) { return format_significant(x, 1); };
  return one(range->lo) == one(range->hi) ? one(range->lo) : one(range->lo) + "…" + one(range->hi);
}

// MuJoCo's errors against the reference at one step, "0.001–0.0012".
std::string mujoco_errors_at(const SceneSweep& s, double dt) {
  std::vector<double> errors;
  for (const SweepRun& r : s.runs) {
    if (r.engine == "mujoco" && r.status == "ok" && csv(r.dt) == csv(dt))
      errors.push_back(r.max_pos);
  }
  const auto range = range_of(errors);
  return range ? range_text(*range, [](double x) { return format_significant(x, 2); }) : "–";
}

// The circle's observed orders: the Euler methods and RK4 (section 3).
std::string circle_orders(const SweepData& d) {
  const SceneSweep* circle = find_sweep(d, "circle");
  if (!circle) return "(no sweep of the circle in this run)";
  const auto euler = range_of(
      observed_orders(*circle, {"explicit_euler", "semi_implicit_euler", "implicit_euler"}));
  std::string out =
      (euler ? range_text(*euler, [](double x) { return fixed(x, 2); }) : std::string("–")) +
      " for the Euler methods, ";
  const OrderRow* rk4 = nullptr;
  for (const OrderRow& o : circle->orders) {
    if (o.engine == "ref" && o.against == "reference" && o.integrator == "rk4" && o.observed)
      rk4 = &o;
  }
  if (!rk4) return out + "no fitted order for RK4";
  return out + "≈ " + fixed(*rk4->observed, 1) + " for RK4 between " + sci(rk4->dt_max) +
         "\n  and " + sci(rk4->dt_min) + " s";
}

// The title, where the numbers come from, and the sweep commands.
std::string sweep_intro(const SweepData& d) {
  const RunInfo& info = d.info;
  std::string out = R"md(# Error against run time, a converged reference, and observed orders

Generated by `contact2d report` (it runs the sweeps, stability maps and
extreme scenes of `contact2d sweep`, `contact2d stability` and `contact2d
simulate`, and `contact2d_bench` from the same build): do not edit, run it
again. Every
number on this page comes from that run; wall-clock times depend on the
machine and on what else it was doing (this run: )md" +
                    std::to_string(info.cores) + " cores, load\n" + info.load +
                    " at the end). The whole run took " + std::to_string(info.total_seconds) +
                    " s\n(sweeps " + std::to_string(info.sweep_seconds) + " s, stability maps " +
                    std::to_string(info.stability_seconds) + " s).\n";
  out += R"md(
The commands, per scene: `contact2d sweep validation/scenes/SCENE.toml
--engines )md" +
         d.engines + " --mujoco-dts " + d.mujoco_dts + R"md( --mujoco-integrators
semi_implicit_euler,rk4 --repeats 2 --study-csv … --csv … --orders-csv … --plot
validation/report/sweep.SCENE.png` (default integrators: all four; default
steps 1e-3, 5e-4, 2e-4, 1e-4, 5e-5, 2e-5, 1e-5 s for the reference; MuJoCo
only down to 1e-4 s, its step costs )md" +
         (mujoco_cost_ratio(d.bench) ? *mujoco_cost_ratio(d.bench) + " more"
                                     : std::string("far more")) +
         R"md(, and only its Euler and RK4:
its implicit integrator is implicit in joint damping and actuators, not in
the contact, and gave the same trajectories as its Euler to every printed
digit in a trial sweep). Errors are taken
at the output samples (every 1 ms): position error = distance between the
COMs, the largest over the run ("max") and at the end.
)md";
  return out;
}

// 1. The converged reference: its method, self-consistency and cost.
std::string converged_reference_section(const SweepData& d) {
  std::string out = R"md(
## 1. The converged reference

`src/core/dense_reference.{hpp,cpp}`: Dormand–Prince 5(4) with error control
and its fourth-order dense output. The contact force is only piecewise smooth,
so the integrator keeps a *mode* per contact point (in contact; damper or
Kelvin–Voigt force active) and evaluates the force on the smooth branch of
that mode, extended past the switching surface. It watches every switching
function — a point's height (entry, exit), its normal velocity (the
compression damper switching), k·d − c·v_n (the Kelvin–Voigt force reaching
zero) — along each accepted step, locates a sign change on the dense output to
rounding level (Illinois regula falsi), redoes the step exactly up to it,
flips the mode and restarts. A function that is on the same side at both ends
of a step but dips in between (a corner swinging through the ground within
one step) is caught by locating its extremum from the end derivatives. Between
events the right-hand side is analytic (tanh friction and tanh rolling
resistance are smooth), so the method keeps its fifth order through impacts.
It works for any body and parameters (not for scenes with static obstacles,
which it refuses); `tests/reference/test_dense_reference.cpp` checks it
against closed-form bounces with both damping laws (to 1e-11 m), a grazing
corner inside a 0.25 s step, and the core's force law on random states.

Self-consistency: the largest position error of the reference at each
tolerance against the same at tol = 1e-14, at the output times, and the
wall-clock time of one run (best of 3; rtol = atol = tol):

)md";
  out += reference_table(d, {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13});
  // The reference at 1e-12 per scene: time, events, self-consistency, and
  // how much the scene magnifies a change of the initial height.
  auto at12 = [&](const std::string& scene, std::string (*field)(const StudyRow&)) {
    const StudyRow* r = study_at(find_sweep(d, scene), 1e-12);
    return r ? field(*r) : std::string("–");
  };
  auto four = [&](std::string (*field)(const StudyRow&), const char* unit, const char* last_sep) {
    std::string out;
    for (size_t i = 0; i < d.scenes.size(); ++i) {
      out += (i == 0                     ? ""
              : i + 1 == d.scenes.size() ? last_sep
                                         : ", ") +
             at12(d.scenes[i], field) + unit;
    }
    return out;
  };
  auto time_of = [](const StudyRow& r) { return ms(r.seconds); };
  auto events_of = [](const StudyRow& r) { return std::to_string(r.events); };
  auto error_of = [](const StudyRow& r) { return format_significant(r.max_pos); };
  std::string amplification;
  for (size_t i = 0; i < d.scenes.size(); ++i) {
    const SceneSweep* s = find_sweep(d, d.scenes[i]);
    amplification += (i == 0                     ? ""
                      : i + 1 == d.scenes.size() ? " and "
                                                 : ", ") +
                     (s ? format_significant(s->amplification) : std::string("–")) + "×";
  }
  out += R"md(
The sweeps measure against the reference at tol = 1e-12, whose own error
(distance to tol 1e-11, a conservative bound) is printed in each sweep. At
1e-12 it takes **)md" +
         at12("point_mass", time_of) + " ms (point mass), " + at12("box", time_of) +
         " ms (box),\n" + at12("tshape", time_of) + " ms (T) and " + at12("circle", time_of) +
         " ms (circle, a 3.5 s scene)** (the budget: 100 ms\nper scene), with " +
         four(events_of, "", " and ") + " located events, and\nis self-consistent to " +
         four(error_of, "", " and ") + R"md( m — well below the 1e-9 m asked for.
The error falls roughly in proportion to the tolerance; it is not monotone
everywhere because a looser run may take a slightly different path through a
near-tangential contact (the T at 1e-8: its resting bar's corners switch their
dampers in pairs 2e-5 s apart), which the tighter runs resolve. The scenes
themselves are well conditioned: a change of 1e-8 m in the initial height
moves the trajectories by at most )md" +
         amplification + R"md( that.
)md";
  return out;
}

// 2. Error against wall-clock time and Δt, per scene.
std::string work_precision_section(const SweepData& d) {
  std::string out = R"md(
## 2. Work–precision diagrams

Left: the largest position error against the wall-clock time of the run
(best of 2 for runs under 0.25 s; two runs side by side on the two cores),
one curve per engine and integrator, MuJoCo dashed, and the adaptive method
itself at tolerances 1e-4…1e-10 in black. Right: the same errors against Δt;
the slope is the observed order.

)md";
  for (const std::string& name : d.scenes) {
    const SceneSweep* s = find_sweep(d, name);
    if (!s) continue;
    out += "### " + name + "\n\n![work-precision " + name + "](sweep." + name + ".png)\n\n" +
           error_table(*s) + "\nAdaptive DOPRI5 + events: " + dopri_line(*s) + ".\n\n";
  }
  out += R"md(### point mass with the Kelvin–Voigt law and c = 200

The same point mass with `--set contact.damping=kelvin_voigt --set
contact.c=200`: the case where MuJoCo's contact can follow the reference
model, so its error against the reference is mostly its own.

![work-precision point mass, Kelvin–Voigt](sweep.point_mass_kv.png)

)md";
  if (const SceneSweep* kv = find_sweep(d, "point_mass_kv")) out += error_table(*kv);
  return out;
}

// 3. The observed orders and why they fall below nominal.
std::string convergence_order_section(const SweepData& d) {
  std::string out = R"md(
## 3. Observed convergence order

Least-squares slope of log(max position error) against log(Δt) over the runs
whose error lies between a floor (10× the reference's own error, and at least
1e-12 m × the length scale) and 10 % of the scene's length scale (larger
errors mean a different bounce or tumble, not yet the asymptotic regime), with
its standard error. For MuJoCo the slope is also taken against its own
smallest-Δt run ("own finest", runs at ≥ 2× that step), which shows its own
convergence apart from the distance between the models.

)md";
  out += orders_table(d);
  out += R"md(
Why the orders fall below nominal:

- **Impacts make every fixed-step method first order.** With damping, the
  normal force jumps from 0 to c·|v_n| when a point enters contact (both
  laws). A fixed step that straddles the jump integrates a discontinuous
  right-hand side: O(Δt) error in velocity per impact, which the flight that
  follows turns into an O(Δt) position error. RK4 therefore shows order ≈ 1
  on the bouncing scenes. Without damping the force is continuous and only its
  slope jumps (the k·d kink), an O(Δt²) error per event: RK4 is then second
  order. `tests/analysis/test_sweep.cpp` measures both on the point mass
  (≈ 0.9 with c = 20, ≈ 2.2 with c = 0). The event-located adaptive method
  does not have this problem: it restarts exactly at the jump.
- **The error constant depends on where each impact falls inside its step**,
  i.e. erratically on Δt (error/Δt of semi-implicit Euler on the point mass
  ranges over 2…70 across 25 steps between 1e-5 and 1e-3 s). Hence the
  zig-zag curves and the standard errors of ±)md" +
         bouncing_stderr(d) + R"md( on the slopes; the
  orders are first order "on average", not pointwise.
- **Stiff tanh friction**: at α = 100 s/m and μ = 0.5 the linearised friction
  rate is μ·g·α = 490 1/s; stick–slip transitions are resolved only when Δt ≪
  1/(μ·g·α) ≈ 2 ms, which bends the curves at the coarse end.
- **The rolling disc** has no impact (it starts at its resting penetration
  with the damper off) and smooth tanh friction, so every method shows its
  nominal order there ()md" +
         circle_orders(d) + R"md(, then the rounding floor). The regularised sign of its rolling
  resistance, tanh(α·R·ω), turns on as the disc stops; at α·R = 10 s it is
  smooth enough not to cost RK4 its order here.
- **MuJoCo against the reference** levels off at the distance between the two
  contact models (its soft contact is Kelvin–Voigt-like; the shipped scenes
  use compression-only damping), which no step removes: slopes near 0. Against
  its own finest run MuJoCo converges at about first order, for the same
  reason as the reference (its contacts switch on and off inside a step).
)md";
  return out;
}

// 4. The cheapest run of each kind per accuracy target.
std::string accuracy_section(const SweepData& d) {
  std::string out = R"md(
## 4. Which integrator and Δt for a given accuracy

The cheapest run (wall clock) of each kind whose largest position error over
the run stays below the target, from the sweeps above:

)md";
  out += accuracy_table(d);
  out += R"md(
In plain words: for anything better than about a millimetre, the fixed-step
methods pay with Δt because impacts hold them to first order, and the
adaptive, event-located Dormand–Prince reaches 1e-6 m and below in a few
milliseconds — it is the method to use for accuracy, and the one the sweeps
trust as reference. Among the fixed-step methods, RK4 at Δt ≈ 5e-5…1e-4 s is
the most accurate per unit time on the bouncing scenes and semi-implicit Euler
the cheapest for a rough (centimetre) answer; explicit Euler only ties with it
where nothing bounces (the disc) and is the first to go unstable; implicit
Euler (a Newton solve per step) is the most expensive per digit, and its
advantage is stability, not accuracy: it is the only method that stays
stable far beyond ω·Δt ≈ 3 (stability.md).
)md";
  return out;
}

// 5. MuJoCo's floor against the reference model.
std::string mujoco_floor_section(const SweepData& d) {
  std::string out = R"md(
## 5. MuJoCo against the reference model

)md";
  out += mujoco_floor_table(d);
  const SceneSweep* kv = find_sweep(d, "point_mass_kv");
  const SweepRun* kv_floor = kv ? mujoco_floor(*kv) : nullptr;
  out += R"md(
MuJoCo's error against the reference does not go below the first column at
any step: that is the difference between the two contact models (the
compression-only damper of the shipped scenes against MuJoCo's
Kelvin–Voigt-like soft contact, and its friction, see README.md), not a
numerical error — refining MuJoCo's step only makes it converge to *its*
model (second column). With the Kelvin–Voigt law and c = 200 (last row) the
floor drops to )md" +
         (kv_floor ? format_significant(kv_floor->max_pos, 2) : std::string("–")) +
         R"md( m (its errors at 1e-4 s are )md" +
         (kv ? mujoco_errors_at(*kv, 1e-4) : std::string("–")) + R"md( m), the
friction difference that README.md explains. So MuJoCo stops being trustworthy as a stand-in for the reference
model at that floor, whatever its step; as a solver of its own model it
converges at first order.
)md";
  return out;
}

// 6. The cost of a reference step against mj_step, and its budget.
std::string step_cost_section(const SweepData& d) {
  std::string out = R"md(
## 6. Cost per step: reference against mj_step

`)md" + d.bench.command +
                    R"md(` (Google Benchmark, one run;
each benchmark replays its scene from the initial state): the per-step cost
of the core's step() against mj_step on the generated
`models/SCENE.calibrated.xml`, with the matching MuJoCo integrator.

```
)md" + bench_block(d.bench) +
                    R"md(
```

The requirement is a reference step at least 100× cheaper than mj_step on
every scene; the ratio column says whether this run meets it (summary at the
end of the page). Where the reference step's time goes: per step, a sin/cos pair for
a body that rotates, and per touching point the contact law with one tanh
for friction while the point slips slower than 22/α — the disc, which never
leaves the ground, pays one for its slip at every step and one more for
rolling resistance once it spins slower than 22/(α·R); semi-implicit Euler evaluates
the force once per step, RK4 four times, implicit Euler once per Newton
iteration (one evaluation gives the residual and its analytic Jacobian;
docs/speed.md). The run loop's divergence check (`run()`, an energy
evaluation after every step) is not part of this measurement; the sweep's
wall-clock times (section 2) include it.

Why 100× is out of reach for an accurate step on every scene: a step is one
chain of dependent operations (each step needs the previous state), so it
costs the latency of that chain, and the last line of the table measures the
links that sincos and tanh put on it, each call feeding the next. For 100× a
semi-implicit step must fit in 1/100 of mj_step: )md" +
                    per_step_budget(d.bench) + R"md(.
)md" + budget_against_floors(d.bench) +
                    R"md(
A step with no contact point at all (call, gravity, state update) already
takes the "empty step" time; the box and the T add a sincos and, on the
ground, a tanh per slowly slipping corner; the disc adds a tanh for its slip,
which stays near zero while it rolls. The step skips tanh where its
correctly rounded value is ±1 (|α·v| ≥ 22, exactly ±1, tested): one tanh
less per evaluation for a fast-sliding corner or a fast-spinning disc.
The tanh is contact2d's own bounded_tanh (core/vector_math.hpp: error at
most 1.27 ULP, derived at the code and tested over the whole range against
long double), about half glibc's latency on this chain; glibc's tanh
(CONTACT2D_SCALAR_TANH=1) and SLEEF's 1-ULP four-wide tanh, slower on this
chain, remain as paths (docs/speed.md). The sincos is still glibc's.
)md";
  return out;
}

// The requirements, each met or not.
std::string requirements_section(const SweepData& d) {
  std::string out = R"md(
## Summary: the requirements

)md";
  out += targets(d);
  return out;
}

}  // namespace

std::string sweep_page(const SweepData& d) {
  std::string out = sweep_intro(d);
  out += converged_reference_section(d);
  out += work_precision_section(d);
  out += convergence_order_section(d);
  out += accuracy_section(d);
  out += mujoco_floor_section(d);
  out += step_cost_section(d);
  out += requirements_section(d);
  return out;
}

}  // namespace contact2d::report
