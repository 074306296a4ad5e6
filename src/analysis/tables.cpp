// Tables and CSV of the sweep, the reference study and the stability map
// (analysis/tables.hpp), and the one-line summary of a simulated run.
#include "analysis/tables.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "core/format.hpp"
#include "engines/engines.hpp"
#include "io/table.hpp"

namespace contact2d::analysis {
namespace {

std::string csv_number(double value) { return std::isfinite(value) ? number(value, 9, "") : ""; }

std::string status_text(const SweepRow& row) {
  switch (row.status) {
    case RunStatus::Ok: return "ok";
    case RunStatus::Diverged: return "diverged";
    case RunStatus::Failed: return "failed";
  }
  return "?";
}

std::string kind_text(DivergenceKind kind) {
  switch (kind) {
    case DivergenceKind::NonFinite: return "non-finite state";
    case DivergenceKind::EnergyGain: return "energy gain";
    case DivergenceKind::Penetration: return "penetration";
    case DivergenceKind::NewtonFailed: return "Newton failed";
  }
  return "?";
}

}  // namespace

std::string number(double value, int digits, const char* missing) {
  if (!std::isfinite(value)) return missing;
  return format_number(value, digits);
}

// ---------------------------------------------------------------- sweep

void print_sweep(std::ostream& out, const SweepResult& r) {
  const DenseStats& st = r.reference.trajectory.stats();
  out << r.scene_name << " (" << number(r.duration, 4)
      << " s): error of each run against the converged reference\n"
      << "reference: Dormand–Prince 5(4) with event location, tol " << number(r.reference.tol, 2)
      << ", " << st.accepted << " steps, " << st.events << " events, "
      << number(r.reference.seconds * 1e3, 3)
      << " ms; its own error <= " << number(r.reference_error, 2)
      << " m (distance to the same at 10x the tolerance)\n"
      << "time: wall clock of each run, best of " << r.repeats << " (one run when it takes over "
      << number(r.single_run_seconds, 3) << " s), " << r.threads << " thread"
      << (r.threads > 1 ? "s" : "") << " side by side\n\n";
  Table runs{{"engine", "integrator", "dt", "max pos err", "end pos err", "max angle err",
              "own-finest err", "time (ms)", "note"},
             {}};
  for (const SweepRow& row : r.rows) {
    const std::string engine = row.engine,
                      integrator = engines::integrator_label(row.engine, row.integrator),
                      dt = number(row.dt, 3);
    if (row.status == RunStatus::Ok) {
      add_row(runs, {engine, integrator, dt, number(row.error.max_pos), number(row.error.end_pos),
                     number(row.error.max_angle),
                     row.self_error ? number(row.self_error->max_pos) : "(finest)",
                     number(row.seconds * 1e3, 3), ""});
    } else if (row.status == RunStatus::Diverged) {
      add_row(runs, {engine, integrator, dt, "-", "-", "-", "-", "-",
                     "diverged at t = " + number(row.divergence->time, 4) + " s (" +
                         kind_text(row.divergence->kind) + ")"});
    } else {
      add_row(runs, {engine, integrator, dt, "-", "-", "-", "-", "-", "failed: " + row.message});
    }
  }
  out << to_text(runs);
  if (!r.dense_curve.empty()) {
    out << "\nthe adaptive method itself (Dormand–Prince 5(4) with events) at other tolerances:\n";
    Table dense{{"tol", "max pos err", "end pos err", "max angle err", "steps", "events",
                 "time (ms)", "note"},
                {}};
    for (const ToleranceRow& row : r.dense_curve) {
      if (!row.failure.empty()) {
        add_row(dense,
                {number(row.tol, 2), "-", "-", "-", "-", "-", "-", "failed: " + row.failure});
        continue;
      }
      add_row(dense, {number(row.tol, 2), number(row.error.max_pos), number(row.error.end_pos),
                      number(row.error.max_angle), std::to_string(row.stats.accepted),
                      std::to_string(row.stats.events), number(row.seconds * 1e3, 3), ""});
    }
    out << to_text(dense);
  }
  out << "\n";
  print_orders(out, r);
}

void print_orders(std::ostream& out, const SweepResult& r) {
  out << "observed order: least-squares slope of log max pos err against log dt over the runs "
         "whose error\n"
         "lies between the floor (10x the reference's own error, >= 1e-12 m) and 10 % of the "
         "scene's length\n"
         "scale L = "
      << number(r.length_scale, 3) << " m (body size or largest COM displacement)\n";
  Table orders{{"engine", "integrator", "against", "nominal", "observed", "dt range", "note"}, {}};
  for (const OrderFit& f : r.orders) {
    add_row(orders, {f.engine, engines::integrator_label(f.engine, f.integrator), f.against,
                     number(f.nominal, 2),
                     f.order ? number(*f.order, 2) + " ± " + number(f.order_stderr, 1) : "-",
                     f.order ? number(f.dt_min, 2) + ".." + number(f.dt_max, 2) + " (" +
                                   std::to_string(f.points) + ")"
                             : "-",
                     f.note});
  }
  out << to_text(orders);
}

void write_sweep_csv(std::FILE* out, const SweepResult& r) {
  Table t{{"scene", "engine", "integrator", "dt", "tol", "status", "max_pos_err", "end_pos_err",
           "max_angle_err", "end_angle_err", "self_max_pos_err", "seconds", "repeats",
           "diverged_at", "reference_tol", "reference_err", "message"},
          {}};
  for (const SweepRow& row : r.rows) {
    const bool ok = row.status == RunStatus::Ok;
    add_row(t, {r.scene_name, row.engine, std::string(integrator_name(row.integrator)),
                csv_number(row.dt), "", status_text(row), ok ? csv_number(row.error.max_pos) : "",
                ok ? csv_number(row.error.end_pos) : "", ok ? csv_number(row.error.max_angle) : "",
                ok ? csv_number(row.error.end_angle) : "",
                row.self_error ? csv_number(row.self_error->max_pos) : "",
                row.repeats > 0 ? csv_number(row.seconds) : "", std::to_string(row.repeats),
                row.divergence ? csv_number(row.divergence->time) : "", csv_number(r.reference.tol),
                csv_number(r.reference_error), row.message});
  }
  // The adaptive method's own curve: integrator "dopri5_events", no dt.
  for (const ToleranceRow& row : r.dense_curve) {
    const bool ok = row.failure.empty();
    add_row(t, {r.scene_name, "ref", "dopri5_events", "", csv_number(row.tol), ok ? "ok" : "failed",
                ok ? csv_number(row.error.max_pos) : "", ok ? csv_number(row.error.end_pos) : "",
                ok ? csv_number(row.error.max_angle) : "",
                ok ? csv_number(row.error.end_angle) : "", "", csv_number(row.seconds), "3", "",
                csv_number(r.reference.tol), csv_number(r.reference_error), row.failure});
  }
  std::fputs(to_csv(t).c_str(), out);
}

void write_orders_csv(std::FILE* out, const SweepResult& r) {
  Table t{{"scene", "engine", "integrator", "against", "nominal", "observed", "observed_stderr",
           "points", "dt_min", "dt_max", "note"},
          {}};
  for (const OrderFit& f : r.orders) {
    add_row(t, {r.scene_name, f.engine, std::string(integrator_name(f.integrator)), f.against,
                csv_number(f.nominal), f.order ? csv_number(*f.order) : "",
                f.order ? csv_number(f.order_stderr) : "", std::to_string(f.points),
                f.order ? csv_number(f.dt_min) : "", f.order ? csv_number(f.dt_max) : "", f.note});
  }
  std::fputs(to_csv(t).c_str(), out);
}

// ------------------------------------------------------ reference study

void print_reference_study(std::ostream& out, const std::string& scene_name,
                           const ReferenceStudy& study) {
  out << scene_name
      << ": converged reference (Dormand–Prince 5(4), events located) at each tolerance\n"
      << "against tol " << number(study.truth_tol, 2) << " (" << study.truth_stats.accepted
      << " steps, " << study.truth_stats.events << " events, "
      << number(study.truth_seconds * 1e3, 3)
      << " ms); the scene magnifies an initial height change by up to "
      << number(study.amplification, 3) << "x\n";
  Table t{{"tol", "max pos err", "end pos err", "max angle err", "steps", "rejected", "events",
           "f evals", "time (ms)", "note"},
          {}};
  for (const ToleranceRow& row : study.rows) {
    if (!row.failure.empty()) {
      add_row(t, {number(row.tol, 2), "-", "-", "-", "-", "-", "-", "-", "-",
                  "failed: " + row.failure});
      continue;
    }
    add_row(t, {number(row.tol, 2), number(row.error.max_pos), number(row.error.end_pos),
                number(row.error.max_angle), std::to_string(row.stats.accepted),
                std::to_string(row.stats.rejected), std::to_string(row.stats.events),
                std::to_string(row.stats.evaluations), number(row.seconds * 1e3, 3), ""});
  }
  out << to_text(t);
}

void write_reference_study_csv(std::FILE* out, const std::string& scene_name,
                               const ReferenceStudy& study) {
  Table t{{"scene", "tol", "truth_tol", "max_pos_err", "end_pos_err", "max_angle_err", "steps",
           "rejected", "events", "evaluations", "seconds", "amplification"},
          {}};
  for (const ToleranceRow& row : study.rows) {
    const bool ok = row.failure.empty();
    add_row(t, {scene_name, csv_number(row.tol), csv_number(study.truth_tol),
                ok ? csv_number(row.error.max_pos) : "", ok ? csv_number(row.error.end_pos) : "",
                ok ? csv_number(row.error.max_angle) : "", std::to_string(row.stats.accepted),
                std::to_string(row.stats.rejected), std::to_string(row.stats.events),
                std::to_string(row.stats.evaluations), csv_number(row.seconds),
                csv_number(study.amplification)});
  }
  std::fputs(to_csv(t).c_str(), out);
}

// ------------------------------------------------------------ stability

void print_stability(std::ostream& out, const StabilityResult& r) {
  out << r.scene_name << ": largest stable dt per contact stiffness k (bisection on log dt to "
      << number(r.precision * 100, 2) << " %, dt up to " << number(r.dt_max, 3) << " s, "
      << number(r.duration, 4) << " s runs)\n"
      << "stable = the core's divergence rule holds at every step: finite state, no energy gain "
         "beyond what\n"
         "the system held, penetration below twice the energy bound, Newton converged (implicit "
         "Euler)\n"
      << "damping: "
      << (r.zeta ? "c = 2*zeta*sqrt(k*m_eff) with zeta = " + number(*r.zeta, 3)
                 : std::string("the scene's c at every k"))
      << "; theory: largest stable omega*dt of the linear oscillator, omega = sqrt(k/m_eff)\n\n";
  Table t{{"engine", "integrator", "k (N/m)", "zeta", "omega", "stable dt", "omega*dt", "theory",
           "ratio", "depth (m)", "at wdt=0.2", "ref depth", "first failure / note"},
          {}};
  for (const StabilityRow& row : r.rows) {
    std::string stable;
    switch (row.verdict) {
      case StabilityVerdict::Bracketed: stable = number(row.dt_stable, 3); break;
      case StabilityVerdict::StableAtMax: stable = ">=" + number(row.dt_stable, 3); break;
      case StabilityVerdict::UnstableAtMin: stable = "<" + number(row.dt_min, 3); break;
      case StabilityVerdict::Failed: stable = "failed"; break;
    }
    const double observed = row.omega * row.dt_stable;
    std::string tail = row.failure;
    if (!row.note.empty()) tail += (tail.empty() ? "" : "; ") + row.note;
    add_row(
        t,
        {row.engine, engines::integrator_label(row.engine, row.integrator), number(row.k, 2),
         number(row.zeta, 3), number(row.omega, 4), stable,
         std::isnan(row.dt_stable)
             ? "-"
             : (row.verdict == StabilityVerdict::StableAtMax ? ">=" : "") + number(observed, 3),
         std::isfinite(row.theory) ? number(row.theory, 3) : "inf",
         std::isfinite(row.theory) && !std::isnan(row.dt_stable) ? number(observed / row.theory, 3)
                                                                 : "-",
         number(row.penetration, 3), number(row.penetration_small_step, 3),
         number(row.reference_penetration, 3), tail});
  }
  out << to_text(t);
}

void write_stability_csv(std::FILE* out, const StabilityResult& r) {
  Table t{{"scene",
           "engine",
           "integrator",
           "k",
           "c",
           "m_eff",
           "omega",
           "zeta",
           "theory_omega_dt",
           "theory_dt",
           "dt_stable",
           "dt_unstable",
           "dt_min",
           "dt_max",
           "verdict",
           "omega_dt_stable",
           "probes",
           "penetration",
           "penetration_small_step",
           "reference_penetration",
           "failure",
           "note"},
          {}};
  for (const StabilityRow& row : r.rows) {
    add_row(t, {r.scene_name,
                row.engine,
                std::string(integrator_name(row.integrator)),
                csv_number(row.k),
                csv_number(row.c),
                csv_number(row.m_eff),
                csv_number(row.omega),
                csv_number(row.zeta),
                std::isfinite(row.theory) ? csv_number(row.theory) : "inf",
                std::isfinite(row.theory) ? csv_number(row.theory / row.omega) : "inf",
                csv_number(row.dt_stable),
                csv_number(row.dt_unstable),
                csv_number(row.dt_min),
                csv_number(r.dt_max),
                verdict_name(row.verdict),
                csv_number(row.omega * row.dt_stable),
                std::to_string(row.probes),
                csv_number(row.penetration),
                csv_number(row.penetration_small_step),
                csv_number(row.reference_penetration),
                row.failure,
                row.note});
  }
  std::fputs(to_csv(t).c_str(), out);
}

// ------------------------------------------------------------ simulate

std::string run_summary(const Scene& scene, const std::string& engine, const EngineRun& run) {
  const Model model = make_model(scene);
  const auto& samples = run.trajectory.samples;
  double deepest = 0.0;
  for (const Sample& s : samples) deepest = std::max(deepest, max_penetration(model, s.state.q));
  const State& first = samples.front().state;
  const State& last = samples.back().state;
  // A duration that is no whole number of steps runs the nearest whole
  // number (core/scene.hpp, step_count): say the time that was run.
  const long long steps = step_count(scene.sim);
  const double ran = static_cast<double>(steps) * scene.sim.dt;
  const std::string span = std::abs(ran - scene.sim.duration) > 1e-9 * scene.sim.duration
                               ? format_number(ran) + " s (" + std::to_string(steps) +
                                     " steps: the whole number nearest to the duration, " +
                                     format_number(scene.sim.duration) + " s)"
                               : format_number(scene.sim.duration) + " s";
  return std::string(shape_name(scene.shape)) + " [" + engine + ", " +
         engines::integrator_label(engine, scene.sim.integrator) +
         ", dt = " + format_number(scene.sim.dt) + " s, " + span + " in " +
         format_duration(run.seconds) + "]: final x = " + format_number(last.q.x()) +
         " m, y = " + format_number(last.q.y()) + " m, theta = " + format_number(last.q.z()) +
         " rad, |v| = " + format_number(last.v.head<2>().norm()) +
         " m/s; max sampled penetration " + format_number(deepest) + " m; energy " +
         format_number(energy(model, first)) + " -> " + format_number(energy(model, last)) +
         " J, largest rise " + format_number(run.trajectory.energy.max_rise, 3) + " J (allowed " +
         format_number(run.trajectory.energy.tolerance, 3) + " J)";
}

}  // namespace contact2d::analysis
