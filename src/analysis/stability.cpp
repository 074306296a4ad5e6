#include "analysis/stability.hpp"
#include "core/format.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <mutex>
#include <stdexcept>

#include "analysis/reference.hpp"
#include "engines/engines.hpp"
#include "reference/dense_reference.hpp"

namespace contact2d::analysis {
namespace {

const char* kind_name(DivergenceKind kind) {
  switch (kind) {
    case DivergenceKind::NonFinite: return "non-finite state";
    case DivergenceKind::EnergyGain: return "energy gain";
    case DivergenceKind::Penetration: return "penetration beyond bound";
    case DivergenceKind::NewtonFailed: return "Newton failed";
  }
  return "?";
}

struct Probe {
  bool stable = false;
  std::string failure;
  double penetration = 0.0;
  bool refsafe = false;
};

// The run loop checks the rule after every step for every engine. The
// reference is sampled at the scene's output_dt; another engine every step
// (output_dt = dt), so that the penetration is the deepest over all steps
// (MuJoCo's stiff runs are short).
Probe probe(Scene scene, const std::string& engine, const EngineRunner& runner) {
  Probe p;
  if (engine != "ref") scene.sim.output_dt = scene.sim.dt;
  const Model model = make_model(scene);
  const EngineRun run = runner(engine, scene);
  p.refsafe = std::find(run.notes.begin(), run.notes.end(), "refsafe") != run.notes.end();
  for (const Sample& s : run.trajectory.samples) {
    p.penetration = std::max(p.penetration, contact2d::max_penetration(model, s.state.q));
  }
  if (run.trajectory.divergence) {
    p.failure = kind_name(run.trajectory.divergence->kind) +
                format_number(" at t = %.3g s", run.trajectory.divergence->time);
    return p;
  }
  // Samples are checked again here, so the rule is the same for a runner
  // that does not go through the run loop (a test's fake engine).
  const State initial = initial_state(scene);
  ContactSet contacts(model);
  find_contacts(model, initial.q, contacts);
  const DivergenceMonitor monitor(model, initial, contacts);
  for (const Sample& s : run.trajectory.samples) {
    find_contacts(model, s.state.q, contacts);
    if (const auto d = monitor.check(s.state, contacts, s.t)) {
      p.failure = kind_name(d->kind) + format_number(" at t = %.3g s", d->time);
      return p;
    }
  }
  // A warning fails the probe, except the reference's friction step: the
  // map is the contact's stability, and the friction's own limit (a
  // two-step cycle at rest, bounded, core/divergence.hpp) is another.
  for (const std::string& w : run.warnings) {
    if (w.rfind(kFrictionStepWarning, 0) == 0) continue;
    p.failure = "warning: " + w;
    return p;
  }
  p.stable = true;
  return p;
}

}  // namespace

const char* verdict_name(StabilityVerdict verdict) {
  switch (verdict) {
    case StabilityVerdict::Bracketed: return "bracketed";
    case StabilityVerdict::StableAtMax: return "stable at dt_max";
    case StabilityVerdict::UnstableAtMin: return "unstable at dt_min";
    case StabilityVerdict::Failed: return "failed";
  }
  return "?";
}

Scene scene_with_stiffness(const Scene& scene, double k, std::optional<double> zeta) {
  Scene s = scene;
  s.contact.k = k;
  if (zeta) {
    const double m_eff = min_effective_mass(make_body(s));
    s.contact.c = 2.0 * *zeta * std::sqrt(k * m_eff);
  }
  return s;
}

namespace {

// Refuses a configuration the search cannot run (std::invalid_argument,
// naming the option).
void check_stability_config(const StabilityConfig& config) {
  if (config.ks.empty()) throw std::invalid_argument("--ks: the list is empty");
  if (config.integrators.empty()) throw std::invalid_argument("--integrators: the list is empty");
  if (config.engines.empty()) throw std::invalid_argument("--engines: the list is empty");
  for (double k : config.ks) {
    if (!(k > 0.0 && k <= 1e12)) {
      throw std::invalid_argument(
          "--ks: " +
          (std::isfinite(k) ? format_number("%g", k) : std::string("a non-finite value")) +
          " is not in (0, 1e12] N/m");
    }
  }
  if (config.zeta && !(*config.zeta >= 0.0 && *config.zeta <= 1e3)) {
    throw std::invalid_argument("--zeta: must be in [0, 1e3]");
  }
  if (!(config.dt_max > 0.0)) throw std::invalid_argument("--dt-max: must be > 0");
  if (!(config.precision > 0.0)) throw std::invalid_argument("precision must be > 0");
}

// One row per engine, integrator it offers and k, with its contact's
// constants, the linear theory's limit and the smallest Δt the search tries.
std::vector<StabilityRow> stability_rows(const Scene& scene, const StabilityConfig& config,
                                         double dt_max) {
  std::vector<StabilityRow> rows;
  for (const std::string& engine : config.engines) {
    for (Integrator integrator : config.integrators) {
      if (!engines::engine_offers(engine, integrator)) continue;
      for (double k : config.ks) {
        StabilityRow row;
        row.engine = engine;
        row.integrator = integrator;
        row.k = k;
        const Scene s = scene_with_stiffness(scene, k, config.zeta);
        const ContactStiffness cs = contact_stiffness(make_model(s));
        row.c = s.contact.c;
        row.m_eff = cs.m_eff;
        row.omega = cs.omega;
        row.zeta = cs.zeta;
        // The limit of the integrator the engine integrates contact forces
        // with (engines::contact_integrator): MuJoCo's implicit integrates
        // them explicitly, so for a contact it is semi-implicit Euler, with
        // that limit (not the reference's unconditionally stable implicit
        // Euler).
        row.theory = stability_limit(engines::contact_integrator(engine, integrator), cs.zeta);
        const long long max_steps = engine == "ref" ? config.max_steps : config.max_steps_other;
        row.dt_min = std::min(dt_max, scene.sim.duration / static_cast<double>(max_steps));
        rows.push_back(row);
      }
    }
  }
  return rows;
}

// The converged reference's deepest penetration at stiffness k (NaN when it
// fails), sampled finely enough for the deepest point of an impact that
// lasts about π/ω.
double converged_penetration(const Scene& scene, double k, std::optional<double> zeta) {
  const Scene s = scene_with_stiffness(scene, k, zeta);
  const DenseTrajectory ref = converged_reference(s, 1e-9);
  if (!ref.ok()) return std::nan("");
  const Model model = make_model(s);
  const double omega = contact_stiffness(model).omega;
  return max_penetration(model, ref, std::min(1e-4, omega > 0.0 ? 0.05 / omega : 1e-4));
}

// The probe series of one row: from 0.9 of the theory's Δt (clamped to
// [dt_min, dt_max]) up or down by factors of 4 until the verdict changes,
// then bisection on log Δt to `config.precision`; the deepest penetration at
// the largest stable Δt, and MuJoCo's at ω·Δt = 0.2 where refsafe softened
// it. A probe that throws fails the row.
void search_stable_dt(StabilityRow& row, const Scene& scene, const StabilityConfig& config,
                      double dt_max, const EngineRunner& runner) {
  Scene s = scene_with_stiffness(scene, row.k, config.zeta);
  s.sim.integrator = row.integrator;
  double penetration_at_stable = std::nan("");
  bool refsafe_at_stable = false;
  auto try_dt = [&](double dt) {
    s.sim.dt = dt;
    ++row.probes;
    const Probe p = probe(s, row.engine, runner);
    if (p.stable) {
      if (!(dt <= row.dt_stable)) {
        penetration_at_stable = p.penetration;
        refsafe_at_stable = p.refsafe;
      }
    } else {
      if (dt < row.dt_unstable) row.failure = p.failure;
    }
    return p.stable;
  };
  try {
    const double theory_dt = row.omega > 0.0 ? row.theory / row.omega : INFINITY;
    double dt = std::clamp(std::isfinite(theory_dt) ? 0.9 * theory_dt : dt_max, row.dt_min, dt_max);
    if (try_dt(dt)) {
      row.dt_stable = dt;
      while (!std::isfinite(row.dt_unstable) && row.dt_stable < dt_max) {
        dt = std::min(4.0 * row.dt_stable, dt_max);
        if (try_dt(dt))
          row.dt_stable = dt;
        else
          row.dt_unstable = dt;
      }
    } else {
      row.dt_unstable = dt;
      while (std::isnan(row.dt_stable) && row.dt_unstable > row.dt_min) {
        dt = std::max(0.25 * row.dt_unstable, row.dt_min);
        if (try_dt(dt))
          row.dt_stable = dt;
        else
          row.dt_unstable = dt;
      }
    }
    if (std::isnan(row.dt_stable)) {
      row.verdict = StabilityVerdict::UnstableAtMin;
    } else if (!std::isfinite(row.dt_unstable)) {
      row.verdict = StabilityVerdict::StableAtMax;
    } else {
      while (row.dt_unstable / row.dt_stable > 1.0 + config.precision) {
        dt = std::sqrt(row.dt_stable * row.dt_unstable);
        if (try_dt(dt))
          row.dt_stable = dt;
        else
          row.dt_unstable = dt;
      }
      row.verdict = StabilityVerdict::Bracketed;
    }
    row.penetration = penetration_at_stable;
    row.refsafe_at_stable = refsafe_at_stable;

    // MuJoCo softened by refsafe: one more run at ω·Δt = 0.2, for its
    // penetration where nothing is softened.
    if (row.refsafe_at_stable && row.omega > 0.0) {
      s.sim.dt = std::max(std::min(0.2 / row.omega, row.dt_stable), row.dt_min);
      const Probe small = probe(s, row.engine, runner);
      if (small.stable) row.penetration_small_step = small.penetration;
    }
  } catch (const std::exception& e) {
    row.verdict = StabilityVerdict::Failed;
    row.failure = e.what();
  }
}

// Each row's reference penetration (of its k) and its notes: refsafe's
// softening, and a limit well beyond the linear bound.
void annotate_stability_rows(std::vector<StabilityRow>& rows, const StabilityConfig& config,
                             const std::vector<double>& reference_penetration) {
  for (StabilityRow& row : rows) {
    const size_t i = static_cast<size_t>(std::find(config.ks.begin(), config.ks.end(), row.k) -
                                         config.ks.begin());
    row.reference_penetration = reference_penetration[i];
    if (row.refsafe_at_stable) {
      row.note =
          "refsafe: at its largest stable dt MuJoCo ran with timeconst raised to 2·dt, a softer "
          "contact "
          "than k";
      const double ratio = row.penetration / row.penetration_small_step;
      if (std::isfinite(ratio))
        row.note +=
            " (deepest penetration " + format_number("%.3g", ratio) + "× that at ω·Δt = 0.2)";
    }
    if (row.engine != "ref" && row.verdict == StabilityVerdict::Bracketed &&
        row.omega * row.dt_stable > 1.5 * row.theory) {
      if (!row.note.empty()) row.note += "; ";
      row.note += "stable beyond the linear bound";
    }
  }
}

}  // namespace

StabilityResult run_stability(const Scene& scene, const StabilityConfig& config,
                              const EngineRunner& runner) {
  check_stability_config(config);

  StabilityResult result;
  result.scene_name = std::string(shape_name(scene.shape));
  result.duration = scene.sim.duration;
  result.dt_max = std::min(config.dt_max, scene.sim.duration);
  result.precision = config.precision;
  result.zeta = config.zeta;
  result.threads = config.threads == 0 ? default_threads() : config.threads;

  result.rows = stability_rows(scene, config, result.dt_max);
  std::vector<StabilityRow>& rows = result.rows;

  // Reference penetration per k, from the converged reference.
  std::vector<double> reference_penetration(config.ks.size(), std::nan(""));
  const size_t n_ref = config.ks.size();
  std::mutex progress_mutex;
  size_t done = 0;
  const size_t total = n_ref + rows.size();
  auto report = [&](const std::string& what) {
    if (!config.progress) return;
    std::lock_guard<std::mutex> lock(progress_mutex);
    config.progress(++done, total, what);
  };

  // Jobs: the converged reference of each k (for its penetration), then one
  // probe series per row.
  parallel_for(total, config.threads, [&](size_t index) {
    if (index < n_ref) {
      reference_penetration[index] = converged_penetration(scene, config.ks[index], config.zeta);
      report("reference k=" + format_number("%g", config.ks[index]));
      return;
    }
    StabilityRow& row = rows[index - n_ref];
    search_stable_dt(row, scene, config, result.dt_max, runner);
    report(row.engine + " " + std::string(integrator_name(row.integrator)) +
           " k=" + format_number("%g", row.k));
  });

  annotate_stability_rows(rows, config, reference_penetration);
  return result;
}

}  // namespace contact2d::analysis
