#include "cli/common.hpp"

#include <unistd.h>
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

void MujocoOptions::add_to(CLI::App& cmd) {
  cmd.add_option("--mapping", mapping,
                 "solref/solimp mapping: seed | exact | calibrated (default calibrated)")
      ->check(CLI::IsMember({"seed", "exact", "calibrated"}));
  cmd.add_option("--geometry", geometry,
                 "MuJoCo geoms of a box or T: corners (a small sphere per 2D contact point, "
                 "default) | boxes")
      ->check(CLI::IsMember({"corners", "boxes"}));
  cmd.add_option("--model-dt", model_dt,
                 "Compute MuJoCo's Δt-dependent values (the calibrated impratio) for this Δt "
                 "instead of the timestep: holds the model fixed while --dt changes")
      ->check(CLI::Validator(
          [](std::string& text) {
            char* end = nullptr;
            const double v = std::strtod(text.c_str(), &end);
            if (end == text.c_str() || *end != '\0' || !(v > 0.0 && v <= 1.0))
              return text + " is out of range: must be in (0, 1] s";
            return std::string();
          },
          "DT in (0, 1] s"));
}

engines::EngineSpec MujocoOptions::spec(const std::string& source) const {
  engines::EngineSpec spec;
  spec.kind = "mujoco";
  spec.mapping = mapping;
  spec.geometry = geometry;
  spec.source = source;
  spec.model_dt = model_dt;
  return spec;
}

// Progress on stderr, rewritten in place, only when stderr is a terminal.
std::function<void(size_t, size_t, const std::string&)> terminal_progress(const std::string& label,
                                                                          bool quiet) {
  if (quiet || !::isatty(2)) return {};
  return [label](size_t done, size_t total, const std::string& what) {
    std::fprintf(stderr, "\r\033[K%s: %zu/%zu %s", label.c_str(), done, total, what.c_str());
    if (done == total) std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
  };
}

Scene load_scene_with(const std::string& path, const std::vector<std::string>& sets,
                      const std::optional<double>& duration) {
  std::vector<Override> overrides;
  overrides.reserve(sets.size() + 1);
  for (const std::string& s : sets) overrides.push_back(parse_override(s));
  if (duration) overrides.push_back({"sim.duration", format_number(*duration, 17)});
  return load_scene(path, overrides);
}

void AnalysisOptions::add_to(CLI::App& cmd, const std::string& csv_help,
                             const std::string& plot_help) {
  cmd.add_option("scene", path, "Scene file (TOML)")->required();
  cmd.add_option(
         "--integrators", integrators,
         "Comma-separated list (default: explicit_euler,semi_implicit_euler,implicit_euler,rk4)")
      ->delimiter(',');
  cmd.add_option("--engines", engines,
                 "Comma-separated: ref, mujoco, mujoco:MAPPING (seed, exact, calibrated; mujoco = "
                 "its default) (default: ref)")
      ->delimiter(',')
      ->check(CLI::IsMember(engines::engine_names()));
  cmd.add_option("--csv", csv, csv_help);
  cmd.add_option("--plot", plot, plot_help);
  cmd.add_option("--threads", threads, "Worker threads (default: one per core)")
      ->check(CLI::Range(1u, 256u));
  cmd.add_option("--duration", duration, "Simulated time of each run, s (overrides sim.duration)");
  cmd.add_option("--set", sets, "Override any scene key, e.g. --set contact.k=1e6 (repeatable)");
  cmd.add_flag("--quiet", quiet, "No progress on stderr");
}

Scene AnalysisOptions::load() const { return load_scene_with(path, sets, duration); }

}  // namespace contact2d::cli
