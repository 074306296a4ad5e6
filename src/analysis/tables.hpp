// Tables and CSV of the sweep, the reference study and the stability map,
// and the one-line summary of a simulated run. No number is ever printed as
// "nan": a missing value is "-" in tables and an empty field in CSV. The
// plots of the same results are analysis/plots.hpp.
#pragma once

#include <cstdio>
#include <ostream>
#include <string>

#include "analysis/reference.hpp"
#include "analysis/stability.hpp"
#include "analysis/sweep.hpp"

namespace contact2d::analysis {

// "%.*g" of a finite value, `missing` otherwise.
std::string number(double value, int digits = 3, const char* missing = "-");

void print_sweep(std::ostream& out, const SweepResult& result);
void print_orders(std::ostream& out, const SweepResult& result);
void write_sweep_csv(std::FILE* out, const SweepResult& result);
void write_orders_csv(std::FILE* out, const SweepResult& result);

void print_reference_study(std::ostream& out, const std::string& scene_name,
                           const ReferenceStudy& study);
void write_reference_study_csv(std::FILE* out, const std::string& scene_name,
                               const ReferenceStudy& study);

void print_stability(std::ostream& out, const StabilityResult& result);
void write_stability_csv(std::FILE* out, const StabilityResult& result);

// The one-line summary `contact2d simulate` prints of a run: scene,
// engine, integrator, Δt, duration, wall clock, final state, deepest sampled
// penetration, energy at the first and last sample and the energy balance:
// its largest rise and the rise the integrator explains (core/divergence.hpp;
// no newline).
std::string run_summary(const Scene& scene, const std::string& engine, const EngineRun& run);

}  // namespace contact2d::analysis
