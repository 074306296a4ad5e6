// Pieces shared by the contact2d subcommands.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/format.hpp"
#include "core/run.hpp"
#include "engines/engines.hpp"
#include "io/exit_status.hpp"

namespace contact2d::cli {

// The exit status, shared with the layers below (io/exit_status.hpp).
using contact2d::kExitBadInput;
using contact2d::kExitDiverged;
using contact2d::kExitOk;

// The output options of a subcommand (--csv FILE, --plot FILE.png, --out
// DIR, …), all checked by check() before the run starts: a path that cannot
// be written is one line naming its option, exit status 2, and nothing is
// written. An option given with an empty value is such a path.
class OutputOptions {
 public:
  // `names` as for CLI11 ("-o,--output"); messages use the last name.
  CLI::Option* file(CLI::App& cmd, const std::string& names, std::string& path,
                    const std::string& help, const std::string& type_name);
  CLI::Option* directory(CLI::App& cmd, const std::string& names, std::string& path,
                         const std::string& help);
  // An input the outputs must not overwrite (the scene file, a pitch, a
  // replay): check() refuses an output that is the same file.
  void input(const std::string& name, const std::string& path);
  void check() const;  // throws InputError

 private:
  struct Entry {
    CLI::Option* option;
    const std::string* path;
    std::string name;
    bool directory;
  };
  std::vector<Entry> entries_;
  std::vector<std::pair<std::string, const std::string*>> inputs_;
};

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

// A finished run that is not physics (core/run.hpp: nonphysical()) fails with
// exit status 3, as a diverged one does, unless --allow-nonphysical keeps it;
// the reason is then a warning. One line on stderr either way, naming
// `source` (the scene file) and `engine` (empty: none).
void add_allow_nonphysical(CLI::App& cmd, bool& allow);
// True when the run must fail (the line is printed).
bool reject_nonphysical(const std::string& reason, bool allow, const std::string& source,
                        const std::string& engine);

// The options sweep and stability share: the scene with --set and
// --duration, --integrators, --engines, --csv, --plot, --threads, --quiet.
struct AnalysisOptions {
  std::string path;
  std::vector<std::string> sets;
  std::optional<double> duration;
  std::vector<std::string> integrators;
  std::vector<std::string> engines{"ref"};
  std::string csv, plot;
  unsigned threads = 0;
  bool quiet = false;
  OutputOptions outputs;  // --csv and --plot, and any the subcommand adds

  void add_to(CLI::App& cmd, const std::string& csv_help, const std::string& plot_help);
  Scene load() const;  // throws InputError
};

// sweep and stability: progress on stderr with an estimate of the time left,
// rewritten in place on a terminal; otherwise one line every 5 s
// (CONTACT2D_PROGRESS_SECONDS overrides the interval) and a last "done in"
// line if any was printed. --quiet: an empty function.
std::function<void(size_t, size_t, const std::string&)> progress_reporter(const std::string& label,
                                                                          bool quiet);
// The scene with --set overrides and an optional --duration.
Scene load_scene_with(const std::string& path, const std::vector<std::string>& sets,
                      const std::optional<double>& duration);

// A CLI11 check of a number in [lo, hi] ((lo, hi] when `lo_open`) whose
// message reads "VALUE is out of range: must be in RANGE", with the range as
// written (CLI11's Range prints 1e-15 as 0.000000).
CLI::Validator number_in(double lo, double hi, bool lo_open, const std::string& range);

// How the command line spells an option, to start an error: "model_dt" →
// "--model-dt".
std::string flag_spelling(std::string_view name);

// The engines' own options, one flag each, made from the registry's data
// (EngineInfo::options: MuJoCo's --mapping and --geometry) and --model-dt
// when an engine has Δt-dependent model values; only engines built in
// offer theirs. An option name two engines share is one flag, checked
// against the first one's values. Empty means the option's fallback.
struct EngineOptions {
  std::map<std::string, std::string, std::less<>> values;  // by option name
  double model_dt = 0.0;                                   // --model-dt; 0: the timestep

  void add_to(CLI::App& cmd);
  // The engine `kind` with these options; `source` is the scene file.
  // Throws InputError when a flag given is not an option of `kind`.
  engines::EngineSpec spec(const std::string& kind, const std::string& source) const;
  // The value given for an option ("" when left out).
  std::string value(std::string_view name) const;
};

// --engine NAME of one engine kind from the registry (engines::engine_kinds):
// the choices checked and listed in the help as "ref | mujoco" before `help`.
CLI::Option* add_engine_kind_option(CLI::App& cmd, std::string& engine, const std::string& help);

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
Command add_fit(CLI::App& app);        // contact parameters from real impacts (src/cli/cmd_fit.cpp)
Command add_report(CLI::App& app);     // validation/report/ (src/cli/cmd_report.cpp; with MuJoCo)
Command add_solref(CLI::App& app);     // MuJoCo numbers for your own model (cmd_solref.cpp; MuJoCo)
Command add_atlas(CLI::App& app);  // fidelity atlas over a parameter space (cmd_atlas.cpp; MuJoCo)
Command add_inspect(CLI::App& app);  // any MJCF model's contacts (cmd_inspect.cpp; MuJoCo)
// A subcommand that needs MuJoCo, by name (compare, report, solref, inspect,
// generate, atlas): added when built with MuJoCo, nullopt otherwise
// (src/cli/mujoco_commands.cpp or no_mujoco_commands.cpp, chosen by CMake),
// so main.cpp lists every subcommand in its place without an #ifdef.
std::optional<Command> add_mujoco_command(CLI::App& app, std::string_view name);

}  // namespace contact2d::cli
