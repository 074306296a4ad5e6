// validation/report/stability.md: the largest stable Δt against the linear
// theory, for the reference and MuJoCo (report/pages.hpp).
#include <algorithm>
#include <cmath>
#include <string>

#include "io/table.hpp"
#include "report/numbers.hpp"
#include "report/pages.hpp"

namespace contact2d::report {
namespace {

std::string csv(double x) { return format_significant(x, 9); }
std::string opt2(const std::optional<double>& x) { return x ? format_significant(*x, 2) : "–"; }

// The failure without its time ("energy gain at t = 0.31 s" → "energy gain").
std::string failure_kind(const std::string& failure) {
  const size_t at = failure.find(" at t = ");
  return at == std::string::npos ? failure : failure.substr(0, at);
}

void add_summary_rows(Table& t, const StabilityMap& map) {
  std::vector<std::pair<std::string, std::string>> keys;
  for (const StabilityRow& r : map.rows) {
    const auto key = std::make_pair(r.engine, r.integrator);
    if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
  }
  for (const auto& [engine, integrator] : keys) {
    std::optional<double> theory;
    std::vector<double> measured, ratios;
    std::vector<const StabilityRow*> stable_at_max, unstable_at_min;
    std::string failures;
    for (const StabilityRow& r : map.rows) {
      if (r.engine != engine || r.integrator != integrator) continue;
      theory = r.theory;
      if (r.verdict == "bracketed") {
        measured.push_back(r.omega_dt_stable);
        if (r.theory) ratios.push_back(r.omega_dt_stable / *r.theory);
      } else if (r.verdict == "stable at dt_max") {
        stable_at_max.push_back(&r);
      } else if (r.verdict == "unstable at dt_min") {
        unstable_at_min.push_back(&r);
      }
      const std::string kind = failure_kind(r.failure);
      if (!kind.empty() && failures.find(kind) == std::string::npos)
        failures += (failures.empty() ? "" : ", ") + kind;
    }
    const auto m = range_of(measured), q = range_of(ratios);
    auto k_range = [](const std::vector<const StabilityRow*>& rows) {
      const std::string first = format_significant(rows.front()->k, 6),
                        last = format_significant(rows.back()->k, 6);
      return "k = " + first + (first != last ? " … " + last : "");
    };
    std::string outside;
    if (!stable_at_max.empty()) {
      outside = k_range(stable_at_max) +
                ": stable up to dt = " + csv(stable_at_max.back()->dt_max) + " s";
    }
    if (!unstable_at_min.empty()) {
      outside += (outside.empty() ? "" : "; ") + k_range(unstable_at_min) +
                 ": unstable down to dt = " + csv(unstable_at_min.back()->dt_min) + " s";
    }
    add_row(t, {map.scene, engine, integrator, theory ? format_significant(*theory) : "∞",
                m ? format_significant(m->lo, 2) + " – " + format_significant(m->hi, 2) : "–",
                q ? fixed(q->lo, 2) + " – " + fixed(q->hi, 2) : "–",
                outside.empty() ? "–" : outside, failures.empty() ? "–" : failures});
  }
}

// Per engine and integrator: measured ω·Δt (where bracketed) against theory,
// the stiffnesses outside the search range, and how the runs failed.
std::string summary_table(const std::vector<StabilityMap>& maps) {
  Table t{{"scene", "engine", "integrator", "linear bound ω·Δt",
           "measured ω·Δt (k = 1e3…1e9, where bracketed)", "measured / bound",
           "outside the search range", "failures at the first unstable step"},
          {}};
  for (const StabilityMap& map : maps) add_summary_rows(t, map);
  return to_markdown(t);
}

std::string mujoco_table(const std::vector<StabilityMap>& maps) {
  Table t{{"scene", "engine", "integrator", "k (N/m)", "largest stable dt", "ω·Δt", "linear bound",
           "deepest penetration there / at ω·Δt = 0.2 / reference", "first failure; note"},
          {}};
  for (const StabilityMap& map : maps) {
    for (const StabilityRow& r : map.rows) {
      std::string text = r.failure;
      if (!r.note.empty()) text += (text.empty() ? "" : "; ") + r.note;
      const bool at_max = r.verdict == "stable at dt_max";
      const std::string dt = at_max                              ? ">= " + csv(r.dt_stable)
                             : r.verdict == "unstable at dt_min" ? "< " + csv(r.dt_min)
                                                                 : format_significant(r.dt_stable);
      const std::string w = std::isnan(r.dt_stable)
                                ? "–"
                                : (at_max ? ">= " : "") + format_significant(r.omega_dt_stable);
      add_row(t, {map.scene, r.engine, r.integrator, format_significant(r.k, 6), dt, w,
                  r.theory ? format_significant(*r.theory) : "∞",
                  opt2(r.penetration) + " / " + opt2(r.penetration_small_step) + " / " +
                      opt2(r.reference_penetration) + " m",
                  text.empty() ? "–" : text});
    }
  }
  return to_markdown(t);
}

// The linear bound of a reference integrator at ζ = 1, from the maps.
std::string bound(const StabilityData& d, const std::string& integrator, int digits) {
  for (const StabilityMap& map : d.reference) {
    for (const StabilityRow& r : map.rows) {
      if (r.engine == "ref" && r.integrator == integrator && r.theory)
        return format_significant(*r.theory, digits);
    }
  }
  return "–";
}

std::string measured_range(const StabilityData& d, const std::string& integrator) {
  const auto range = range_of(bracketed_omega_dt(d.reference, "ref", integrator));
  return range ? range_text(*range, [](double x) { return format_significant(x, 2); }) : "–";
}

// "20 N·s/m at every k\n\nHolding c fixed makes ζ = … fall from 0.32 to
// 0.00032": the scene's c and the damping ratio at the smallest and largest k.
std::string scene_c_text(const StabilityMap& map) {
  const StabilityRow *first = nullptr, *last = nullptr;
  for (const StabilityRow& r : map.rows) {
    if (!first || r.k < first->k) first = &r;
    if (!last || r.k > last->k) last = &r;
  }
  if (!first) return "c at every k\n\nHolding c fixed makes ζ = c/(2√(k·m)) fall";
  return format_significant(first->c) +
         " N·s/m at every k\n\nHolding c fixed makes ζ = c/(2√(k·m)) fall from " +
         format_significant(first->zeta, 2) + " to " + format_significant(last->zeta, 2);
}

}  // namespace

std::string stability_page(const StabilityData& d, const Bench& bench) {
  const auto cost = mujoco_cost_ratio(bench);
  std::string out = R"md(# Stability: the largest stable Δt against the linear theory

Generated by `contact2d report`: do not edit, run it again.

Commands: `contact2d stability validation/scenes/SCENE.toml --zeta 1 --csv …
--plot validation/report/stability.SCENE.png` for the reference (k = 1e3 …
1e9), and `--engines mujoco,mujoco:exact --ks 1e4,1e6,1e8 --duration 0.7` for
MuJoCo on the point mass and the box (0.7 s: both land by 0.45 s; a MuJoCo
step costs )md" + (cost ? *cost : std::string("far more than")) +
                    R"md( a reference step).

**Stable** means that the run of the scene (its own initial state and
duration, with k replaced and c = 2ζ·√(k·m_eff), ζ = 1) passes the core's
divergence rule (`src/core/divergence.hpp`) after every step: the state stays
finite, the mechanical energy never rises above what the system ever held, no
point sinks deeper than twice what all that energy could push it, and implicit
Euler's Newton iteration converges. MuJoCo runs are held to the same rule
(the adaptor checks it every step) and any MuJoCo warning counts as a
failure. The largest stable Δt is found by bisection on log Δt to 2 %, from a
first probe just below the theoretical step, assuming stability is monotone
in Δt. Δt ranges from 2 s / 2e6 steps (1e-6 s; MuJoCo 2e-5…1e-5 s) to 0.01 s.

**Theory**: a contact point in its linear regime is the oscillator
x'' + 2ζω·x' + ω²·x = 0 with ω = √(k/m_eff), m_eff the smallest effective
mass of a contact point (1/m_eff = 1/m + r²/I: a corner of a box or T);
`stability_limit(method, ζ)` gives the largest stable ω·Δt: explicit Euler
2ζ (ζ ≤ 1), semi-implicit Euler min(1/ζ, 2(√(1+ζ²) − ζ)) = )md" +
                    bound(d, "semi_implicit_euler", 2) + " at ζ = 1,\nRK4 " + bound(d, "rk4", 3) +
                    R"md( at ζ = 1 (2√2 at ζ = 0), implicit Euler ∞.

## 1. The reference solver at critical damping

)md";
  for (const std::string& s : d.scenes)
    out += "![stability " + s + "](stability." + s + ".png)\n\n";
  out += summary_table(d.reference);
  out += R"md(
- **Semi-implicit Euler and RK4 follow the theory on the point mass**
  (measured/bound near 1). On the box and the T they survive beyond the
  bound: the bound uses the *smallest* effective mass over all orientations
  (a corner at the end of the half-diagonal), while the contacts they
  actually make (a box landing on an edge, a T on its bar) have larger
  effective masses, hence smaller ω.
- **A linear instability of a one-sided contact saturates.** Once the
  oscillation outgrows the static penetration the point leaves the ground,
  and the growth stops; the run then hops or chatters with bounded energy,
  which the divergence rule (finite, no energy gain, bounded penetration)
  counts as stable. This is why some measured values (the resting disc, the
  T) exceed the linear bound: *stable by the rule* there does not mean
  *right* — the sweeps measure that.
- **Explicit Euler fails at ω·Δt ≈ )md" +
         measured_range(d, "explicit_euler") + R"md( (the table), far below its linear
  bound 2ζ = 2.** The bound assumes a bilateral spring and a damper acting both ways.
  At ω·Δt > 1 the explicit update overshoots, the contact opens (the force
  is unilateral), and with compression-only damping the rebound half of each
  contact is undamped, where explicit Euler gains energy every step. The same
  happens, less, with the Kelvin–Voigt law (`tests/analysis/test_stability.cpp`
  keeps this finding).
- **Implicit Euler is stable up to the largest step tried for soft contacts,
  but not unconditionally in practice**: at large ω·Δt (≳ )md" +
         measured_range(d, "implicit_euler") + R"md(, the table) its Newton
  iteration on the non-smooth force (the kinks at contact entry and at the
  damper switch) fails to converge even after splitting the step 64 times,
  and the divergence rule stops the run.

### The point mass with the scene's own c = )md" +
         scene_c_text(d.scene_c) + R"md( as k grows.

![stability point mass, scene c](stability.point_mass_scene_c.png)

)md";
  out += summary_table({d.scene_c});
  out += R"md(
Here explicit Euler appears stable far beyond its bound 2ζ: with ζ → 0 its
amplitude grows only by √(1 + (ω·Δt)²) per step, too slowly to break the
energy rule within a 2 s run. **Stable over the run is not stable**: the map
is a finite-horizon measurement, and for explicit Euler the linear bound is
the one to trust.

## 2. MuJoCo (and where refsafe changes the contact instead of failing)

)md";
  if (!d.mujoco) return out + "(contact2d was built without MuJoCo: no MuJoCo map.)\n";
  for (const std::string& s : d.mujoco_scenes) {
    out += "![stability MuJoCo " + s + "](stability.mujoco." + s + ".png)\n\n";
  }
  out += mujoco_table(d.mujoco_maps);
  out += R"md(
`mujoco` is the default (calibrated) mapping, MuJoCo's direct form
`solref="-k·Â -c·Â"`; `mujoco:exact` is the standard form timeconst = 2m/c,
dampratio = c/(2√(mk)). The "linear bound" column is the limit of the method
MuJoCo runs for a contact: its Euler is semi-implicit, and its "implicit"
integrator is implicit in the joint damping and actuator terms, not in the
contact force, so its contact limit is semi-implicit Euler's too (it fails
near ω·Δt ≈ 1 like an explicit method). The penetration column gives the
deepest penetration over every step of the run at the largest stable Δt, of
a run at ω·Δt = 0.2 (only where refsafe was active), and of the converged
reference.

**refsafe.** MuJoCo raises a standard-form timeconst below 2·Δt to 2·Δt
(the flag `refsafe`, on by default). With the exact mapping the timeconst
is 2m/c = 1/ω at ζ = 1, so it is raised as soon as ω·Δt > 0.5; the rows
marked "refsafe" ran their largest stable step with that softer contact
(the generator reports the clamp; `src/mujoco/mapping.hpp`). There MuJoCo
keeps going at steps where the reference integrator fails, by changing the
model: the contact gets softer as Δt grows, and the penetration grows with it
(the ratio in the note). It is not unconditional either: beyond ω·Δt ≈ 2 the
runs still break the divergence rule. The calibrated mapping uses the direct
form, which refsafe does not touch: it fails where its integrator does
instead of changing the contact.
)md";
  return out;
}

}  // namespace contact2d::report
