// The seam between the report and the engines: EVERY call that runs an
// engine or an analysis for `contact2d report` is in runs.cpp, and each
// returns the report's plain structs (report/results.hpp). The page writers
// never see an engine type, so pointing the report at another engine API
// means changing runs.cpp alone.
//
// runs.cpp is compiled into the contact2d program (not the contact2d_report
// library): it calls the same functions the CLI subcommands call, several of
// which live in src/cli (the MuJoCo runner, the comparison plot, the
// analysis runner of sweep and stability).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/scene.hpp"
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

// `contact2d_bench --benchmark_min_time=MIN --benchmark_out=…
// --benchmark_out_format=json`, run as a subprocess from the current
// directory (it reads models/SCENE.calibrated.xml). Throws
// std::runtime_error when it fails.
Bench run_bench(const std::string& executable, const std::string& min_time);

}  // namespace contact2d::report
