#include "io/plot.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <limits>
#include <sstream>
#include <vector>

#include "core/format.hpp"
#include "core/input_error.hpp"
#include "io/atomic_file.hpp"
#include "io/child_process.hpp"

namespace contact2d {
namespace {

// Columns: t, x, y, θ (first run), x, y, θ (second run), position
// distance, angle difference.
void write_data(std::FILE* out, const Trajectory& ref, const Trajectory& mj) {
  const size_t n = std::min(ref.samples.size(), mj.samples.size());
  for (size_t i = 0; i < n; ++i) {
    const State& a = ref.samples[i].state;
    const State& b = mj.samples[i].state;
    const double pos = (a.q.head<2>() - b.q.head<2>()).norm();
    const double angle = std::abs(a.q.z() - b.q.z());
    std::fprintf(out, "%.9g %.12g %.12g %.12g %.12g %.12g %.12g %s %s\n", ref.samples[i].t, a.q.x(),
                 a.q.y(), a.q.z(), b.q.x(), b.q.y(), b.q.z(), log_axis_value(pos).c_str(),
                 log_axis_value(angle).c_str());
  }
}

// Range of a distance on a log axis: from 1e-9 of its largest value (and
// not below 1e-16) to above it; a distance that is 0 throughout gets a
// range of its own and the panel says so.
std::string distance_range(double largest) {
  if (!(largest > 1e-290)) return "set yrange [1e-16:1e-12]\n";
  return gnuplot_range("y", std::max(largest * 1e-9, 1e-16), largest, true);
}

std::string script(const std::string& data, const std::string& png, const std::string& title,
                   const Trajectory& ref, const Trajectory& mj, const std::string& ref_label,
                   const std::string& second_label) {
  const size_t n = std::min(ref.samples.size(), mj.samples.size());
  Extent t, x, y, theta;
  double pos_max = 0.0, angle_max = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const State& a = ref.samples[i].state;
    const State& b = mj.samples[i].state;
    t.add(ref.samples[i].t);
    x.add(a.q.x());
    x.add(b.q.x());
    y.add(a.q.y());
    y.add(b.q.y());
    theta.add(a.q.z());
    theta.add(b.q.z());
    pos_max = std::max(pos_max, (a.q.head<2>() - b.q.head<2>()).norm());
    angle_max = std::max(angle_max, std::abs(a.q.z() - b.q.z()));
  }
  // A point mass (or a body that never turns) gets no θ panels.
  const bool turns = theta.lo != 0.0 || theta.hi != 0.0;
  const std::string d = gnuplot_quoted(data);
  std::ostringstream s;
  s << gnuplot_png(png, 1400, 900) << "set multiplot title '" << gnuplot_text(title)
    << "' font ',13'\n"
    << "set grid\nset xlabel 't (s)'\n"
    << gnuplot_range("x", t.lo, t.hi, false)
    // The key above each panel, outside the data.
    << "set key outside top center horizontal\n";
  const int top = turns ? 3 : 2;
  const double w = 1.0 / top;
  auto panel = [&](int i, const char* label, int ref_col, int mj_col, const Extent& e) {
    s << "set size " << w << ",0.46\nset origin " << i * w << ",0.47\n"
      << "set ylabel '" << label << "'\n"
      << gnuplot_range("y", e.lo, e.hi, false) << "plot " << d << " using 1:" << ref_col
      << " with lines lw 2 lc " << kColourRef << " title '" << gnuplot_text(ref_label) << "', " << d
      << " using 1:" << mj_col << " with lines lw 2 dt 2 lc " << kColourSecond << " title '"
      << gnuplot_text(second_label) << "'\n";
  };
  panel(0, "x (m)", 2, 5, x);
  panel(1, "y (m)", 3, 6, y);
  if (turns) panel(2, "θ (rad)", 4, 7, theta);
  // The distance between the engines, one panel per unit.
  const int bottom = turns ? 2 : 1;
  const double wb = 1.0 / bottom;
  s << "unset key\nset logscale y\nset format y '10^{%L}'\nset datafile missing '?'\n";
  auto distance = [&](int i, const std::string& label, int col, double largest) {
    s << "set size " << wb << ",0.46\nset origin " << i * wb << ",0.0\n"
      << "set ylabel '" << gnuplot_text(label) << "'\n"
      << distance_range(largest);
    if (!(largest > 1e-290)) {
      s << "set label 1 'identical: the distance is 0 at every sample' at graph 0.5,0.5 center\n"
        << "plot NaN notitle\nunset label 1\n";
      return;
    }
    s << "plot " << d << " using 1:" << col << " with lines lw 2 lc 'black' notitle\n";
  };
  const std::string pair = ref_label + " ↔ " + second_label;
  distance(0, "position distance " + pair + " (m)", 8, pos_max);
  if (turns) distance(1, "angle difference " + pair + " (rad)", 9, angle_max);
  s << "unset multiplot\n";
  return s.str();
}

void require_quotable(const std::string& text, const std::string& what) {
  if (text.find('\'') != std::string::npos || text.find('\n') != std::string::npos) {
    throw InputError(what + " '" + text +
                     "' must not contain a single quote or newline (gnuplot script)");
  }
}

}  // namespace

void plot_comparison(const std::string& png_path, const std::string& title, const Trajectory& ref,
                     const Trajectory& second, const std::string& ref_label,
                     const std::string& second_label) {
  require_quotable(png_path, "--plot");
  AtomicFile png(png_path);  // gnuplot writes here; renamed on success
  plot_comparison(png, title, ref, second, ref_label, second_label);
  png.commit();
}

void plot_comparison(AtomicFile& png, const std::string& title, const Trajectory& ref,
                     const Trajectory& second, const std::string& ref_label,
                     const std::string& second_label) {
  require_quotable(png.path(), "--plot");
  AtomicFile data(png.path() + ".data");  // never committed: removed on return
  write_data(data.get(), ref, second);
  if (std::fflush(data.get()) != 0) throw InputError(data.temp_path() + ": cannot write plot data");
  run_gnuplot(
      script(data.temp_path(), png.temp_path(), title, ref, second, ref_label, second_label),
      png.path());
}

void run_gnuplot(const std::string& script, const std::string& png_path) {
  // gnuplot is started directly (no shell), registered with the interrupt
  // handler (it writes an output file), fed the script on its input; its
  // output is dropped and its standard error read back and passed on below.
  ChildEnding end;
  try {
    ChildProcess gnuplot({"gnuplot"}, {}, /*writes_output=*/true);
    gnuplot.write(script);
    end = gnuplot.finish();
  } catch (const ChildProcessError& e) {
    if (e.spawn_error == ENOENT)
      throw InputError(png_path + ": gnuplot not found (install Debian package gnuplot-nox)");
    throw InputError(png_path + ": gnuplot " + e.what());
  }
  std::vector<std::string> messages;
  {
    std::istringstream in(end.standard_error);
    std::string line;
    while (std::getline(in, line)) {
      // gnuplot marks the place in the script with "^" lines and blanks.
      if (line.find_first_not_of(" \t^") != std::string::npos) messages.push_back(line);
    }
  }
  if (end.status != 0) {
    const std::string how =
        end.status >= 0 ? "exit status " + std::to_string(end.status) : end.description;
    throw InputError(png_path + ": gnuplot failed (" + how + ")" +
                     (messages.empty() ? "" : ": " + messages.front()));
  }
  for (const std::string& m : messages)
    std::cerr << "contact2d: gnuplot warning drawing " << png_path << ": " << m << "\n";
}

std::string gnuplot_quoted(const std::string& path) {
  if (path.find('\'') != std::string::npos || path.find('\n') != std::string::npos) {
    throw InputError(path + ": a plot path must not contain a quote or newline");
  }
  return "'" + path + "'";
}

std::string gnuplot_text(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '_' || c == '^' || c == '{' || c == '}' || c == '@' || c == '&' || c == '~')
      out += '\\';
    if (c == '\'') {
      out += "''";
      continue;
    }
    if (c == '\n') {
      out += ' ';
      continue;
    }
    out += c;
  }
  return out;
}

std::string gnuplot_png(const std::string& png_tmp, int width, int height) {
  const std::string size = std::to_string(width) + "," + std::to_string(height);
  return "set encoding utf8\n"
         "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size " +
         size + " font ',11' } else { set terminal png size " + size + " }\nset output " +
         gnuplot_quoted(png_tmp) + "\n";
}

std::string log_axis_value(double value) {
  if (!(value > 0.0)) return "?";
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

double log_axis_fraction(double value, double lo, double hi) {
  const double pad = hi > lo * (1 + 1e-12) ? 2.0 : 3.0;  // as gnuplot_range
  const double a = std::log10(lo / pad), b = std::log10(hi * pad);
  return (std::log10(value) - a) / (b - a);
}

std::vector<double> spread_labels(const std::vector<double>& fractions, double gap, double top) {
  std::vector<size_t> order(fractions.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return fractions[a] < fractions[b]; });
  std::vector<double> at(fractions.size());
  for (size_t n = 0; n < order.size(); ++n)  // upwards: each at least `gap` above the last
    at[order[n]] =
        n == 0 ? fractions[order[n]] : std::max(fractions[order[n]], at[order[n - 1]] + gap);
  for (size_t n = order.size(); n-- > 0;)  // downwards: below `top` and `gap` below the next
    at[order[n]] = std::min(at[order[n]], n + 1 < order.size() ? at[order[n + 1]] - gap : top);
  return at;
}

std::string gnuplot_range(const char* axis, double lo, double hi, bool log) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || (log && !(lo > 0.0))) {
    return std::string("set ") + axis + "range [" + (log ? "1e-16:1" : "-1:1") + "]\n";
  }
  double a = lo, b = hi;
  if (log) {
    const double pad = b > a * (1 + 1e-12) ? 2.0 : 3.0;
    a /= pad;
    b *= pad;
  } else if (b - a > 1e-12 * std::max(1.0, std::abs(b))) {
    const double pad = 0.05 * (b - a);
    a -= pad;
    b += pad;
  } else {
    const double pad = std::max(0.05 * std::abs(a), 1e-3);
    a -= pad;
    b += pad;
  }
  std::string out = std::string("set ") + axis + "range [" + format_number(a, 17) + ":" +
                    format_number(b, 17) + "]\n";
  if (!log) return out + "set " + axis + "tics autofreq\n";
  if (b / a >= 100)
    return out + "set " + axis + "tics autofreq\nset format " + axis + " '10^{%L}'\n";
  // Under two decades a log axis has one power of ten or none to label:
  // tics at 1, 2, 5 × 10^n (every digit when that gives fewer than 3).
  std::vector<double> tics;
  for (const std::vector<int>& digits : {std::vector<int>{1, 2, 5}, {1, 2, 3, 4, 5, 6, 7, 8, 9}}) {
    tics.clear();
    for (int e = static_cast<int>(std::floor(std::log10(a))); e <= std::ceil(std::log10(b)); ++e) {
      for (int d : digits) {
        const double v = d * std::pow(10.0, e);
        if (v >= a && v <= b) tics.push_back(v);
      }
    }
    if (tics.size() >= 3) break;
  }
  out += std::string("set ") + axis + "tics (";
  for (size_t i = 0; i < tics.size(); ++i) out += (i ? ", " : "") + format_number(tics[i], 3);
  return out + ")\nset format " + axis + " '%g'\n";
}

std::string integrator_colour(Integrator integrator) {
  switch (integrator) {
    case Integrator::ExplicitEuler: return "rgb '#D55E00'";
    case Integrator::SemiImplicitEuler: return "rgb '#0072B2'";
    case Integrator::ImplicitEuler: return "rgb '#009E73'";
    case Integrator::RK4: return "rgb '#CC79A7'";
  }
  return "rgb '#000000'";
}

}  // namespace contact2d
