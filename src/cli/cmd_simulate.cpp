// contact2d simulate SCENE --engine ref|mujoco [--csv FILE] [overrides]
#include <iostream>
#include <memory>

#include "cli/common.hpp"
#include "core/input_error.hpp"
#include "io/csv.hpp"

namespace contact2d::cli {
namespace {

struct SimulateOptions {
  SceneOptions scene;
  std::string engine = "ref";
  std::string csv;
  MujocoOptions mujoco;  // --mapping, --geometry (when built with MuJoCo)
};

engines::EngineRun run_chosen_engine(const SimulateOptions& options, const Scene& scene) {
  if (options.engine == "mujoco")
    return engines::run_engine(options.mujoco.spec(options.scene.path), scene);
  return engines::run_engine(engines::parse_engine(options.engine), scene);
}

void print_summary(const Scene& scene, const std::string& engine, const engines::EngineRun& run) {
  const Model model = make_model(scene);
  const auto& samples = run.trajectory.samples;
  double deepest = 0.0;
  for (const Sample& s : samples) deepest = std::max(deepest, max_penetration(model, s.state.q));
  const State& first = samples.front().state;
  const State& last = samples.back().state;
  std::cout << shape_name(scene.shape) << " [" << engine << ", "
            << integrator_name(scene.sim.integrator) << ", dt = " << format_number(scene.sim.dt)
            << " s, " << format_number(scene.sim.duration) << " s in "
            << format_number(run.seconds * 1e3, 3)
            << " ms]: final x = " << format_number(last.q.x())
            << " m, y = " << format_number(last.q.y())
            << " m, theta = " << format_number(last.q.z())
            << " rad, |v| = " << format_number(last.v.head<2>().norm())
            << " m/s; max sampled penetration " << format_number(deepest) << " m; energy "
            << format_number(energy(model, first)) << " -> " << format_number(energy(model, last))
            << " J\n";
}

int simulate(const SimulateOptions& options) {
  const Scene scene = options.scene.load();
  // Open the output first: a bad path fails before any work, and the file
  // only appears (renamed from a temporary) once the run has succeeded.
  std::unique_ptr<AtomicFile> out;
  if (!options.csv.empty()) out = std::make_unique<AtomicFile>(options.csv);
  const engines::EngineRun run = run_chosen_engine(options, scene);
  for (const std::string& warning : run.warnings) {
    std::cerr << "contact2d: " << options.engine << " warning: " << warning << "\n";
  }
  if (run.trajectory.divergence) {
    std::cerr << "contact2d: " << options.scene.path << ": "
              << describe(*run.trajectory.divergence, scene) << "\n";
    return kExitDiverged;
  }
  if (out) {
    std::fprintf(out->get(), "%s\n", kTrajectoryHeader);
    for (const Sample& s : run.trajectory.samples) write_trajectory_row(out->get(), s);
    out->commit();
  }
  print_summary(scene, options.engine, run);
  return kExitOk;
}

}  // namespace

Command add_simulate(CLI::App& app) {
  auto options = std::make_shared<SimulateOptions>();
  CLI::App* cmd =
      app.add_subcommand("simulate", "Run one engine on a scene and write its trajectory");
  options->scene.add_to(*cmd);
  cmd->add_option("--engine", options->engine, "ref | mujoco")
      ->check(CLI::IsMember({"ref", "mujoco"}));
  cmd->add_option("--csv", options->csv,
                  "Write the trajectory (t,x,y,theta,vx,vy,omega) to this file");
  if (engines::mujoco_available()) options->mujoco.add_to(*cmd);
  return {cmd, [options] { return simulate(*options); }};
}

}  // namespace contact2d::cli
