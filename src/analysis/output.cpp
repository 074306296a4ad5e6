#include "analysis/output.hpp"

#include "core/format.hpp"

#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iomanip>
#include <map>
#include <sstream>
#include <stdexcept>

#include "io/csv.hpp"
#include "io/plot.hpp"

namespace contact2d::analysis {
namespace {

std::string pad(const std::string& text, size_t width) {
  // Width in characters, counting a UTF-8 sequence as one.
  size_t chars = 0;
  for (unsigned char c : text) chars += (c & 0xC0) != 0x80;
  return chars >= width ? text + " " : text + std::string(width - chars, ' ');
}

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

std::string csv_text(std::string text) {
  for (char& c : text) {
    if (c == '"') c = '\'';
    if (c == '\n') c = ' ';
  }
  return "\"" + text + "\"";
}

// "RK4" for the reference, "MuJoCo Euler" etc. for MuJoCo (its Euler is
// semi-implicit; it has no explicit Euler).
std::string series_title(const std::string& engine, Integrator integrator) {
  if (engine == "ref") return std::string(integrator_title(integrator));
  if (engine.rfind("mujoco", 0) == 0) {
    // "mujoco" or "mujoco:MAPPING"
    const std::string prefix = engine.size() > 7 ? "MuJoCo (" + engine.substr(7) + ") " : "MuJoCo ";
    switch (integrator) {
      case Integrator::SemiImplicitEuler: return prefix + "Euler";
      case Integrator::ImplicitEuler: return prefix + "implicit";
      case Integrator::RK4: return prefix + "RK4";
      case Integrator::ExplicitEuler: return prefix + "explicit Euler";
    }
  }
  return engine + " " + std::string(integrator_title(integrator));
}

// Text for gnuplot's enhanced mode inside single quotes: '_' and '^' would
// start a subscript or superscript.

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
  out << pad("engine", 8) << pad("integrator", 21) << pad("dt", 9) << pad("max pos err", 13)
      << pad("end pos err", 13) << pad("max angle err", 15) << pad("own-finest err", 16)
      << "time (ms)\n";
  for (const SweepRow& row : r.rows) {
    out << pad(row.engine, 8) << pad(std::string(integrator_name(row.integrator)), 21)
        << pad(number(row.dt, 3), 9);
    if (row.status == RunStatus::Ok) {
      out << pad(number(row.error.max_pos), 13) << pad(number(row.error.end_pos), 13)
          << pad(number(row.error.max_angle), 15)
          << pad(row.self_error ? number(row.self_error->max_pos) : "(finest)", 16)
          << number(row.seconds * 1e3, 3);
    } else if (row.status == RunStatus::Diverged) {
      out << "diverged at t = " << number(row.divergence->time, 4) << " s ("
          << kind_text(row.divergence->kind) << ")";
    } else {
      out << "failed: " << row.message;
    }
    out << "\n";
  }
  if (!r.dense_curve.empty()) {
    out << "\nthe adaptive method itself (Dormand–Prince 5(4) with events) at other tolerances:\n"
        << pad("tol", 9) << pad("max pos err", 13) << pad("end pos err", 13)
        << pad("max angle err", 15) << pad("steps", 8) << pad("events", 8) << "time (ms)\n";
    for (const ToleranceRow& row : r.dense_curve) {
      out << pad(number(row.tol, 2), 9);
      if (!row.failure.empty()) {
        out << "failed: " << row.failure << "\n";
        continue;
      }
      out << pad(number(row.error.max_pos), 13) << pad(number(row.error.end_pos), 13)
          << pad(number(row.error.max_angle), 15) << pad(std::to_string(row.stats.accepted), 8)
          << pad(std::to_string(row.stats.events), 8) << number(row.seconds * 1e3, 3) << "\n";
    }
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
  out << pad("engine", 8) << pad("integrator", 21) << pad("against", 12) << pad("nominal", 9)
      << pad("observed", 12) << pad("dt range", 18) << "note\n";
  for (const OrderFit& f : r.orders) {
    out << pad(f.engine, 8) << pad(std::string(integrator_name(f.integrator)), 21)
        << pad(f.against, 12) << pad(number(f.nominal, 2), 9)
        << pad(f.order ? number(*f.order, 2) + " ± " + number(f.order_stderr, 1) : "-", 12)
        << pad(f.order ? number(f.dt_min, 2) + ".." + number(f.dt_max, 2) + " (" +
                             std::to_string(f.points) + ")"
                       : "-",
               18)
        << f.note << "\n";
  }
}

void write_sweep_csv(std::FILE* out, const SweepResult& r) {
  std::fprintf(
      out,
      "scene,engine,integrator,dt,tol,status,max_pos_err,end_pos_err,max_angle_err,end_angle_err,"
      "self_max_pos_err,seconds,repeats,diverged_at,reference_tol,reference_err,message\n");
  for (const SweepRow& row : r.rows) {
    const bool ok = row.status == RunStatus::Ok;
    std::fprintf(out, "%s,%s,%s,%s,,%s,%s,%s,%s,%s,%s,%s,%d,%s,%s,%s,%s\n", r.scene_name.c_str(),
                 row.engine.c_str(), std::string(integrator_name(row.integrator)).c_str(),
                 csv_number(row.dt).c_str(), status_text(row).c_str(),
                 ok ? csv_number(row.error.max_pos).c_str() : "",
                 ok ? csv_number(row.error.end_pos).c_str() : "",
                 ok ? csv_number(row.error.max_angle).c_str() : "",
                 ok ? csv_number(row.error.end_angle).c_str() : "",
                 row.self_error ? csv_number(row.self_error->max_pos).c_str() : "",
                 row.repeats > 0 ? csv_number(row.seconds).c_str() : "", row.repeats,
                 row.divergence ? csv_number(row.divergence->time).c_str() : "",
                 csv_number(r.reference.tol).c_str(), csv_number(r.reference_error).c_str(),
                 csv_text(row.message).c_str());
  }
  // The adaptive method's own curve: integrator "dopri5_events", no dt.
  for (const ToleranceRow& row : r.dense_curve) {
    const bool ok = row.failure.empty();
    std::fprintf(out, "%s,ref,dopri5_events,,%s,%s,%s,%s,%s,%s,,%s,3,,%s,%s,%s\n",
                 r.scene_name.c_str(), csv_number(row.tol).c_str(), ok ? "ok" : "failed",
                 ok ? csv_number(row.error.max_pos).c_str() : "",
                 ok ? csv_number(row.error.end_pos).c_str() : "",
                 ok ? csv_number(row.error.max_angle).c_str() : "",
                 ok ? csv_number(row.error.end_angle).c_str() : "", csv_number(row.seconds).c_str(),
                 csv_number(r.reference.tol).c_str(), csv_number(r.reference_error).c_str(),
                 csv_text(row.failure).c_str());
  }
}

void write_orders_csv(std::FILE* out, const SweepResult& r) {
  std::fprintf(out,
               "scene,engine,integrator,against,nominal,observed,observed_stderr,points,dt_min,dt_"
               "max,note\n");
  for (const OrderFit& f : r.orders) {
    std::fprintf(out, "%s,%s,%s,%s,%s,%s,%s,%d,%s,%s,%s\n", r.scene_name.c_str(), f.engine.c_str(),
                 std::string(integrator_name(f.integrator)).c_str(), f.against.c_str(),
                 csv_number(f.nominal).c_str(), f.order ? csv_number(*f.order).c_str() : "",
                 f.order ? csv_number(f.order_stderr).c_str() : "", f.points,
                 f.order ? csv_number(f.dt_min).c_str() : "",
                 f.order ? csv_number(f.dt_max).c_str() : "", csv_text(f.note).c_str());
  }
}

void plot_sweep(const std::string& png_path, const SweepResult& r) {
  AtomicFile png(png_path);  // gnuplot writes the temporary file; renamed on success
  const std::string& png_tmp = png.temp_path();
  AtomicFile data_file(png_path + ".dat");  // never committed: removed on return
  std::FILE* f = data_file.get();
  const std::string& data = data_file.temp_path();
  // One block per engine/integrator: dt, seconds, max position error.
  std::vector<std::string> titles;
  std::vector<std::pair<std::string, Integrator>> keys;
  for (const SweepRow& row : r.rows) {
    const auto key = std::make_pair(row.engine, row.integrator);
    if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
  }
  const double floor = std::max(r.reference_error, 1e-16);
  int blocks = 0;
  for (const auto& key : keys) {
    int points = 0;
    for (const SweepRow& row : r.rows) {
      if (row.engine != key.first || row.integrator != key.second || row.status != RunStatus::Ok)
        continue;
      std::fprintf(f, "%.9g %.9g %.9g\n", row.dt, std::max(row.seconds, 1e-9),
                   std::max(row.error.max_pos, 1e-16));
      ++points;
    }
    if (points == 0) continue;
    std::fprintf(f, "\n\n");
    titles.push_back(series_title(key.first, key.second));
    ++blocks;
  }
  // The adaptive method: tolerance in column 1 (no dt), its time and error.
  int dense_points = 0;
  for (const ToleranceRow& row : r.dense_curve) {
    if (!row.failure.empty()) continue;
    std::fprintf(f, "%.9g %.9g %.9g\n", row.tol, std::max(row.seconds, 1e-9),
                 std::max(row.error.max_pos, 1e-16));
    ++dense_points;
  }
  std::fprintf(f, "\n\n");
  if (std::fflush(f) != 0) throw std::runtime_error(data + ": cannot write plot data");
  if (blocks == 0) throw std::runtime_error(png_path + ": no run finished, nothing to plot");

  std::ostringstream s;
  s << "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size 1400,600 font "
       "',11' } "
       "else { set terminal png size 1400,600 }\n"
    << "set output " << gnuplot_quoted(png_tmp) << "\n"
    << "set multiplot layout 1,2 title '" << gnuplot_text(r.scene_name) << " ("
    << number(r.duration, 3)
    << " s): max position error against the converged reference (its own error: "
    << number(floor, 2) << " m)'\n"
    << "set logscale xy\nset grid\nset format y '10^{%L}'\nset key bottom right font ',9'\n"
    << "set ylabel 'max position error (m)'\n"
    << "set xlabel 'wall-clock time of the run (s)'\nset format x '10^{%L}'\n"
    << "set title 'work–precision'\n";
  auto plot_lines = [&](const char* using_cols, bool with_dense) {
    s << "plot ";
    for (int i = 0; i < blocks; ++i) {
      // MuJoCo dashed, the reference solid.
      const bool mujoco = titles[i].rfind("MuJoCo", 0) == 0;
      s << (i ? ", " : "") << gnuplot_quoted(data) << " index " << i << " using " << using_cols
        << " with linespoints lw 2 pt " << (i % 7) + 1 << (mujoco ? " dt 2" : "") << " title '"
        << gnuplot_text(titles[i]) << "'";
    }
    if (with_dense && dense_points > 0) {
      s << ", " << gnuplot_quoted(data) << " index " << blocks
        << " using 2:3 with linespoints lw 2 lc 'black' pt 7 ps 0.7 title 'adaptive DOPRI5 + "
           "events (tol 1e-4..1e-10)'";
    }
    s << ", " << number(floor, 3) << " with lines dt 3 lc 'gray' title 'reference error'\n";
  };
  s << "set yrange [" << number(floor / 10.0, 3) << ":*]\n";
  plot_lines("2:3", true);
  s << "set xlabel 'time step dt (s)'\nset title 'error against dt (slope = observed order)'\n";
  plot_lines("1:3", false);
  s << "unset multiplot\n";
  run_gnuplot(s.str(), png_tmp);
  png.commit();
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
  out << pad("tol", 8) << pad("max pos err", 13) << pad("end pos err", 13)
      << pad("max angle err", 15) << pad("steps", 8) << pad("rejected", 10) << pad("events", 8)
      << pad("f evals", 9) << "time (ms)\n";
  for (const ToleranceRow& row : study.rows) {
    out << pad(number(row.tol, 2), 8);
    if (!row.failure.empty()) {
      out << "failed: " << row.failure << "\n";
      continue;
    }
    out << pad(number(row.error.max_pos), 13) << pad(number(row.error.end_pos), 13)
        << pad(number(row.error.max_angle), 15) << pad(std::to_string(row.stats.accepted), 8)
        << pad(std::to_string(row.stats.rejected), 10) << pad(std::to_string(row.stats.events), 8)
        << pad(std::to_string(row.stats.evaluations), 9) << number(row.seconds * 1e3, 3) << "\n";
  }
}

void write_reference_study_csv(std::FILE* out, const std::string& scene_name,
                               const ReferenceStudy& study) {
  std::fprintf(out,
               "scene,tol,truth_tol,max_pos_err,end_pos_err,max_angle_err,steps,rejected,events,"
               "evaluations,seconds,amplification\n");
  for (const ToleranceRow& row : study.rows) {
    const bool ok = row.failure.empty();
    std::fprintf(out, "%s,%s,%s,%s,%s,%s,%lld,%lld,%lld,%lld,%s,%s\n", scene_name.c_str(),
                 csv_number(row.tol).c_str(), csv_number(study.truth_tol).c_str(),
                 ok ? csv_number(row.error.max_pos).c_str() : "",
                 ok ? csv_number(row.error.end_pos).c_str() : "",
                 ok ? csv_number(row.error.max_angle).c_str() : "", row.stats.accepted,
                 row.stats.rejected, row.stats.events, row.stats.evaluations,
                 csv_number(row.seconds).c_str(), csv_number(study.amplification).c_str());
  }
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
  out << pad("engine", 8) << pad("integrator", 21) << pad("k (N/m)", 9) << pad("zeta", 9)
      << pad("omega", 10) << pad("stable dt", 11) << pad("omega*dt", 10) << pad("theory", 8)
      << pad("ratio", 7) << pad("depth (m)", 11) << pad("at wdt=0.2", 11) << pad("ref depth", 10)
      << "first failure / note\n";
  for (const StabilityRow& row : r.rows) {
    out << pad(row.engine, 8) << pad(std::string(integrator_name(row.integrator)), 21)
        << pad(number(row.k, 2), 9) << pad(number(row.zeta, 3), 9) << pad(number(row.omega, 4), 10);
    std::string stable;
    switch (row.verdict) {
      case StabilityVerdict::Bracketed: stable = number(row.dt_stable, 3); break;
      case StabilityVerdict::StableAtMax: stable = ">=" + number(row.dt_stable, 3); break;
      case StabilityVerdict::UnstableAtMin: stable = "<" + number(row.dt_min, 3); break;
      case StabilityVerdict::Failed: stable = "failed"; break;
    }
    const double observed = row.omega * row.dt_stable;
    out << pad(stable, 11)
        << pad(std::isnan(row.dt_stable)
                   ? "-"
                   : (row.verdict == StabilityVerdict::StableAtMax ? ">=" : "") +
                         number(observed, 3),
               10)
        << pad(std::isfinite(row.theory) ? number(row.theory, 3) : "inf", 8)
        << pad(std::isfinite(row.theory) && !std::isnan(row.dt_stable)
                   ? number(observed / row.theory, 3)
                   : "-",
               7)
        << pad(number(row.penetration, 3), 11) << pad(number(row.penetration_small_step, 3), 11)
        << pad(number(row.reference_penetration, 3), 10);
    std::string tail = row.failure;
    if (!row.note.empty()) tail += (tail.empty() ? "" : "; ") + row.note;
    out << tail << "\n";
  }
}

void write_stability_csv(std::FILE* out, const StabilityResult& r) {
  std::fprintf(out,
               "scene,engine,integrator,k,c,m_eff,omega,zeta,theory_omega_dt,theory_dt,dt_stable,"
               "dt_unstable,"
               "dt_min,dt_max,verdict,omega_dt_stable,probes,penetration,penetration_small_step,"
               "reference_penetration,"
               "failure,note\n");
  for (const StabilityRow& row : r.rows) {
    std::fprintf(out, "%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%d,%s,%s,%s,%s,%s\n",
                 r.scene_name.c_str(), row.engine.c_str(),
                 std::string(integrator_name(row.integrator)).c_str(), csv_number(row.k).c_str(),
                 csv_number(row.c).c_str(), csv_number(row.m_eff).c_str(),
                 csv_number(row.omega).c_str(), csv_number(row.zeta).c_str(),
                 std::isfinite(row.theory) ? csv_number(row.theory).c_str() : "inf",
                 std::isfinite(row.theory) ? csv_number(row.theory / row.omega).c_str() : "inf",
                 csv_number(row.dt_stable).c_str(), csv_number(row.dt_unstable).c_str(),
                 csv_number(row.dt_min).c_str(), csv_number(r.dt_max).c_str(),
                 verdict_name(row.verdict), csv_number(row.omega * row.dt_stable).c_str(),
                 row.probes, csv_number(row.penetration).c_str(),
                 csv_number(row.penetration_small_step).c_str(),
                 csv_number(row.reference_penetration).c_str(), csv_text(row.failure).c_str(),
                 csv_text(row.note).c_str());
  }
}

void plot_stability(const std::string& png_path, const StabilityResult& r) {
  AtomicFile png(png_path);  // gnuplot writes the temporary file; renamed on success
  const std::string& png_tmp = png.temp_path();
  AtomicFile data_file(png_path + ".dat");  // never committed: removed on return
  std::FILE* f = data_file.get();
  const std::string& data = data_file.temp_path();
  std::vector<std::pair<std::string, Integrator>> keys;
  for (const StabilityRow& row : r.rows) {
    const auto key = std::make_pair(row.engine, row.integrator);
    if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
  }
  // Per block: k, bracketed ω·Δt, theory ω·Δt, lower bound (stable up to
  // dt_max), upper bound (unstable down to dt_min); '?' where absent.
  std::vector<std::string> titles;
  std::vector<bool> has_theory;
  std::vector<std::array<bool, 3>> has;  // bracketed, lower bound, upper bound
  for (const auto& key : keys) {
    bool theory = false;
    std::array<bool, 3> any{false, false, false};
    for (const StabilityRow& row : r.rows) {
      if (row.engine != key.first || row.integrator != key.second) continue;
      const double observed = row.omega * row.dt_stable;
      const bool bracketed = row.verdict == StabilityVerdict::Bracketed;
      const bool lower = row.verdict == StabilityVerdict::StableAtMax;
      const bool upper = row.verdict == StabilityVerdict::UnstableAtMin;
      std::fprintf(f, "%.9g %s %s %s %s\n", row.k, bracketed ? number(observed, 6).c_str() : "?",
                   std::isfinite(row.theory) ? number(row.theory, 6).c_str() : "?",
                   lower ? number(observed, 6).c_str() : "?",
                   upper ? number(row.omega * row.dt_min, 6).c_str() : "?");
      theory = theory || std::isfinite(row.theory);
      any[0] = any[0] || bracketed;
      any[1] = any[1] || lower;
      any[2] = any[2] || upper;
    }
    has.push_back(any);
    std::fprintf(f, "\n\n");
    titles.push_back(series_title(key.first, key.second));
    has_theory.push_back(theory);
  }
  if (std::fflush(f) != 0) throw std::runtime_error(data + ": cannot write plot data");

  std::ostringstream s;
  s << "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size 1000,650 font "
       "',11' } "
       "else { set terminal png size 1000,650 }\n"
    << "set output " << gnuplot_quoted(png_tmp) << "\n"
    << "set title '" << gnuplot_text(r.scene_name)
    << ": largest stable {/Symbol w}{/Symbol D}t against contact stiffness"
    << (r.zeta ? " ({/Symbol z} = " + number(*r.zeta, 3) + " at every k)"
               : std::string(" (c of the scene file at every k)"))
    << "'\n"
    << "set logscale xy\nset grid\nset format x '10^{%L}'\nset datafile missing '?'\nset key "
       "outside right font ',9'\n"
    << "set xlabel 'contact stiffness k (N/m)'\nset ylabel 'largest stable {/Symbol w}{/Symbol "
       "D}t'\n"
    << "plot ";
  bool first = true;
  for (size_t i = 0; i < keys.size(); ++i) {
    // The first plotted element of each series carries its title.
    std::string title = " title '" + gnuplot_text(titles[i]) + "'";
    auto element = [&](const std::string& spec) {
      s << (first ? "" : ", ") << gnuplot_quoted(data) << " index " << i << " using " << spec
        << title;
      first = false;
      title = " notitle";
    };
    if (has[i][0])
      element("1:2 with linespoints pt " + std::to_string(i % 7 + 1) + " ps 1.5 lc " +
              std::to_string(i + 1));
    if (has[i][1]) element("1:4 with points pt 8 ps 1.5 lc " + std::to_string(i + 1));
    if (has[i][2]) element("1:5 with points pt 10 ps 1.5 lc " + std::to_string(i + 1));
    if (has_theory[i]) {
      title = " notitle";
      element("1:3 with lines dt 2 lc " + std::to_string(i + 1));
    }
  }
  if (first) throw std::runtime_error(png_path + ": nothing to plot");
  s << ", NaN with lines dt 2 lc 'black' title 'linear theory', NaN with points pt 8 lc 'black' "
       "title "
       "'stable up to the largest dt tried', NaN with points pt 10 lc 'black' title 'unstable at "
       "the smallest dt tried'";
  s << "\n";
  run_gnuplot(s.str(), png_tmp);
  png.commit();
}

// ---------------------------------------------------------------- gnuplot

std::string run_summary(const Scene& scene, const std::string& engine, const EngineRun& run) {
  const Model model = make_model(scene);
  const auto& samples = run.trajectory.samples;
  double deepest = 0.0;
  for (const Sample& s : samples) deepest = std::max(deepest, max_penetration(model, s.state.q));
  const State& first = samples.front().state;
  const State& last = samples.back().state;
  return std::string(shape_name(scene.shape)) + " [" + engine + ", " +
         std::string(integrator_name(scene.sim.integrator)) +
         ", dt = " + format_number(scene.sim.dt) + " s, " + format_number(scene.sim.duration) +
         " s in " + format_number(run.seconds * 1e3, 3) +
         " ms]: final x = " + format_number(last.q.x()) + " m, y = " + format_number(last.q.y()) +
         " m, theta = " + format_number(last.q.z()) +
         " rad, |v| = " + format_number(last.v.head<2>().norm()) +
         " m/s; max sampled penetration " + format_number(deepest) + " m; energy " +
         format_number(energy(model, first)) + " -> " + format_number(energy(model, last)) + " J";
}

}  // namespace contact2d::analysis
