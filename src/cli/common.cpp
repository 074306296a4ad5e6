#include "cli/common.hpp"

#include <chrono>
#include <cstdio>

#include "io/scene_file.hpp"

namespace contact2d::cli {

void SceneOptions::add_to(CLI::App& cmd) {
  cmd.add_option("scene", path, "Scene file (TOML)")->required();
  cmd.add_option(
      "--integrator", integrator,
      "explicit_euler | semi_implicit_euler | implicit_euler | rk4 (overrides sim.integrator)");
  cmd.add_option("--dt", dt, "Time step, s (overrides sim.dt)");
  cmd.add_option("--duration", duration, "Simulated time, s (overrides sim.duration)");
  cmd.add_option("--set", sets, "Override any scene key, e.g. --set contact.k=1e6 (repeatable)");
}

Scene SceneOptions::load() const {
  std::vector<Override> overrides;
  for (const std::string& s : sets) overrides.push_back(parse_override(s));
  if (!integrator.empty()) overrides.push_back({"sim.integrator", "\"" + integrator + "\""});
  if (dt) overrides.push_back({"sim.dt", format_number(*dt, 17)});
  if (duration) overrides.push_back({"sim.duration", format_number(*duration, 17)});
  return load_scene(path, overrides);
}

std::string format_number(double v, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, v);
  return buffer;  // "%g" output is also a valid TOML number (inf and nan included)
}

EngineRun run_reference(const Scene& scene) {
  EngineRun run;
  const auto start = std::chrono::steady_clock::now();
  run.trajectory = simulate(scene);
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

}  // namespace contact2d::cli
