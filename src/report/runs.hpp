// The seam between the report and the engines: EVERY call that runs an
// engine or an analysis for `contact2d report` is in runs.cpp, and each
// returns the report's plain structs (report/results.hpp) or the analysis
// tables a page reads as they are (closed forms, friction, atlas). The page
// writers never see an engine type, so pointing the report at another
// engine API means changing runs.cpp alone. The plan (report/plan.hpp)
// says which of these run, on which scenes.
//
// runs.cpp and plan.cpp are the library contact2d_report_runs (CMake),
// beside the page library contact2d_report, which runs nothing: the same
// engine, analysis and game libraries the CLI subcommands call.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "analysis/atlas.hpp"
#include "analysis/closed_forms.hpp"
#include "analysis/comparison.hpp"
#include "analysis/friction_table.hpp"
#include "analysis/version_table.hpp"
#include "core/run.hpp"
#include "core/scene.hpp"
#include "report/pages.hpp"
#include "report/random_scenes.hpp"
#include "report/results.hpp"

namespace contact2d::report {

// Whether this contact2d was built with MuJoCo.
bool mujoco_built();
// Why MuJoCo 3.14 cannot run here (Node or its package missing); empty
// when it can.
std::string mujoco3_missing();

// `contact2d compare`: the scene on the reference and on MuJoCo under a
// mapping and geometry ("calibrated", "corners", …), errors at the shared
// samples; draws the comparison PNG when `plot_png` is not empty. `source`
// names the scene in the MJCF and in messages. Throws std::runtime_error
// when either engine diverges, InputError for a scene MuJoCo cannot take.
ComparisonRow compare_engines(const Scene& scene, const std::string& source,
                              const std::string& mapping, const std::string& geometry,
                              const std::string& plot_png = "");

// compare_engines on MuJoCo 2.2.2 and on 3.14 (`--engine mujoco3`: the
// model written for MuJoCo 3, the same mapping and geometry), the
// reference run once: each version's row, and the largest distance between
// the versions' positions (m).
struct VersionsComparison {
  ComparisonRow v2, v3;
  double apart = 0.0;
};
VersionsComparison compare_versions(const Scene& scene, const std::string& source,
                                    const std::string& mapping, const std::string& geometry,
                                    const std::string& plot_png = "");

// `contact2d compare SCENE` under the calibrated mapping: three-way
// distances at `tol` and the diagnosis (analysis/comparison.hpp), on this
// thread. With `keep`, what it ran is kept there for its animation.
struct ThreeWayRuns {
  Scene scene;
  Trajectory reference, mujoco, mujoco3;  // mujoco3: empty when it did not run
  DenseTrajectory converged;
  bool converged_available = false;
};
// With `mujoco3`, MuJoCo 3.14 too (its distances in the case's *_v3).
ThreeWayCase compare_three_way(const Scene& scene, const std::string& source,
                               const std::string& law, double tol, ThreeWayRuns* keep = nullptr,
                               bool mujoco3 = false);

// `contact2d compare SCENE --video VIDEO`: the case's animation drawn into
// `video` and named in `c.animation`; when it cannot be drawn (no window
// built, no offscreen context), returns the reason and leaves `animation`
// empty. Run it on the program's main thread (a GLFW window is drawn
// there).
// With `mujoco3`, the reference beside MuJoCo 3.14 instead, named in
// `c.animation_v3`.
std::string animate_three_way(const ThreeWayRuns& runs, const std::string& video, ThreeWayCase& c,
                              bool mujoco3 = false);

// `contact2d play --headless --replay REPLAY` on the reference and on
// MuJoCo (the built-in pitch), where the two balls part, and both
// trajectories drawn into `plot_png`.
ReplayComparison replay_on_both(const std::string& replay_path, const std::string& plot_png);

// `contact2d generate -o PATH`: the scene's MJCF under a mapping.
void write_model(const Scene& scene, const std::string& source, const std::string& mapping,
                 const std::string& path);

// `contact2d sweep` (with --study-csv when `study`).
struct SweepRequest {
  std::vector<std::string> engines{"ref"};
  std::vector<std::string> integrators;  // empty: the analysis default (all four)
  std::vector<double> mujoco_dts;
  std::vector<std::string> mujoco_integrators;
  int repeats = 2;
  bool study = false;
  unsigned threads = 0;  // as analysis::parallel_for (0: one per core)
};
SceneSweep sweep_scene(const Scene& scene, const std::string& name, const SweepRequest& request,
                       const std::string& plot_png);

// `contact2d stability`.
struct StabilityRequest {
  std::vector<std::string> engines{"ref"};
  std::vector<double> ks;  // empty: the analysis default (1e3 … 1e9)
  std::optional<double> zeta;
  unsigned threads = 0;  // as analysis::parallel_for (0: one per core)
};
StabilityMap stability_map(const Scene& scene, const std::string& name,
                           const StabilityRequest& request, const std::string& plot_png);

// `contact2d simulate PATH --engine ENGINE`: its exit status and output.
EngineOutcome simulate_outcome(const std::string& path, const std::string& engine);

// The share of MuJoCo's difference a cause must take away to be named
// (analysis/comparison.hpp), as README.md states it.
double named_share();

// The friction goal's split of MuJoCo's difference under a mapping
// (analysis/friction_table.hpp: friction_parts) into `g`; with `mujoco3`,
// MuJoCo 3.14's rest too.
void add_friction_parts(const Scene& scene, const std::string& mapping, GoalCase& g,
                        bool mujoco3 = false);

// A random scene on both engines without and with friction, under a
// mapping ("calibrated", "compensated"), and its difference with friction
// taken apart; with `v3`, MuJoCo 3.14's case into it (the same reference
// runs; shape and push are the reference's).
RandomCase compare_random_scene(const RandomScene& r, const std::string& mapping,
                                RandomCase* v3 = nullptr);

// Whether the scene's force evaluations start with a sincos: a body that
// turns, with contact points that turn with it.
bool points_turn(const Scene& scene);

// Both engines and the converged solution against the closed forms
// (analysis::closed_form_table), and MuJoCo's friction against the
// reference (analysis::friction_table); `threads` as
// analysis::parallel_for.
analysis::ClosedFormTable closed_form_rows(unsigned threads);
std::vector<analysis::FrictionRow> friction_rows(unsigned threads);
// friction.md's scenes (analysis::friction_scenes), built without running.
std::vector<analysis::FrictionScene> friction_scene_list();
// MuJoCo 3.14 beside 2.2.2 on these scenes (analysis::version_table: one
// Node process per thread that runs a row, kept for the thread's life; its
// not_run says why when MuJoCo 3 cannot run here).
analysis::VersionTable version_rows(const std::vector<analysis::NamedScene>& scenes,
                                    unsigned threads);

// `contact2d atlas SPEC --out OUT_DIR` on every core, then its summary into
// `run`. The summary points into the rows of `run.data` (its worst and
// failed points), so `run` is filled in place and is not copied.
struct AtlasRun {
  analysis::AtlasData data;
  analysis::AtlasSummary summary;
  AtlasRunInfo info;
  AtlasRun() = default;
  AtlasRun(const AtlasRun&) = delete;
  AtlasRun& operator=(const AtlasRun&) = delete;
};
void run_atlas(const std::string& spec_path, const std::string& out_dir, AtlasRun& run);
// Its heat maps, PNG_PREFIX*.png under PLOT_DIR.
void draw_atlas(AtlasRun& run, const std::string& plot_dir, const std::string& png_prefix);

// `contact2d_bench --benchmark_min_time=MIN --benchmark_out=…
// --benchmark_out_format=json`, run as a subprocess from the current
// directory (it reads models/SCENE.calibrated.xml). Throws
// std::runtime_error when it fails.
Bench run_bench(const std::string& executable, const std::string& min_time);

// real_impacts.md: contact2d fit on the recording (one thread, the default
// bootstrap and engines when MuJoCo is built), its three pictures in
// `out_dir` (real_impacts.*.png) and the spin's slope.
RealImpactsData real_impacts_run(const std::string& recording, const std::string& out_dir,
                                 bool mujoco);

}  // namespace contact2d::report
