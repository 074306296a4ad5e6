// Pieces shared by the contact2d subcommands.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/simulate.hpp"

namespace contact2d::cli {

constexpr int kExitOk = 0;
constexpr int kExitBadInput = 2;
constexpr int kExitDiverged = 3;

// The scene argument and the overrides every scene-running command accepts.
struct SceneOptions {
  std::string path;
  std::string integrator;
  // Kept as text and applied as overrides of sim.dt / sim.duration, so a bad
  // value gets the scene reader's message (key, type, allowed range).
  std::optional<std::string> dt;
  std::optional<std::string> duration;
  std::vector<std::string> sets;

  void add_to(CLI::App& cmd);
  Scene load() const;  // throws InputError
};

std::string format_number(double v, int digits = 6);

// A run of one engine: the sampled trajectory, wall-clock time of the
// stepping alone, and anything the engine warned about.
struct EngineRun {
  Trajectory trajectory;
  double seconds = 0.0;
  std::vector<std::string> warnings;
};

EngineRun run_reference(const Scene& scene);

// A subcommand: adds itself to the app and returns the action to run if it
// was chosen. The action returns the exit status.
using Action = std::function<int()>;
struct Command {
  CLI::App* app = nullptr;
  Action action;
};

Command add_simulate(CLI::App& app);
Command add_play(CLI::App& app);       // the game (src/game)
Command add_generate(CLI::App& app);   // built with MuJoCo only
Command add_compare(CLI::App& app);    // built with MuJoCo only
Command add_sweep(CLI::App& app);      // error against run time (src/cli/cmd_sweep.cpp)
Command add_stability(CLI::App& app);  // stability map (src/cli/cmd_stability.cpp)
Command add_report(CLI::App& app);     // validation/report/ (src/cli/cmd_report.cpp; with MuJoCo)

}  // namespace contact2d::cli
