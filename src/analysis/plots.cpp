// gnuplot PNGs of the sweep and the stability map (analysis/plots.hpp).
#include "analysis/plots.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "analysis/tables.hpp"
#include "core/format.hpp"
#include "engines/engines.hpp"
#include "io/atomic_file.hpp"
#include "io/plot.hpp"

namespace contact2d::analysis {
namespace {

// "ref: rk4", "mujoco:seed: semi_implicit_euler (MuJoCo Euler)": the
// engine and integrator as --engines and --integrators name them.
std::string series_title(const std::string& engine, Integrator integrator) {
  return engine + ": " + engines::integrator_label(engine, integrator);
}

// The name of a series' stability limit: its integrator's, or where the
// engine integrates contact forces with another integrator (MuJoCo's
// implicit: semi-implicit Euler's limit), the engine's title and its own
// name of the integrator ("MuJoCo implicit").
std::string theory_name(const std::string& engine, Integrator integrator) {
  if (engines::contact_integrator(engine, integrator) == integrator)
    return std::string(integrator_name(integrator));
  const engines::EngineInfo* info = engines::find_engine(engine);
  return std::string(info->title) + " " + engines::own_integrator_name(engine, integrator);
}

// How a series of an engine is drawn: the reference solid with small
// filled markers; each MuJoCo engine dashed with open markers, each larger
// than the last, so curves that coincide (MuJoCo's mappings often do) show
// as nested markers. Colour = integrator, shape = integrator (point_type).
struct EngineStyle {
  double point_size;
  int dash_type;
};
EngineStyle engine_style(size_t engine_index) {
  static const EngineStyle styles[] = {{1.0, 1}, {1.6, 2}, {2.1, 4}, {2.6, 5}};
  return styles[std::min<size_t>(engine_index, 3)];
}

// The marker of one engine's integrator: a shape per integrator (square,
// circle, pentagon, diamond), filled for the reference and open for MuJoCo,
// so that one engine's integrators whose points coincide (MuJoCo's Euler
// and RK4 at small Δt) show as different nested shapes rather than one
// marker hiding another. Triangles are left to the stability map's bounds.
int point_type(const std::string& engine, Integrator integrator) {
  static const int filled[] = {5, 7, 15, 13}, open[] = {4, 6, 14, 12};
  const int i = static_cast<int>(integrator);
  return engine == "ref" ? filled[i] : open[i];
}

// The position of `engine` in the order the engines first appear.
size_t engine_index(std::vector<std::string>& engines, const std::string& engine) {
  auto it = std::find(engines.begin(), engines.end(), engine);
  if (it == engines.end()) {
    engines.push_back(engine);
    return engines.size() - 1;
  }
  return static_cast<size_t>(it - engines.begin());
}

}  // namespace

// ---------------------------------------------------------------- sweep

void plot_sweep(const std::string& png_path, const SweepResult& r) {
  AtomicFile png(png_path);  // gnuplot writes the temporary file; renamed on success
  const std::string& png_tmp = png.temp_path();
  AtomicFile data_file(png_path + ".dat");  // never committed: removed on return
  std::FILE* f = data_file.get();
  const std::string& data = data_file.temp_path();
  // One block per engine/integrator: dt, seconds, max position error.
  std::vector<std::pair<std::string, Integrator>> keys;
  for (const SweepRow& row : r.rows) {
    const auto key = std::make_pair(row.engine, row.integrator);
    if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
  }
  const double floor = std::max(r.reference_error, 1e-16);
  struct Series {
    std::string title;
    Integrator integrator;
    EngineStyle style;
    int point_type;
  };
  std::vector<Series> series;
  std::vector<std::string> engines;
  Extent seconds, dts, errors;
  errors.add(floor);
  for (const auto& key : keys) {
    int points = 0;
    for (const SweepRow& row : r.rows) {
      if (row.engine != key.first || row.integrator != key.second || row.status != RunStatus::Ok)
        continue;
      const double t = std::max(row.seconds, 1e-9), e = std::max(row.error.max_pos, floor / 10);
      std::fprintf(f, "%.9g %.9g %.9g\n", row.dt, t, e);
      seconds.add(t);
      dts.add(row.dt);
      errors.add(e);
      ++points;
    }
    if (points == 0) continue;
    std::fprintf(f, "\n\n");
    const size_t engine = engine_index(engines, key.first);
    series.push_back({series_title(key.first, key.second), key.second, engine_style(engine),
                      point_type(key.first, key.second)});
  }
  // The adaptive method: tolerance in column 1 (no dt), its time and error.
  int dense_points = 0;
  Extent tols;
  for (const ToleranceRow& row : r.dense_curve) {
    if (!row.failure.empty()) continue;
    const double t = std::max(row.seconds, 1e-9), e = std::max(row.error.max_pos, floor / 10);
    std::fprintf(f, "%.9g %.9g %.9g\n", row.tol, t, e);
    tols.add(row.tol);
    seconds.add(t);
    errors.add(e);
    ++dense_points;
  }
  std::fprintf(f, "\n\n");
  if (std::fflush(f) != 0) throw std::runtime_error(data + ": cannot write plot data");
  if (series.empty()) throw std::runtime_error(png_path + ": no run finished, nothing to plot");

  // Two panels side by side above one legend for both.
  const int legend_rows = static_cast<int>((series.size() + 2 + 2) / 3);
  const int height = 600 + 22 * legend_rows;
  const double legend = (30.0 + 22.0 * legend_rows) / height;
  const int blocks = static_cast<int>(series.size());
  std::ostringstream s;
  s << gnuplot_png(png_tmp, 1400, height) << "set multiplot title '" << gnuplot_text(r.scene_name)
    << " (" << number(r.duration, 3)
    << " s): max position error against the converged reference' font ',13'\n"
    << "set logscale xy\nset grid\n"
    << "set ylabel 'max position error (m)'\n"
    << gnuplot_range("y", errors.lo, errors.hi, true) << "set size 0.5,"
    << 1.0 - legend - 40.0 / height << "\nset origin 0," << legend << "\n"
    << "set key at screen 0.5," << legend << " center top vertical maxrows " << legend_rows
    << " reverse Left samplen 3 font ',10'\n"
    << "set xlabel 'wall-clock time of the run (s)'\n"
    << gnuplot_range("x", seconds.lo, seconds.hi, true) << "set title 'work–precision'\n";
  auto plot_lines = [&](const char* using_cols, bool with_dense) {
    s << "plot ";
    for (int i = 0; i < blocks; ++i) {
      const Series& c = series[static_cast<size_t>(i)];
      s << (i ? ", " : "") << gnuplot_quoted(data) << " index " << i << " using " << using_cols
        << " with linespoints lw 2 lc " << integrator_colour(c.integrator) << " dt "
        << c.style.dash_type << " pt " << c.point_type
        << " ps "
        // Grows with the integrator too: one engine's flat curves nest.
        << number(c.style.point_size + 0.35 * static_cast<int>(c.integrator), 3)
        << (with_dense ? " title '" + gnuplot_text(c.title) + "'" : std::string(" notitle"));
    }
    if (with_dense && dense_points > 0) {
      s << ", " << gnuplot_quoted(data) << " index " << blocks
        << " using 2:3 with linespoints lw 2 lc 'black' pt 5 ps 0.8 title 'adaptive DOPRI5 + "
           "events (tol "
        << number(tols.hi, 2) << ".." << number(tols.lo, 2) << ")'";
    }
    s << ", " << number(floor, 3) << " with lines dt 3 lw 2 lc 'gray40' "
      << (with_dense ? "title 'the reference''s own error (" + number(floor, 2) + " m)'"
                     : std::string("notitle"))
      << "\n";
  };
  plot_lines("2:3", true);
  s << "unset key\nset origin 0.5," << legend << "\n"
    << "set xlabel 'time step Δt (s)'\n"
    << gnuplot_range("x", dts.lo, dts.hi, true)
    << "set title 'error against Δt (slope = observed order)'\n";
  plot_lines("1:3", false);
  s << "unset multiplot\n";
  run_gnuplot(s.str(), png_path);
  png.commit();
}

// ------------------------------------------------------------ stability

namespace {

// One engine/integrator of the stability map: a block of the data file.
struct StabilitySeries {
  std::string title;
  Integrator integrator = Integrator::RK4;
  EngineStyle style{};
  int point_type = 7;
  std::string theory_name;                       // the limit's name (theory_name())
  std::array<bool, 3> has{false, false, false};  // bracketed, lower, upper
  std::vector<double> theory;                    // ω·Δt per k (NaN: none)
  double last_k = 0, last_theory_dt = 0, last_theory = 0;
};

// The ranges of the map's axes: k, Δt and ω·Δt.
struct StabilityExtents {
  Extent ks, dts, wdts;
};

// Writes the data file, one block per engine/integrator, in Δt (s) then in
// ω·Δt: bracketed, theory, lower bound (stable up to dt_max), upper bound
// (unstable down to dt_min); '?' where absent. Column 1 is k.
std::vector<StabilitySeries> write_stability_data(std::FILE* f, const StabilityResult& r,
                                                  StabilityExtents& extents) {
  std::vector<std::pair<std::string, Integrator>> keys;
  for (const StabilityRow& row : r.rows) {
    const auto key = std::make_pair(row.engine, row.integrator);
    if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
  }
  std::vector<StabilitySeries> series;
  std::vector<std::string> engines;
  Extent& ks = extents.ks;
  Extent& dts = extents.dts;
  Extent& wdts = extents.wdts;
  auto field = [](bool present, double v) { return present ? number(v, 6) : std::string("?"); };
  for (const auto& key : keys) {
    StabilitySeries c;
    c.title = series_title(key.first, key.second);
    c.integrator = key.second;
    const size_t engine = engine_index(engines, key.first);
    c.style = engine_style(engine);
    c.point_type = point_type(key.first, key.second);
    c.theory_name = theory_name(key.first, key.second);
    for (const StabilityRow& row : r.rows) {
      if (row.engine != key.first || row.integrator != key.second) continue;
      const bool bracketed = row.verdict == StabilityVerdict::Bracketed;
      const bool lower = row.verdict == StabilityVerdict::StableAtMax;
      const bool upper = row.verdict == StabilityVerdict::UnstableAtMin;
      const bool theory = std::isfinite(row.theory) && row.omega > 0;
      const double dt = bracketed || lower ? row.dt_stable : row.dt_min;
      std::fprintf(f, "%.9g %s %s %s %s %s %s %s %s\n", row.k, field(bracketed, dt).c_str(),
                   field(theory, row.theory / row.omega).c_str(), field(lower, dt).c_str(),
                   field(upper, dt).c_str(), field(bracketed, row.omega * dt).c_str(),
                   field(theory, row.theory).c_str(), field(lower, row.omega * dt).c_str(),
                   field(upper, row.omega * dt).c_str());
      ks.add(row.k);
      if (bracketed || lower || upper) {
        dts.add(dt);
        wdts.add(row.omega * dt);
      }
      if (theory) {
        dts.add(row.theory / row.omega);
        wdts.add(row.theory);
        c.last_k = row.k;
        c.last_theory_dt = row.theory / row.omega;
        c.last_theory = row.theory;
      }
      c.theory.push_back(theory ? row.theory : std::nan(""));
      c.has[0] = c.has[0] || bracketed;
      c.has[1] = c.has[1] || lower;
      c.has[2] = c.has[2] || upper;
    }
    std::fprintf(f, "\n\n");
    series.push_back(c);
  }
  return series;
}

// One theory line per distinct limit (engines that share it share the
// line; MuJoCo's implicit has semi-implicit Euler's for contacts), labelled
// at its right end with the integrators it is the limit of.
struct TheoryLines {
  std::vector<size_t> of;          // the series whose limit each line draws
  std::vector<std::string> label;  // its integrators, "semi_implicit_euler = MuJoCo implicit"
};

TheoryLines theory_lines(const std::vector<StabilitySeries>& series) {
  TheoryLines lines;
  std::vector<size_t>& theory_of = lines.of;
  std::vector<std::string>& theory_label = lines.label;
  for (size_t i = 0; i < series.size(); ++i) {
    if (series[i].last_k <= 0) continue;
    const std::string& name = series[i].theory_name;
    bool same = false;
    for (size_t n = 0; n < theory_of.size() && !same; ++n) {
      const StabilitySeries& other = series[theory_of[n]];
      same =
          other.theory.size() == series[i].theory.size() &&
          std::equal(other.theory.begin(), other.theory.end(), series[i].theory.begin(),
                     [](double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); });
      if (same && theory_label[n].find(name) == std::string::npos) theory_label[n] += " = " + name;
    }
    if (!same) {
      theory_of.push_back(i);
      theory_label.push_back(name);
    }
  }
  return lines;
}

// The theory lines' labels of a panel (offset 0: columns in Δt, 4: in
// ω·Δt). They sit in the right margin (outside the plot: no marker covers
// them), each at its line's height as a fraction of the log axis
// gnuplot_range sets (lo/pad to hi·pad), pushed apart to at least one text
// line (0.035 of the panel: a 9-point line of a ~500-pixel panel) where
// lines nearly coincide.
// A limit shared by several integrators gets a line per other name
// under its own, "(= MuJoCo implicit)": the margin is 19 characters.
void theory_labels(std::ostringstream& s, const std::vector<StabilitySeries>& series,
                   const TheoryLines& theory, int offset, const Extent& range) {
  struct Line {
    std::string text;
    double height;
    std::string colour;
  };
  std::vector<Line> lines;
  for (size_t n = 0; n < theory.of.size(); ++n) {
    const StabilitySeries& c = series[theory.of[n]];
    const double h =
        log_axis_fraction(offset ? c.last_theory : c.last_theory_dt, range.lo, range.hi);
    std::string names = theory.label[n];
    const size_t cut = names.find(" = ");
    lines.push_back({names.substr(0, cut) + " theory", h, integrator_colour(c.integrator)});
    for (size_t at = cut; at != std::string::npos;) {  // below it, in order
      const size_t next = names.find(" = ", at + 3);
      lines.push_back(
          {"(= " + names.substr(at + 3, next == std::string::npos ? next : next - at - 3) + ")",
           h - 1e-9 * static_cast<double>(lines.size()), integrator_colour(c.integrator)});
      at = next;
    }
  }
  std::vector<double> heights;
  heights.reserve(lines.size());
  for (const Line& line : lines) heights.push_back(line.height);
  heights = spread_labels(heights, 0.035, 0.98);
  for (size_t n = 0; n < lines.size(); ++n) {
    s << "set label " << n + 1 << " '" << gnuplot_text(lines[n].text) << "' at graph 1.02, graph "
      << number(heights[n], 6) << " left tc " << lines[n].colour << " font ',9'\n";
  }
}

// The plot command of a panel (offset 0: columns in Δt, 4: in ω·Δt): every
// series' bracketed limits and bounds, the theory lines and, with_key, the
// key's entries for the line and marker kinds.
void stability_plot(std::ostringstream& s, const std::string& data,
                    const std::vector<StabilitySeries>& series, const TheoryLines& theory,
                    int offset, bool with_key) {
  s << "plot ";
  bool first = true;
  auto element = [&](size_t i, const std::string& spec, const std::string& title) {
    s << (first ? "" : ", ") << gnuplot_quoted(data) << " index " << i << " using " << spec
      << (with_key && !title.empty() ? " title '" + gnuplot_text(title) + "'"
                                     : std::string(" notitle"));
    first = false;
  };
  auto col = [&](int c) { return "1:" + std::to_string(c + offset); };
  for (size_t i = 0; i < series.size(); ++i) {
    const StabilitySeries& c = series[i];
    const std::string colour = " lc " + integrator_colour(c.integrator);
    const std::string marker =
        " pt " + std::to_string(c.point_type) + " ps " +
        // Grows with the integrator too (as in the sweep): MuJoCo's Euler
        // and implicit coincide on contacts, and nest instead of hiding.
        number(c.style.point_size + 0.35 * static_cast<int>(c.integrator), 3);
    // Bounds often coincide (every series stable at the largest Δt): their
    // markers grow with the engine and the integrator, so they nest.
    const std::string bound_size =
        " ps " + number(c.style.point_size + 0.4 + 0.45 * static_cast<int>(c.integrator), 3);
    std::string title = c.title;
    if (c.has[0]) {
      // Thinner with each integrator, drawn in their order: curves that
      // coincide (MuJoCo's Euler and implicit on contacts) show as a band of
      // the earlier one's colour, a line width or more, on either side of
      // the later one instead of hiding under it.
      constexpr double kWidths[] = {7.5, 6.0, 2.5, 2.0};  // in Integrator's order
      const double width = kWidths[static_cast<size_t>(c.integrator)];
      element(i,
              col(2) + " with linespoints lw " + number(width, 3) + " dt " +
                  std::to_string(c.style.dash_type) + marker + colour,
              title);
      title.clear();
    }
    if (c.has[1]) {
      element(i, col(4) + " with points pt 8" + bound_size + colour, title);
      title.clear();
    }
    if (c.has[2]) {
      element(i, col(5) + " with points pt 10" + bound_size + colour, title);
      title.clear();
    }
  }
  for (size_t i : theory.of) {
    element(i, col(3) + " with lines lw 1.5 dt 3 lc " + integrator_colour(series[i].integrator),
            "");
  }
  if (with_key) {
    s << ", NaN with lines lw 1.5 dt 3 lc 'black' title 'linear theory (labelled with its "
         "integrator)', NaN with points pt 8 ps 2 lc 'black' title 'stable up to the largest Δt "
         "tried', NaN with points pt 10 ps 2 lc 'black' title 'unstable at the smallest Δt "
         "tried'";
  }
  s << "\n";
}

}  // namespace

void plot_stability(const std::string& png_path, const StabilityResult& r) {
  AtomicFile png(png_path);  // gnuplot writes the temporary file; renamed on success
  const std::string& png_tmp = png.temp_path();
  AtomicFile data_file(png_path + ".dat");  // never committed: removed on return
  std::FILE* f = data_file.get();
  const std::string& data = data_file.temp_path();
  StabilityExtents extents;
  const std::vector<StabilitySeries> series = write_stability_data(f, r, extents);
  const Extent& ks = extents.ks;
  const Extent& dts = extents.dts;
  const Extent& wdts = extents.wdts;
  if (std::fflush(f) != 0) throw std::runtime_error(data + ": cannot write plot data");
  if (!(dts.hi > 0)) throw std::runtime_error(png_path + ": nothing to plot");
  const TheoryLines theory = theory_lines(series);

  const size_t entries = series.size() + 3;
  const int legend_rows = static_cast<int>((entries + 2) / 3);
  const int height = 650 + 22 * legend_rows;
  const double legend = (30.0 + 22.0 * legend_rows) / height;
  std::ostringstream s;
  s << gnuplot_png(png_tmp, 1400, height) << "set multiplot title '" << gnuplot_text(r.scene_name)
    << ": largest stable time step against contact stiffness"
    << (r.zeta ? " (ζ = " + number(*r.zeta, 3) + " at every k)"
               : std::string(" (c of the scene file at every k)"))
    << "; ω = √(k/m_{eff})' font ',13'\n"
    << "set logscale xy\nset grid\n"
    << "set datafile missing '?'\nset xlabel 'contact stiffness k (N/m)'\n"
    << "set rmargin 19\n"  // the theory lines' labels
    << gnuplot_range("x", ks.lo, ks.hi, true) << "set size 0.5," << 1.0 - legend - 40.0 / height
    << "\n"
    << "set key at screen 0.5," << legend << " center top vertical maxrows " << legend_rows
    << " reverse Left samplen 3 font ',10'\n";
  s << "set origin 0," << legend << "\nset ylabel 'largest stable Δt (s)'\n"
    << gnuplot_range("y", dts.lo, dts.hi, true) << "set title 'in seconds'\n";
  theory_labels(s, series, theory, 0, dts);
  stability_plot(s, data, series, theory, 0, true);
  // ω·Δt is a number (the phase advanced per step), not an angle: no unit.
  s << "unset key\nset origin 0.5," << legend << "\nset ylabel 'largest stable ω·Δt'\n"
    << gnuplot_range("y", wdts.lo, wdts.hi, true) << "set title 'in ω·Δt'\n";
  theory_labels(s, series, theory, 4, wdts);
  stability_plot(s, data, series, theory, 4, false);
  s << "unset multiplot\n";
  run_gnuplot(s.str(), png_path);
  png.commit();
}

}  // namespace contact2d::analysis
