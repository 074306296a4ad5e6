// PNG plot of a comparison with gnuplot (Debian package gnuplot-nox):
// x, y and θ of both engines against t, and the position and angle errors
// on a log scale. The PNG appears (renamed from a temporary) only when
// gnuplot succeeded.
#pragma once

#include <string>

#include "core/run.hpp"

namespace contact2d {

// Throws InputError when the path cannot be written or gnuplot fails.
// gnuplot is the one plotting back end: every plot of the project is a
// script piped to `gnuplot` (Debian gnuplot-nox) by run_gnuplot().

// Runs gnuplot on the script. Throws InputError when gnuplot is missing or
// fails, naming `png_path` (the plot it was drawing).
void run_gnuplot(const std::string& script, const std::string& png_path);

// 'path' for a gnuplot script; InputError if it contains a quote or newline.
std::string gnuplot_quoted(const std::string& path);

// Text for a gnuplot title or key: enhanced-text specials (_ ^ { } @ &)
// escaped, quotes doubled, so "point_mass" is not set as a subscript.
std::string gnuplot_text(const std::string& text);

void plot_comparison(const std::string& png_path, const std::string& title, const Trajectory& ref,
                     const Trajectory& mujoco);

}  // namespace contact2d
