// contact2d simulate SCENE --engine ref|mujoco [--csv FILE] [overrides]
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "analysis/tables.hpp"
#include "cli/common.hpp"
#include "core/input_error.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"

namespace contact2d::cli {
namespace {

struct SimulateOptions {
  SceneOptions scene;
  std::string engine = "ref";
  std::string csv;
  EngineOptions engine_options;  // --mapping, --geometry, …: the engines' own
  OutputOptions outputs;         // --csv
  bool allow_nonphysical = false;
};

engines::EngineRun run_chosen_engine(const SimulateOptions& options, const Scene& scene) {
  return engines::run_engine(options.engine_options.spec(options.engine, options.scene.path),
                             scene);
}

int simulate(const SimulateOptions& options) {
  options.outputs.check();
  const Scene scene = options.scene.load();
  // Open the output first: a bad path fails before any work, and the file
  // only appears (renamed from a temporary) once the run has succeeded.
  std::unique_ptr<AtomicFile> out;
  if (!options.csv.empty()) out = std::make_unique<AtomicFile>(options.csv);
  const engines::EngineRun run = run_chosen_engine(options, scene);
  // A run that fails says so in one line (its message names the cause); the
  // engine's warnings come with a run that stands.
  if (run.trajectory.divergence) {
    std::cerr << "contact2d: " << options.scene.path << ": " << run.divergence_message << "\n";
    return kExitDiverged;
  }
  if (reject_nonphysical(nonphysical(run.trajectory, scene), options.allow_nonphysical,
                         options.scene.path, ""))
    return kExitDiverged;
  for (const std::string& warning : run.warnings) {
    std::cerr << "contact2d: " << options.engine << " warning: " << warning << "\n";
  }
  if (out) {
    std::fprintf(out->get(), "%s\n", kTrajectoryHeader);
    for (const Sample& s : run.trajectory.samples) write_trajectory_row(out->get(), s);
    out->commit();
  }
  std::cout << analysis::run_summary(scene, options.engine, run) << "\n";
  return kExitOk;
}

}  // namespace

Command add_simulate(CLI::App& app) {
  auto options = std::make_shared<SimulateOptions>();
  CLI::App* cmd =
      app.add_subcommand("simulate", "Run one engine on a scene and write its trajectory");
  options->scene.add_to(*cmd);
  options->outputs.input("scene file", options->scene.path);
  add_engine_kind_option(*cmd, options->engine, "");
  options->outputs.file(*cmd, "--csv", options->csv,
                        "Write the trajectory (t,x,y,theta,vx,vy,omega) to this file", "FILE.csv");
  add_allow_nonphysical(*cmd, options->allow_nonphysical);
  options->engine_options.add_to(*cmd);
  return {cmd, [options] { return simulate(*options); }};
}

}  // namespace contact2d::cli
