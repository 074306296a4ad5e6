// What the analysis needs from an engine: run a scene, return the sampled
// trajectory and the wall-clock time of the stepping. The analysis library
// does not link the command line or MuJoCo; the caller passes a runner
// (contact2d's CLI passes its run_engine(), tests pass the reference alone).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/simulate.hpp"

namespace contact2d::analysis {

struct EngineResult {
  Trajectory trajectory;
  double seconds = 0.0;               // wall clock of the run
  std::vector<std::string> warnings;  // anything the engine reported
  // Facts about the run that are not failures, e.g. "refsafe" when MuJoCo
  // raised a standard-form timeconst to 2·Δt (a softer contact than asked).
  std::vector<std::string> notes;
};

// Runs `scene` (its sim.integrator and sim.dt included) on the named engine;
// may throw (std::exception) for an engine or integrator it cannot run.
using EngineRunner = std::function<EngineResult(const std::string& engine, const Scene& scene)>;

// The reference solver (core run() with the divergence rule), timed.
EngineResult run_reference_engine(const Scene& scene);

// A runner that knows "ref" only.
EngineRunner reference_runner();

// Nominal order of an engine's integrator: 1 for the Euler methods (MuJoCo's
// Euler and implicit included), 4 for RK4.
double nominal_order(Integrator integrator);

// Whether an engine offers the integrator: MuJoCo 2.2 has no explicit Euler.
bool engine_offers(const std::string& engine, Integrator integrator);

// Runs task(i) for every i in [0, n) on `threads` threads (0: one per core);
// indices are handed out in order. The first exception thrown by a task is
// rethrown after all threads have finished.
void parallel_for(size_t n, unsigned threads, const std::function<void(size_t)>& task);
unsigned default_threads();

}  // namespace contact2d::analysis

namespace contact2d::analysis {

// "rk4,semi_implicit_euler" → integrators; throws std::invalid_argument
// naming the unknown entry.
std::vector<Integrator> parse_integrators(const std::vector<std::string>& names);

}  // namespace contact2d::analysis
