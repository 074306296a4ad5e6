#include "cli/common.hpp"

#include <filesystem>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "io/atomic_file.hpp"
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

namespace {

std::string last_name(const std::string& names) {
  const size_t comma = names.rfind(',');
  return comma == std::string::npos ? names : names.substr(comma + 1);
}

}  // namespace

CLI::Option* OutputOptions::file(CLI::App& cmd, const std::string& names, std::string& path,
                                 const std::string& help, const std::string& type_name) {
  CLI::Option* option = cmd.add_option(names, path, help)->type_name(type_name);
  entries_.push_back({option, &path, last_name(names), false});
  return option;
}

CLI::Option* OutputOptions::directory(CLI::App& cmd, const std::string& names, std::string& path,
                                      const std::string& help) {
  CLI::Option* option = cmd.add_option(names, path, help)->type_name("DIR");
  entries_.push_back({option, &path, last_name(names), true});
  return option;
}

void OutputOptions::input(const std::string& name, const std::string& path) {
  inputs_.emplace_back(name, &path);
}

void OutputOptions::check() const {
  for (const Entry& e : entries_) {
    // Not given and no default: that output is not wanted.
    if (e.option->count() == 0 && e.path->empty()) continue;
    if (e.directory) {
      check_output_directory(e.name, *e.path);
    } else {
      check_output_file(e.name, *e.path);
      for (const auto& [name, input] : inputs_) {
        std::error_code ec;
        if (!input->empty() && std::filesystem::equivalent(*e.path, *input, ec))
          throw InputError(e.name + " " + *e.path + ": is the " + name +
                           " this run reads; name a new file");
      }
    }
  }
}

void SceneOptions::add_to(CLI::App& cmd) {
  cmd.add_option("scene", path, "Scene file (TOML)")->required()->type_name("SCENE.toml");
  cmd.add_option("--integrator", integrator,
                 "explicit_euler | semi_implicit_euler | implicit_euler | rk4 (overrides "
                 "sim.integrator; MuJoCo runs semi_implicit_euler as its Euler, implicit_euler as "
                 "its implicit and rk4 as its RK4)")
      ->type_name("NAME");
  cmd.add_option("--dt", dt, "Time step (overrides sim.dt)")->type_name("SECONDS");
  cmd.add_option("--duration", duration, "Simulated time (overrides sim.duration)")
      ->type_name("SECONDS");
  cmd.add_option("--set", sets, "Override any scene key, e.g. --set contact.k=1e6 (repeatable)")
      ->type_name("KEY=VALUE");
}

Scene SceneOptions::load() const {
  std::vector<Override> overrides;
  overrides.reserve(sets.size() + 3);  // and --integrator, --dt, --duration
  for (const std::string& s : sets) overrides.push_back(parse_override(s));
  if (!integrator.empty())
    overrides.push_back({"sim.integrator", "\"" + integrator + "\"", "--integrator"});
  if (dt) overrides.push_back({"sim.dt", number_option("--dt", *dt, "a time step in s"), "--dt"});
  if (duration) {
    overrides.push_back(
        {"sim.duration", number_option("--duration", *duration, "a time in s"), "--duration"});
  }
  return load_scene(path, overrides);
}

void add_allow_nonphysical(CLI::App& cmd, bool& allow) {
  cmd.add_flag("--allow-nonphysical", allow,
               "Keep a run that is not physics (a contact deeper than the body, the body below "
               "the ground, or an energy rise beyond the integrator's allowance) with a warning, "
               "instead of failing it with exit status 3");
}

bool reject_nonphysical(const std::string& reason, bool allow, const std::string& source,
                        const std::string& engine) {
  if (reason.empty()) return false;
  const std::string who = "contact2d: " + source + ": " + (engine.empty() ? "" : engine + " ");
  if (allow) {
    std::fprintf(stderr, "%swarning: not physics, kept (--allow-nonphysical): %s\n", who.c_str(),
                 reason.c_str());
    return false;
  }
  std::fprintf(stderr, "%snot physics: %s. Pass --allow-nonphysical to keep the run.\n",
               who.c_str(), reason.c_str());
  return true;
}

CLI::Validator number_in(double lo, double hi, bool lo_open, const std::string& range) {
  return CLI::Validator(
      [lo, hi, lo_open, range](std::string& text) {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0') return text + " is not a number in " + range;
        if (!((lo_open ? v > lo : v >= lo) && v <= hi))
          return text + " is out of range: must be in " + range;
        return std::string();
      },
      range);
}

void EngineOptions::add_to(CLI::App& cmd) {
  const engines::EngineInfo* with_model_dt = nullptr;
  for (const engines::EngineInfo* info : engines::engine_list()) {
    if (info->make == nullptr) continue;
    if (with_model_dt == nullptr && !info->model_dt_help.empty()) with_model_dt = info;
    for (const engines::EngineOption& option : info->options) {
      const std::string name(option.name);
      if (values.count(name) > 0) continue;
      std::vector<std::string> allowed(option.values.begin(), option.values.end());
      std::string listed;
      for (const std::string& v : allowed) listed += (listed.empty() ? "" : " | ") + v;
      cmd.add_option("--" + name, values[name],
                     std::string(option.what) + ": " + listed + " (default " +
                         std::string(option.fallback) + ")")
          ->type_name("NAME")
          ->check(CLI::IsMember(allowed));
    }
  }
  if (with_model_dt != nullptr) {
    cmd.add_option("--model-dt", model_dt, std::string(with_model_dt->model_dt_help))
        ->type_name("SECONDS")
        ->check(number_in(0.0, 1.0, true, "(0, 1] s"));
  }
}

engines::EngineSpec EngineOptions::spec(const std::string& kind, const std::string& source) const {
  const engines::OptionValues given(values.begin(), values.end());
  return engines::engine_with_options(kind, given, model_dt, source, flag_spelling);
}

std::string flag_spelling(std::string_view name) {
  std::string flag = "--" + std::string(name);
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

std::string EngineOptions::value(std::string_view name) const {
  const auto it = values.find(name);
  return it == values.end() ? std::string() : it->second;
}

CLI::Option* add_engine_kind_option(CLI::App& cmd, std::string& engine, const std::string& help) {
  const std::vector<std::string> kinds = engines::engine_kinds();
  std::string text;
  for (const std::string& kind : kinds) text += (text.empty() ? "" : " | ") + kind;
  return cmd.add_option("--engine", engine, text + help)
      ->type_name("ENGINE")
      ->check(CLI::IsMember(kinds));
}

std::function<void(size_t, size_t, const std::string&)> progress_reporter(const std::string& label,
                                                                          bool quiet) {
  if (quiet) return {};
  double every = 5.0;
  // The tests' knob (a line at every run with 0); anything but a number ≥ 0
  // keeps the default.
  if (const char* text = std::getenv("CONTACT2D_PROGRESS_SECONDS")) {
    char* end = nullptr;
    const double seconds = std::strtod(text, &end);
    if (end != text && *end == '\0' && seconds >= 0.0) every = seconds;
  }
  struct State {
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
    double last_line = 0.0;  // seconds since start of the last line (pipes)
    bool printed = false;
  };
  auto state = std::make_shared<State>();
  const bool tty = ::isatty(2) != 0;
  return [label, every, state, tty](size_t done, size_t total, const std::string& what) {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - state->start).count();
    std::string text = label + ": " + std::to_string(done) + "/" + std::to_string(total);
    if (done == total) {
      text += " done in " + format_duration(elapsed);
    } else {
      text += " " + what;
      if (done > 0) {
        const double left = elapsed / static_cast<double>(done) * static_cast<double>(total - done);
        text += ", about " + format_duration(left) + " left";
      }
    }
    if (tty) {
      std::fprintf(stderr, "\r\033[K%s", text.c_str());
      if (done == total) std::fprintf(stderr, "\r\033[K");
    } else {
      // Not a terminal (a log, CI): a line every `every` seconds, and the
      // final one only when earlier lines were printed.
      const bool due = done == total ? state->printed : elapsed - state->last_line >= every;
      if (!due) return;
      std::fprintf(stderr, "%s\n", text.c_str());
      state->last_line = elapsed;
      state->printed = true;
    }
    std::fflush(stderr);
  };
}

Scene load_scene_with(const std::string& path, const std::vector<std::string>& sets,
                      const std::optional<double>& duration) {
  std::vector<Override> overrides;
  overrides.reserve(sets.size() + 1);
  for (const std::string& s : sets) overrides.push_back(parse_override(s));
  if (duration) overrides.push_back({"sim.duration", format_number(*duration, 17), "--duration"});
  return load_scene(path, overrides);
}

void AnalysisOptions::add_to(CLI::App& cmd, const std::string& csv_help,
                             const std::string& plot_help) {
  cmd.add_option("scene", path, "Scene file (TOML)")->required()->type_name("SCENE.toml");
  cmd.add_option("--integrators", integrators,
                 "Comma-separated list (default: explicit_euler,semi_implicit_euler,implicit_euler,"
                 "rk4; MuJoCo runs semi_implicit_euler as its Euler, implicit_euler as its "
                 "implicit and rk4 as its RK4)")
      ->type_name("NAME")
      ->delimiter(',');
  cmd.add_option("--engines", engines,
                 "Comma-separated: " + engines::engine_names_help() + " (default: ref)")
      ->type_name("ENGINE")
      ->delimiter(',')
      ->check(CLI::IsMember(engines::engine_names()));
  outputs.file(cmd, "--csv", csv, csv_help, "FILE.csv");
  outputs.file(cmd, "--plot", plot, plot_help, "FILE.png");
  outputs.input("scene file", path);
  cmd.add_option("--threads", threads, "Worker threads (default: one per core)")
      ->type_name("N")
      ->check(CLI::Range(1u, 256u));
  cmd.add_option("--duration", duration, "Simulated time of each run (overrides sim.duration)")
      ->type_name("SECONDS");
  cmd.add_option("--set", sets, "Override any scene key, e.g. --set contact.k=1e6 (repeatable)")
      ->type_name("KEY=VALUE");
  cmd.add_flag("--quiet", quiet,
               "No progress on stderr (else: the time left, in place on a terminal, a line every "
               "5 s otherwise)");
}

Scene AnalysisOptions::load() const { return load_scene_with(path, sets, duration); }

}  // namespace contact2d::cli
