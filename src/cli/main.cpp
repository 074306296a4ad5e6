// contact2d: the command-line program. A thin layer over the library: every
// subcommand parses its arguments, loads a scene, calls the library and prints
// or writes the result.  Exit status: 0 success, 2 bad input, 3 diverged.
#include <algorithm>
#include <iostream>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include "cli/common.hpp"
#include "cli/version.hpp"
#include "core/input_error.hpp"
#include "io/interrupt.hpp"

namespace contact2d::cli {
namespace {

// The top-level help lists the subcommands under "Subcommands:" (where
// tests/docs reads them), each group under its heading in the order of its
// first subcommand, the subcommands in the order they were added. (CLI11's
// own formatter prints each group's heading in place of "Subcommands:".)
class GroupedSubcommandsHelp : public CLI::Formatter {
 public:
  std::string make_subcommands(const CLI::App* app, CLI::AppFormatMode mode) const override {
    if (mode == CLI::AppFormatMode::All) return CLI::Formatter::make_subcommands(app, mode);
    const std::vector<const CLI::App*> subs = app->get_subcommands({});
    std::vector<std::string> groups;
    for (const CLI::App* sub : subs) {
      if (std::find(groups.begin(), groups.end(), sub->get_group()) == groups.end())
        groups.push_back(sub->get_group());
    }
    std::string out = "\nSubcommands:\n";
    for (const std::string& group : groups) {
      out += "\n" + group + ":\n";
      for (const CLI::App* sub : subs) {
        if (sub->get_group() == group) out += make_subcommand(sub);
      }
    }
    return out;
  }
};

}  // namespace
}  // namespace contact2d::cli

int main(int argc, char** argv) {
  using namespace contact2d::cli;
  // SIGINT, SIGTERM, SIGHUP: remove unfinished output files, exit 130/143/129.
  contact2d::install_interrupt_cleanup();
  CLI::App app{
      "contact2d: a 2D rigid-body penalty-contact reference solver, cross-validated against MuJoCo "
      "2.2"};
  app.set_version_flag("--version", version_text(),
                       "Print the version and git revision of this contact2d and exit");
  app.require_subcommand(1);

  // In the order users come for them, under headings (CLI11 lists the
  // groups in the order of their first subcommand): comparing the engines,
  // then your own model, fitting to measurements, running a scene, studies,
  // the game last. Without MuJoCo its subcommands are left out.
  std::vector<Command> commands;
  const auto add = [&commands](std::optional<Command> command, const char* group) {
    if (!command) return;
    command->app->group(group);
    commands.push_back(*command);
  };
  const char* const compare = "Compare the reference with MuJoCo";
  const char* const own = "Your own MuJoCo model";
  add(add_mujoco_command(app, "compare"), compare);
  add(add_mujoco_command(app, "report"), compare);
  add(add_mujoco_command(app, "solref"), own);
  add(add_mujoco_command(app, "inspect"), own);
  add(add_fit(app), "Contact parameters from measurements");
  const char* const run = "Run and export a scene";
  add(add_simulate(app), run);
  add(add_mujoco_command(app, "generate"), run);
  const char* const studies = "Step size, stability and fidelity studies";
  add(add_sweep(app), studies);
  add(add_stability(app), studies);
  add(add_mujoco_command(app, "atlas"), studies);
  add(add_play(app), "The game");
  // Set after the subcommands are added: they keep CLI11's own (a
  // subcommand takes its parent's formatter when it is created).
  app.formatter(std::make_shared<GroupedSubcommandsHelp>());

  // An unknown subcommand is named (CLI11 would say "A subcommand is
  // required", as if none had been given).
  if (argc > 1 && argv[1][0] != '-') {
    const std::string first = argv[1];
    std::string names;
    bool known = false;
    for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
      known = known || sub->get_name() == first;
      names += (names.empty() ? "" : ", ") + sub->get_name();
    }
    if (!known) {
      std::cerr << "contact2d: " << first << ": unknown subcommand (one of " << names
                << "; see contact2d --help)\n";
      return kExitBadInput;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    // (An unknown subcommand was named above, before parsing.)
    std::cerr << "contact2d: " << e.what() << " (see contact2d --help)\n";
    return kExitBadInput;
  }
  try {
    for (const Command& command : commands) {
      if (*command.app) return command.action();
    }
  } catch (const contact2d::InputError& e) {
    std::cerr << "contact2d: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const contact2d::EngineError& e) {
    std::cerr << "contact2d: " << e.what() << "\n";
    return kExitDiverged;
  } catch (const std::bad_alloc&) {
    std::cerr
        << "contact2d: out of memory (a run of this length and output_dt needs more than "
           "this machine has: a longer output_dt or a shorter duration keeps fewer samples)\n";
    return kExitDiverged;
  } catch (const std::exception& e) {  // a run failed for a reason outside its input
    std::string what = e.what();
    for (char& ch : what)
      if (ch == '\n') ch = ' ';
    std::cerr << "contact2d: " << what << "\n";
    return kExitDiverged;
  }
  return kExitOk;
}
