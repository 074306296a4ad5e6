// contact2d: the command-line program. A thin layer over the library: every
// subcommand parses its arguments, loads a scene, calls the library and prints
// or writes the result.  Exit status: 0 success, 2 bad input, 3 diverged.
#include <iostream>
#include <new>
#include <string>
#include <vector>

#include "cli/common.hpp"
#include "cli/version.hpp"
#include "core/input_error.hpp"
#include "io/interrupt.hpp"

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

  std::vector<Command> commands = {add_simulate(app), add_play(app)};
  for (Command& c : add_mujoco_commands(app)) commands.push_back(c);  // generate, compare, report
  commands.push_back(add_sweep(app));
  commands.push_back(add_stability(app));
  commands.push_back(add_fit(app));

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
