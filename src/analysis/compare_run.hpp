// One `contact2d compare` run as a library call, shared by the program and
// the Python module (src/python): the reference and any number of engines
// on one scene, each measured against the converged solution and against
// the first run, the diagnosis of the first two, and the --json text of
// the result.
//
// The run is cut where a caller has to act between its stages, so that the
// program keeps its order of checks and messages (bad input before any
// work, a divergence before any measurement):
//
//   prepare_comparison   the scene and the engines; throws InputError for an
//                        engine that cannot run the scene (EngineInfo::check:
//                        MuJoCo has no explicit Euler) — no engine has run
//   run_engines          every engine, each timed (and the diagnosis's early
//                        MuJoCo runs beside them, when it will be asked for)
//   run_problems         why the runs cannot be compared: every engine that
//                        diverged, else every run that is not physics
//                        (core/run.hpp: nonphysical())
//   measure              the distances and, unless skipped, the diagnosis of
//                        the reference and the first engine with soft
//                        constraints (analysis/comparison.hpp)
//   comparison_json      the one JSON object `compare --json` prints
//
// What the run measures and why is in analysis/comparison.hpp; this file
// only sequences it.
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "analysis/comparison.hpp"
#include "analysis/trajectory_error.hpp"
#include "core/scene.hpp"
#include "engines/engines.hpp"

namespace contact2d::analysis {

// One engine's run in a comparison.
struct ComparedRun {
  engines::EngineSpec spec;
  // Its name in tables ("ref", "MuJoCo": EngineInfo::title; the full name,
  // "mujoco:exact", when two runs share a title) and in keys and CSV
  // columns ("ref", "mujoco"; "mujoco_exact" when two share a kind).
  std::string label;
  std::string key;
  engines::EngineRun run;
  TrajectoryError vs_converged;  // zero when the converged solution is not available
  TrajectoryError vs_first;      // runs[0] ↔ this run; zero for runs[0]
};

struct Comparison {
  Scene scene;
  // runs[0] is the one every other is measured against: `compare` puts the
  // reference first, then the engines asked for in their order.
  std::vector<ComparedRun> runs;
  ConvergedSolution converged;
  // Of runs[0] ↔ runs[diagnosed], the first engine after the reference with
  // soft constraints (EngineInfo::soft_constraints; 0: none of them has):
  // ran = false until measure() runs it, and when no engine has them.
  Diagnosis diagnosis;
  size_t diagnosed = 0;
  // The diagnosis's MuJoCo runs made beside the base runs, by cause
  // (run_engines with early_diagnosis).
  std::vector<std::pair<std::string, EngineRun>> early;
};

// The engines of `contact2d compare`: the reference first, then `names`
// (--engines: each name with its options), or when `names` is empty every
// engine built in but the reference, each with the `given` options it
// takes (--mapping, --geometry). `model_dt` goes to every engine with
// Δt-dependent model values; `source` is the scene file; `spelled` says
// how the caller's user writes an option, for errors. Throws InputError
// for an unknown engine or option, `given` options together with names, or
// one engine named twice (the reference included: it is always first).
std::vector<engines::EngineSpec> comparison_engines(
    const std::vector<std::string>& names, const engines::OptionValues& given, double model_dt,
    const std::string& source, const std::function<std::string(std::string_view)>& spelled);

// The comparison of `scene` on `specs` (at least two; their options and
// source as `contact2d compare` takes them). Throws InputError before any
// work when an engine cannot run the scene.
Comparison prepare_comparison(const Scene& scene, const std::vector<engines::EngineSpec>& specs);

// Runs every engine. With `early_diagnosis` (compare without
// --no-diagnosis), the diagnosis's first-tier MuJoCo runs that depend on
// the scene and the engine alone (early_reruns) are made beside them,
// on `threads` threads (0: analysis::default_threads()), into
// Comparison::early, for measure() to use.
void run_engines(Comparison& c, bool early_diagnosis = false, unsigned threads = 0);

// A reason the runs cannot be compared.
struct RunProblem {
  std::string engine;  // ComparedRun::label ("ref", "MuJoCo")
  bool diverged = false;
  // diverged: the engine's divergence message (EngineRun::divergence_message);
  // else why the run is not physics (nonphysical()).
  std::string message;
};
// Every engine that diverged; when none did, every run that is not physics;
// empty when all can be compared.
std::vector<RunProblem> run_problems(const Comparison& c);

// The distances at `converged_tol` and, when `diagnosis`, the diagnosis of
// runs[0] ↔ runs[diagnosed] (re-runs of both engines); when no engine has
// soft constraints, a summary that says why there is none. `options`: how
// far the diagnosis goes (analysis/comparison.hpp).
void measure(Comparison& c, double converged_tol, bool diagnosis,
             const DiagnosisOptions& options = {});

// runs[0] ↔ runs[i] with the converged solution, as the diagnosis takes it.
ThreeWay pair(const Comparison& c, size_t i);

// The text `contact2d compare` prints of a measured comparison: the
// three-way table, energies, wall clocks, the versions and the diagnosis,
// wrapped at 78 columns (analysis/compare_text.cpp). Like comparison_json,
// formatted here, in the layer that measured it, for every caller.
std::string comparison_text(const Comparison& c);

// "mapping calibrated, geometry corners" (`name_first`) or "calibrated
// mapping" (the first option only): the run's engine options, given or
// their fallbacks; empty for an engine without options.
std::string run_options_text(const ComparedRun& r, bool name_first);

// The --json object of a measured comparison, newline-terminated; `scene_label`
// is its "scene" (the scene file as given).
std::string comparison_json(const Comparison& c, const std::string& scene_label);

// What two runs of one engine in two versions have between them, as
// sentences (analysis/comparison.cpp: MuJoCo 2.2.2 and MuJoCo 3.14 — their
// distance and its named cause); empty when no such pair was compared.
// compare prints them under "Versions"; --json has them as "version_notes".
std::vector<std::string> version_notes(const Comparison& c);

// A contact the reference's model has on an engine's own trajectory and
// the engine's geometry cannot make: an obstacle's corner pressing into the
// body's face, away from its corners, where MuJoCo's corners geometry (a
// sphere at each corner of the body) has no geom, so MuJoCo makes no
// contact and the body passes into the obstacle. One paragraph naming the
// first time, the obstacle, the depth and the geometry that sees it; empty
// when there is none (no obstacle, a body without corners, another
// geometry, no such state). Also, on MuJoCo 2.2.2, a corner sinking into a
// box obstacle: its sphere–box collider gives a sphere whose centre is
// inside the box the depth −radius whatever the true depth
// (engine_collision_box.c), and the corners' spheres (radius 1e-9 m) are
// inside as soon as they touch, so the contact has no spring; named when a
// corner is more than twice as deep in a box obstacle as the reference's
// deepest obstacle contact (`reference`: its trajectory).
std::string missed_obstacle_contact(const Scene& scene, const engines::EngineSpec& spec,
                                    const Trajectory& run, const Trajectory& reference);

// Energy of the scene's body at the first and last sample of a run, J.
struct Energies {
  double initial = 0.0;
  double final = 0.0;
};
Energies energies(const Scene& scene, const Trajectory& t);

}  // namespace contact2d::analysis
