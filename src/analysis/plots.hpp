// gnuplot PNGs of the sweep and the stability map (io/plot.hpp runs
// gnuplot); their tables and CSV are analysis/tables.hpp.
#pragma once

#include <string>

#include "analysis/stability.hpp"
#include "analysis/sweep.hpp"

namespace contact2d::analysis {

// Work–precision diagram (max position error against wall-clock, log–log)
// beside error against Δt. Throws std::runtime_error when gnuplot fails.
void plot_sweep(const std::string& png_path, const SweepResult& result);

// Largest stable ω·Δt against k per engine/integrator, with the theoretical
// bounds as lines. Throws std::runtime_error when gnuplot fails.
void plot_stability(const std::string& png_path, const StabilityResult& result);

}  // namespace contact2d::analysis
