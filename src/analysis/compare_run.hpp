// One `contact2d compare` run as a library call, shared by the program and
// the Python module (src/python): both engines on one scene, the three-way
// comparison against the converged solution, the diagnosis, and the
// --json text of the result.
//
// The run is cut where a caller has to act between its stages, so that the
// program keeps its order of checks and messages (bad input before any
// work, a divergence before any measurement):
//
//   prepare_comparison   the scene and MuJoCo's model options; throws
//                        InputError for a mapping, geometry or integrator
//                        MuJoCo cannot run (explicit Euler) — no engine has run
//   run_engines          MuJoCo, then the reference, each timed
//   run_problems         why the runs cannot be compared: every engine that
//                        diverged, else every run that is not physics
//                        (core/run.hpp: nonphysical())
//   measure              the three distances and, unless skipped, the
//                        diagnosis (analysis/comparison.hpp)
//   comparison_json      the one JSON object `compare --json` prints
//
// What the run measures and why is in analysis/comparison.hpp; this file
// only sequences it.
#pragma once

#include <string>
#include <vector>

#include "analysis/comparison.hpp"
#include "analysis/trajectory_error.hpp"
#include "core/scene.hpp"
#include "engines/engines.hpp"
#include "mujoco/mjcf.hpp"

namespace contact2d::analysis {

struct Comparison {
  Scene scene;
  engines::EngineSpec spec;  // the MuJoCo engine
  mujoco::MjcfOptions mjcf;  // its model options, as the spec names them
  engines::EngineRun ref;
  engines::EngineRun mujoco;
  TrajectoryError errors;  // ref ↔ MuJoCo
  ThreeWay three;
  Diagnosis diagnosis;  // ran = false until measure() runs it
};

// The comparison of `scene` with the MuJoCo engine `spec` (kind "mujoco";
// its mapping, geometry, model_dt and source as `contact2d compare` takes
// them). Throws InputError before any work when MuJoCo cannot run it.
Comparison prepare_comparison(const Scene& scene, const engines::EngineSpec& spec);

// Runs MuJoCo, then the reference.
void run_engines(Comparison& c);

// A reason the two runs cannot be compared.
struct RunProblem {
  std::string engine;  // "ref" or "MuJoCo"
  bool diverged = false;
  // diverged: the engine's divergence message (EngineRun::divergence_message);
  // else why the run is not physics (nonphysical()).
  std::string message;
};
// Every engine that diverged; when none did, every run that is not physics;
// empty when both can be compared.
std::vector<RunProblem> run_problems(const Comparison& c);

// The three-way comparison at `converged_tol` and, when `diagnosis`, the
// diagnosis of the difference (re-runs of both engines).
void measure(Comparison& c, double converged_tol, bool diagnosis);

// The --json object of a measured comparison, newline-terminated; `scene_label`
// is its "scene" (the scene file as given).
std::string comparison_json(const Comparison& c, const std::string& scene_label);

// Energy of the scene's body at the first and last sample of a run, J.
struct Energies {
  double initial = 0.0;
  double final = 0.0;
};
Energies energies(const Scene& scene, const Trajectory& t);

}  // namespace contact2d::analysis
