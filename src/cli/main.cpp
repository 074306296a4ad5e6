// contact2d: the command-line program. A thin layer: parse arguments, load a
// scene, call the library, print or write the result.
//   exit 0 success, 2 bad input, 3 the simulation diverged
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "core/simulate.hpp"
#include "io/csv.hpp"
#include "io/scene_file.hpp"

namespace {

using namespace contact2d;

constexpr int kExitBadInput = 2;
constexpr int kExitDiverged = 3;

// Options shared by every subcommand that runs a scene.
struct SceneOptions {
  std::string path;
  std::string integrator;
  std::optional<double> dt;
  std::optional<double> duration;
  std::vector<std::string> sets;

  void add_to(CLI::App& cmd) {
    cmd.add_option("scene", path, "Scene file (TOML)")->required();
    cmd.add_option("--integrator", integrator,
                   "explicit_euler | semi_implicit_euler | implicit_euler | rk4");
    cmd.add_option("--dt", dt, "Time step, s (overrides sim.dt)");
    cmd.add_option("--duration", duration, "Simulated time, s (overrides sim.duration)");
    cmd.add_option("--set", sets, "Override any scene key, e.g. --set contact.k=1e6 (repeatable)");
  }

  Scene load() const {
    std::vector<Override> overrides;
    for (const std::string& s : sets) overrides.push_back(parse_override(s));
    if (!integrator.empty()) overrides.push_back({"sim.integrator", "\"" + integrator + "\""});
    if (dt) overrides.push_back({"sim.dt", std::to_string(*dt)});
    if (duration) overrides.push_back({"sim.duration", std::to_string(*duration)});
    return load_scene(path, overrides);
  }
};

std::string format_number(double v) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

int run_simulate(const SceneOptions& options, const std::string& engine, const std::string& csv) {
  if (engine != "ref") {
    std::cerr << "contact2d: --engine " << engine
              << ": not yet available (only 'ref' is implemented so far)\n";
    return kExitBadInput;
  }
  const Scene scene = options.load();
  std::optional<AtomicFile> out;
  if (!csv.empty()) {
    out.emplace(csv);
    std::fprintf(out->get(), "%s\n", kTrajectoryHeader);
  }
  const Model model = make_model(scene);
  const State initial = initial_state(scene);
  Sample last{0.0, initial};
  double deepest = 0.0;
  const auto start = std::chrono::steady_clock::now();
  const RunResult result = run(scene, [&](const Sample& s) {
    if (out) write_trajectory_row(out->get(), s);
    deepest = std::max(deepest, max_penetration(model, s.state.q));
    last = s;
  });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (result.divergence) {
    std::cerr << "contact2d: " << options.path << ": " << describe(*result.divergence, scene) << "\n";
    return kExitDiverged;  // `out` is destroyed uncommitted: no file is left
  }
  if (out) out->commit();
  std::cout << shape_name(scene.shape) << " (" << integrator_name(scene.sim.integrator)
            << ", dt = " << format_number(scene.sim.dt) << " s, " << result.steps << " steps in "
            << format_number(seconds * 1e3) << " ms): final x = " << format_number(last.state.q.x())
            << " m, y = " << format_number(last.state.q.y())
            << " m, theta = " << format_number(last.state.q.z())
            << " rad, |v| = " << format_number(last.state.v.head<2>().norm())
            << " m/s; max sampled penetration " << format_number(deepest)
            << " m; energy " << format_number(energy(model, initial)) << " -> "
            << format_number(energy(model, last.state)) << " J\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"contact2d: a 2D rigid-body penalty-contact reference solver, cross-validated against MuJoCo"};
  app.require_subcommand(1);

  SceneOptions simulate_options;
  std::string engine = "ref";
  std::string csv;
  CLI::App* simulate = app.add_subcommand("simulate", "Run one engine on a scene and write its trajectory");
  simulate_options.add_to(*simulate);
  simulate->add_option("--engine", engine, "ref | mujoco")->check(CLI::IsMember({"ref", "mujoco"}));
  simulate->add_option("--csv", csv, "Write the trajectory (t,x,y,theta,vx,vy,omega) to this file");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kExitBadInput;
  }
  try {
    if (*simulate) return run_simulate(simulate_options, engine, csv);
  } catch (const InputError& e) {
    std::cerr << "contact2d: " << e.what() << "\n";
    return kExitBadInput;
  }
  return 0;
}
