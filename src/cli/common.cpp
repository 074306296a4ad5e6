#include "cli/common.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "io/scene_file.hpp"

namespace contact2d::cli {

namespace {

// The text of a numeric option, checked to be one number ("inf" and "nan"
// pass here and are refused, with their range, by the scene's validation).
std::string number_option(const char* name, const std::string& text, const char* what) {
  char* end = nullptr;
  std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size()) {
    throw InputError(std::string(name) + " = " + text + " is not a number: expected " + what);
  }
  return text;
}

}  // namespace

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
  if (dt) overrides.push_back({"sim.dt", number_option("--dt", *dt, "a time step in s")});
  if (duration) {
    overrides.push_back({"sim.duration", number_option("--duration", *duration, "a time in s")});
  }
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
