// What the analysis needs from an engine: run a scene, return the sampled
// trajectory and the wall-clock time of the run loop — the engine
// registry's run_engine() (engines/engines.hpp). Tests can pass a runner of
// their own (an engine that fails on purpose, say).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/run.hpp"
#include "engines/engines.hpp"

namespace contact2d::analysis {

using EngineRun = engines::EngineRun;

// Runs `scene` (its sim.integrator and sim.dt included) on the named engine;
// may throw (std::exception) for an engine or integrator it cannot run.
using EngineRunner = std::function<EngineRun(const std::string& engine, const Scene& scene)>;

// The registry's engines (engines::run_engine by name).
EngineRunner registry_runner();

// Nominal order of an engine's integrator: 1 for the Euler methods (MuJoCo's
// Euler and implicit included), 4 for RK4.
double nominal_order(Integrator integrator);

// Runs task(i) for every i in [0, n) on `threads` threads (0:
// default_threads());
// indices are handed out in order, and task(0) runs on the calling thread
// (the report's animations, which a GLFW window must draw there). The first
// exception thrown by a task is rethrown after all threads have finished.
void parallel_for(size_t n, unsigned threads, const std::function<void(size_t)>& task);
// One per core this process may run on (its CPU affinity), at least 1.
unsigned default_threads();

}  // namespace contact2d::analysis

namespace contact2d::analysis {

// "rk4,semi_implicit_euler" → integrators; throws std::invalid_argument
// naming the unknown entry.
std::vector<Integrator> parse_integrators(const std::vector<std::string>& names);

}  // namespace contact2d::analysis
