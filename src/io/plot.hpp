// gnuplot is the one plotting back end: every plot of the project is a
// script piped to `gnuplot` (Debian gnuplot-nox) by run_gnuplot(), which
// reports anything gnuplot prints on stderr. The rules every plot follows:
// units on every axis (metres and radians never share one); legends outside
// the data; titles escaped (gnuplot_text); no empty panel; every axis range
// set from the data (an empty range would make gnuplot warn); the Okabe–Ito
// palette (readable by colour-blind readers) with markers and dash types
// that also tell the series apart in grey.
#pragma once

#include <limits>

#include <cmath>

#include <algorithm>

#include <string>
#include <vector>

#include "core/integrators.hpp"
#include "core/run.hpp"
#include "io/atomic_file.hpp"

namespace contact2d {

// The smallest and largest finite value seen (axis ranges of the plots).
struct Extent {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    if (!std::isfinite(v)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
};

// Runs gnuplot on the script. Throws InputError when gnuplot is missing or
// fails, naming `png_path` (the plot it was drawing). Whatever gnuplot
// prints on stderr is passed on, one "contact2d: gnuplot warning" line each:
// a plot that makes gnuplot warn is a bug (tests/cli checks every plot).
void run_gnuplot(const std::string& script, const std::string& png_path);

// 'path' for a gnuplot script; InputError if it contains a quote or newline.
std::string gnuplot_quoted(const std::string& path);

// Text for a gnuplot title or key: enhanced-text specials (_ ^ { } @ &)
// escaped, quotes doubled, so "point_mass" is not set as a subscript.
std::string gnuplot_text(const std::string& text);

// The opening of every plot script: UTF-8, a PNG terminal (pngcairo when
// gnuplot has it) of this size, output to `png_tmp`.
std::string gnuplot_png(const std::string& png_tmp, int width, int height);

// "set xrange [lo:hi]\n" for `axis` ("x", "y") around data in [lo, hi],
// padded (by a factor on a log axis), never empty: a constant curve gets a
// range around its value. On a log axis also its tic format: powers of ten
// over two decades or more, plain numbers below.
std::string gnuplot_range(const char* axis, double lo, double hi, bool log);

// Where a value falls on the log axis gnuplot_range sets for data in
// [lo, hi], as a fraction of the axis (0 bottom, 1 top).
double log_axis_fraction(double value, double lo, double hi);

// Label heights (axis fractions) pushed apart to at least `gap` from each
// other, in the order given, moved as little as possible and kept at or
// below `top`: labels of lines that nearly coincide do not overlap.
std::vector<double> spread_labels(const std::vector<double>& fractions, double gap, double top);

// A value for a log axis in a plot data file: "?" (gnuplot's missing value
// where the script sets `set datafile missing '?'`) when it is not > 0,
// which has no logarithm, so the line skips it rather than falling to the
// bottom of the panel.
std::string log_axis_value(double value);

// Okabe–Ito colours as gnuplot specs ("rgb '#0072B2'"), one per integrator:
// explicit Euler vermillion, semi-implicit Euler blue, implicit Euler bluish
// green, RK4 reddish purple (Rec. 601 grey levels 0.47, 0.34, 0.42, 0.59).
std::string integrator_colour(Integrator integrator);
inline constexpr const char* kColourRef = "rgb '#0072B2'";     // blue
inline constexpr const char* kColourSecond = "rgb '#D55E00'";  // vermillion

// x, y (and θ unless it stays 0 in both runs, as for a point mass) of two
// runs against t, and below them the distance between them: position
// (m) and angle (rad) in separate panels, each on a log axis. `ref_label` and
// `second_label` name the curves. The PNG appears (renamed from a temporary)
// only when gnuplot succeeded. Throws InputError when the path cannot be
// written or gnuplot fails.
void plot_comparison(const std::string& png_path, const std::string& title, const Trajectory& ref,
                     const Trajectory& second, const std::string& ref_label,
                     const std::string& second_label);
// The same drawn into `png` (its temporary), which the caller commits with
// its other outputs.
void plot_comparison(AtomicFile& png, const std::string& title, const Trajectory& ref,
                     const Trajectory& second, const std::string& ref_label,
                     const std::string& second_label);

}  // namespace contact2d
