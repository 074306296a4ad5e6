// PNG plot of a comparison with gnuplot (Debian package gnuplot-nox):
// x, y and θ of both engines against t, and the position and angle errors
// on a log scale. The PNG appears (renamed from a temporary) only when
// gnuplot succeeded.
#pragma once

#include <string>

#include "core/run.hpp"

namespace contact2d::cli {

// Throws InputError when the path cannot be written or gnuplot fails.
void plot_comparison(const std::string& png_path, const std::string& title, const Trajectory& ref,
                     const Trajectory& mujoco);

}  // namespace contact2d::cli
