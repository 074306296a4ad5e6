#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "analysis/real_impacts.hpp"
#include "core/format.hpp"
#include "io/atomic_file.hpp"
#include "io/plot.hpp"

namespace contact2d::analysis {

namespace {

const SplitFit& impact_split(const ImpactFit& fit, const std::string& split) {
  for (const SplitFit& s : fit.splits)
    if (s.split == split) return s;
  throw std::runtime_error("real impacts: no split '" + split + "' to plot");
}

const ModelFit* impact_model(const SplitFit& s, const std::string& name,
                             const std::string& engine) {
  for (const ModelFit& m : s.models)
    if (m.name == name && m.engine == engine) return &m;
  return nullptr;
}

void flush_plot_data(std::FILE* f, const std::string& data) {
  if (std::fflush(f) != 0) throw std::runtime_error(data + ": cannot write plot data");
}

std::string impact_model_title(const ModelFit& m) {
  return m.name + (m.engine == "baseline" ? std::string() : " (" + m.engine + ")");
}

}  // namespace

void plot_impact_predictions(const std::string& png_path, const ImpactFit& fit,
                             const std::string& split) {
  const SplitFit& s = impact_split(fit, split);
  const std::vector<const ModelFit*> models = {impact_model(s, "penalty", "ref"),
                                               impact_model(s, "newton_coulomb", "baseline"),
                                               impact_model(s, "irb_bound", "baseline")};
  AtomicFile png(png_path);
  AtomicFile data_file(png_path + ".dat");  // never committed: removed on return
  std::FILE* f = data_file.get();
  const std::string& data = data_file.temp_path();
  // One block per model: measured vx, vy, ω, then predicted vx, vy, ω; and
  // each quantity's extent over every model, so that a column's panels
  // share their axes.
  int blocks = 0;
  std::array<double, 3> lo{}, hi{};
  lo.fill(std::numeric_limits<double>::infinity());
  hi.fill(-std::numeric_limits<double>::infinity());
  for (const ModelFit* m : models) {
    if (!m) continue;
    for (size_t i = 0; i < s.test.size(); ++i) {
      const Vec3& v = fit.impacts[s.test[i]].after.v;
      const Vec3& p = m->predicted[i];
      std::fprintf(f, "%.6g %.6g %.6g %.6g %.6g %.6g\n", v.x(), v.y(), v.z(), p.x(), p.y(), p.z());
      for (Eigen::Index c = 0; c < 3; ++c) {
        const auto k = static_cast<size_t>(c);
        lo[k] = std::min({lo[k], v[c], p[c]});
        hi[k] = std::max({hi[k], v[c], p[c]});
      }
    }
    std::fprintf(f, "\n\n");
    ++blocks;
  }
  flush_plot_data(f, data);
  const char* colours[] = {"'#1f77b4'", "'#ff7f0e'", "'#2ca02c'"};
  const char* labels[] = {"v_x after (m/s)", "v_y after (m/s)", "ω after (rad/s)"};
  // One row per model, one column per quantity: drawn in one panel, the
  // model drawn last hid the others' points where they overlap.
  std::ostringstream g;
  g << gnuplot_png(png.temp_path(), 1500, 60 + 430 * std::max(blocks, 1)) << "set multiplot layout "
    << std::max(blocks, 1) << ",3 title '"
    << gnuplot_text(std::to_string(s.test.size()) + " held-out impacts (" + split +
                    " split): predicted against measured, one model a row; on the diagonal a "
                    "model is exact")
    << "' font ',13'\nset grid\nset key top left font ',10'\nset size ratio -1\n";
  int b = 0;
  for (size_t j = 0; j < models.size(); ++j) {
    if (!models[j]) continue;
    for (int c = 0; c < 3; ++c) {
      const auto k = static_cast<size_t>(c);
      const double pad = 0.05 * (hi[k] - lo[k]);
      g << "set xlabel 'measured " << labels[c] << "'\nset ylabel 'predicted " << labels[c] << "'\n"
        << (std::isfinite(pad)
                ? "set xrange [" + format_number(lo[k] - pad, 4) + ":" +
                      format_number(hi[k] + pad, 4) + "]\nset yrange [" +
                      format_number(lo[k] - pad, 4) + ":" + format_number(hi[k] + pad, 4) + "]\n"
                : std::string())
        << "plot " << gnuplot_quoted(data) << " index " << b << " using " << (c + 1) << ":"
        << (c + 4) << " with points pt 7 ps 0.35 lc rgb " << colours[j] << " title '"
        << gnuplot_text(impact_model_title(*models[j]))
        << "', x with lines lc 'black' dt 2 notitle\n";
    }
    ++b;
  }
  g << "unset multiplot\n";
  if (blocks == 0) throw std::runtime_error(png_path + ": no model to plot");
  run_gnuplot(g.str(), png_path);
  png.commit();
}

void plot_impact_errors(const std::string& png_path, const ImpactFit& fit,
                        const std::string& split) {
  const SplitFit& s = impact_split(fit, split);
  AtomicFile png(png_path);
  AtomicFile data_file(png_path + ".dat");
  std::FILE* f = data_file.get();
  const std::string& data = data_file.temp_path();
  // One block per model: its sorted errors and the fraction of impacts at or below.
  std::vector<std::string> titles;
  for (const ModelFit& m : s.models) {
    std::vector<double> e = m.errors;
    std::sort(e.begin(), e.end());
    for (size_t i = 0; i < e.size(); ++i)
      std::fprintf(f, "%.6g %.6g\n", e[i],
                   static_cast<double>(i + 1) / static_cast<double>(e.size()));
    std::fprintf(f, "\n\n");
    titles.push_back(impact_model_title(m) + ": median " + format_number("%.3f", m.median));
  }
  flush_plot_data(f, data);
  std::ostringstream g;
  g << gnuplot_png(png.temp_path(), 1100, 650) << "set title '"
    << gnuplot_text("held-out error of every model (" + split +
                    " split): the fraction of impacts predicted at least that well")
    << "' font ',13'\nset grid\nset xrange [0:1.5]\nset yrange [0:1]\n"
    << "set xlabel '|W(v_{predicted} - v)| / |W v| after the impact'\n"
    << "set ylabel 'fraction of held-out impacts'\nset key bottom right font ',10'\n"
    << "set arrow from 0,0.5 to 1.5,0.5 nohead dt 3 lc 'gray50'\nplot ";
  // The reference's fit (the first model) wide and drawn first: the engines
  // that replay its parameters follow it closely and are drawn over it,
  // dashed, so that both stay visible where they coincide.
  for (size_t b = 0; b < titles.size(); ++b) {
    g << (b ? ", " : "") << gnuplot_quoted(data) << " index " << b << " using 1:2 with steps lw "
      << (b == 0 ? 6 : 2) << " dt " << (b < 2 ? 1 : (b < 4 ? 2 : 4)) << " title '"
      << gnuplot_text(titles[b]) << "'";
  }
  g << "\n";
  run_gnuplot(g.str(), png_path);
  png.commit();
}

void plot_k_profile(const std::string& png_path, const ImpactFit& fit) {
  const SplitFit& s = impact_split(fit, "seeded");
  if (s.k_profile.empty()) throw std::runtime_error(png_path + ": no profile of k to plot");
  AtomicFile png(png_path);
  AtomicFile data_file(png_path + ".dat");
  std::FILE* f = data_file.get();
  const std::string& data = data_file.temp_path();
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& [k, e] : s.k_profile) {
    std::fprintf(f, "%.6g %.6g\n", k, e);
    lo = std::min(lo, e);
    hi = std::max(hi, e);
  }
  flush_plot_data(f, data);
  std::ostringstream g;
  g << gnuplot_png(png.temp_path(), 900, 520) << "set title '"
    << gnuplot_text(
           "how well k is determined: the training median error with k held, ζ, μ, "
           "μ_roll refitted (seeded split)")
    << "' font ',12'\nset grid\nset logscale x\nset format x '10^{%L}'\n"
    << gnuplot_range("x", s.k_profile.front().first, s.k_profile.back().first, true)
    << gnuplot_range("y", lo, hi, false) << "set xlabel 'k (N/m)'\n"
    << "set ylabel 'median error, training impacts'\nunset key\nplot " << gnuplot_quoted(data)
    << " using 1:2 with linespoints lw 2 pt 7 lc '#1f77b4'\n";
  run_gnuplot(g.str(), png_path);
  png.commit();
}

}  // namespace contact2d::analysis
