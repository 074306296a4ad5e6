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
#include "analysis/friction_table.hpp"
#include "analysis/version_table.hpp"
#include "core/scene.hpp"
#include "report/pages.hpp"
#include "report/random_scenes.hpp"
#include "report/results.hpp"

namespace contact2d::report {

// Whether this contact2d was built with MuJoCo.
bool mujoco_built();

// `contact2d compare`: the scene on the reference and on MuJoCo under a
// mapping and geometry ("calibrated", "corners", …), errors at the shared
// samples; draws the comparison PNG when `plot_png` is not empty. `source`
// names the scene in the MJCF and in messages. Throws std::runtime_error
// when either engine diverges, InputError for a scene MuJoCo cannot take.
Comparison compare_engines(const Scene& scene, const std::string& source,
                           const std::string& mapping, const std::string& geometry,
                           const std::string& plot_png = "");

// `contact2d compare SCENE [--video VIDEO]` under the calibrated mapping:
// three-way distances at `tol` and the diagnosis (analysis/comparison.hpp).
// With `video` not empty, draws the animation there; when it cannot
// (no window built, no offscreen context), leaves `animation` empty and
// puts the reason into `video_failure`.
ThreeWayCase compare_three_way(const Scene& scene, const std::string& source,
                               const std::string& law, double tol, const std::string& video,
                               std::string& video_failure);

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
};
SceneSweep sweep_scene(const Scene& scene, const std::string& name, const SweepRequest& request,
                       const std::string& plot_png);

// `contact2d stability`.
struct StabilityRequest {
  std::vector<std::string> engines{"ref"};
  std::vector<double> ks;  // empty: the analysis default (1e3 … 1e9)
  std::optional<double> zeta;
};
StabilityMap stability_map(const Scene& scene, const std::string& name,
                           const StabilityRequest& request, const std::string& plot_png);

// `contact2d simulate PATH --engine ENGINE`: its exit status and output.
EngineOutcome simulate_outcome(const std::string& path, const std::string& engine);

// The share of MuJoCo's difference a cause must take away to be named
// (analysis/comparison.hpp), as README.md states it.
double named_share();

// The friction goal's split of MuJoCo's difference under a mapping
// (analysis/friction_table.hpp: friction_parts) into `g`.
void add_friction_parts(const Scene& scene, const std::string& mapping, GoalCase& g);

// The random scenes on both engines without and with friction, under the
// calibrated (`calibrated[i]`) and the compensated (`compensated[i]`)
// mapping, two runs at a time (one per core; their run times are not shown).
void compare_random_scenes(const std::vector<RandomScene>& scenes,
                           std::vector<RandomCase>& calibrated,
                           std::vector<RandomCase>& compensated);

// Whether the scene's force evaluations start with a sincos: a body that
// turns, with contact points that turn with it.
bool points_turn(const Scene& scene);

// Both engines and the converged solution against the closed forms
// (analysis::closed_form_table), and MuJoCo's friction against the
// reference (analysis::friction_table).
analysis::ClosedFormTable closed_form_rows();
std::vector<analysis::FrictionRow> friction_rows();
// MuJoCo 3.14 beside 2.2.2 on these scenes (analysis::version_table; its
// not_run says why when MuJoCo 3 cannot run here).
analysis::VersionTable version_rows(const std::vector<analysis::NamedScene>& scenes);

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

}  // namespace contact2d::report
