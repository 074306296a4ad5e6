// The contact2d program on good input: the trajectory CSV format, --help and
// its metavariables, --version, progress on a pipe, and every plot the
// program draws (compare, sweep, stability --plot) with nothing printed on
// stderr by gnuplot.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "support/files.hpp"
#include "support/needs.hpp"

namespace fs = std::filesystem;

namespace {

int run(const std::string& args) {
  const int raw = std::system((std::string("'") + CONTACT2D_EXE + "' " + args).c_str());
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

struct Output {
  int status = -1;
  std::string out, err;
};

using contact2d::test::read_file;

// Runs contact2d with `env` before it (e.g. "VAR=1"), capturing both streams.
Output capture(const std::string& args, const std::string& env = "") {
  const fs::path base =
      fs::temp_directory_path() / ("contact2d_cli_out_" + std::to_string(::getpid()));
  const fs::path out = base.string() + ".out", err = base.string() + ".err";
  const int raw = std::system((env + (env.empty() ? "" : " ") + "'" + CONTACT2D_EXE + "' " + args +
                               " >'" + out.string() + "' 2>'" + err.string() + "'")
                                  .c_str());
  Output o{WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, read_file(out), read_file(err)};
  fs::remove(out);
  fs::remove(err);
  return o;
}

fs::path temp_png(const std::string& name) {
  return fs::temp_directory_path() /
         ("contact2d_plot_" + name + "_" + std::to_string(::getpid()) + ".png");
}

// A PNG that gnuplot finished: the signature and more than a header.
void expect_png(const fs::path& png) {
  ASSERT_TRUE(fs::exists(png)) << png;
  EXPECT_GT(fs::file_size(png), 10000u) << png;
  EXPECT_EQ(read_file(png).substr(1, 3), "PNG") << png;
}

TEST(Cli, SimulateWritesTheTrajectoryCsv) {
  const fs::path csv =
      fs::temp_directory_path() / ("contact2d_cli_" + std::to_string(::getpid()) + ".csv");
  fs::remove(csv);
  ASSERT_EQ(run("simulate " CONTACT2D_SCENES_DIR "/box.toml --engine ref --duration 0.5 --csv '" +
                csv.string() + "' >/dev/null"),
            0);
  std::ifstream in(csv);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "t,x,y,theta,vx,vy,omega");
  // 0.5 s sampled every output_dt = 1 ms: 501 rows, all finite, 7 columns.
  int rows = 0;
  std::string line;
  while (std::getline(in, line)) {
    ++rows;
    std::stringstream fields(line);
    std::string field;
    int columns = 0;
    while (std::getline(fields, field, ',')) {
      ++columns;
      EXPECT_TRUE(std::isfinite(std::stod(field))) << line;
    }
    EXPECT_EQ(columns, 7) << line;
  }
  EXPECT_EQ(rows, 501);
  fs::remove(csv);
}

TEST(Cli, HelpOnTheProgramAndEverySubcommand) {
  EXPECT_EQ(run("--help >/dev/null"), 0);
  for (const char* command : {"simulate", "generate", "compare", "sweep", "stability", "play"}) {
    EXPECT_EQ(run(std::string(command) + " --help >/dev/null"), 0) << command;
  }
}

// The top-level help orders the subcommands by what users come for
// (comparing the engines, then their own model, fitting, running a scene,
// the studies, the game last), under headings, and docs/cli.md's sections
// follow the same order.
TEST(Cli, TheHelpListsTheSubcommandsByWhatUsersComeForUnderHeadings) {
  const Output o = capture("--help");
  ASSERT_EQ(o.status, 0) << o.err;
  std::vector<std::string> order = {"compare",  "report", "solref",    "inspect", "fit", "simulate",
                                    "generate", "sweep",  "stability", "atlas",   "play"};
  std::vector<std::string> headings = {
      "Compare the reference with MuJoCo:",         "Your own MuJoCo model:",
      "Contact parameters from measurements:",      "Run and export a scene:",
      "Step size, stability and fidelity studies:", "The game:"};
#ifndef CONTACT2D_WITH_MUJOCO
  const std::vector<std::string> mujoco_only = {"compare", "report",   "solref",
                                                "inspect", "generate", "atlas"};
  order.erase(std::remove_if(order.begin(), order.end(),
                             [&](const std::string& c) {
                               return std::find(mujoco_only.begin(), mujoco_only.end(), c) !=
                                      mujoco_only.end();
                             }),
              order.end());
  headings.erase(headings.begin(), headings.begin() + 2);
#endif
  // Each subcommand's line, "  NAME   description", in this order, after
  // "Subcommands:" (tests/docs reads the list from there).
  size_t at = o.out.find("\nSubcommands:\n");
  ASSERT_NE(at, std::string::npos) << o.out;
  std::vector<std::string> listed;
  const std::regex line(R"(\n  ([a-z]+) )");
  for (auto it = std::sregex_iterator(o.out.begin() + static_cast<long>(at), o.out.end(), line);
       it != std::sregex_iterator(); ++it)
    listed.push_back((*it)[1]);
  EXPECT_EQ(listed, order) << o.out;
  for (const std::string& heading : headings) {
    const size_t h = o.out.find("\n" + heading + "\n", at);
    EXPECT_NE(h, std::string::npos) << heading << "\n" << o.out;
    at = h == std::string::npos ? at : h;  // in this order
  }
  // docs/cli.md: its "## contact2d NAME" sections in the same order.
  const std::string page = read_file(fs::path(CONTACT2D_SOURCE_DIR) / "docs" / "cli.md");
  std::vector<std::string> sections;
  const std::regex section(R"(\n## contact2d ([a-z]+))");
  for (auto it = std::sregex_iterator(page.begin(), page.end(), section);
       it != std::sregex_iterator(); ++it) {
    const std::string name = (*it)[1];
    if (std::find(order.begin(), order.end(), name) != order.end()) sections.push_back(name);
  }
  EXPECT_EQ(sections, order) << "docs/cli.md's sections";
}

#ifdef CONTACT2D_WITH_MUJOCO
// generate -o wrote the file silently: it says what it wrote, in one line
// on standard output; without -o standard output is the model alone.
TEST(Cli, GenerateToAFileSaysWhatItWrote) {
  const fs::path xml =
      fs::temp_directory_path() / ("contact2d_generate_" + std::to_string(::getpid()) + ".xml");
  const std::string scene = CONTACT2D_SCENES_DIR "/box.toml";
  const Output o = capture("generate " + scene + " -o '" + xml.string() + "'");
  ASSERT_EQ(o.status, 0) << o.err;
  EXPECT_EQ(o.err, "");
  ASSERT_TRUE(fs::exists(xml));
  EXPECT_EQ(o.out, "contact2d generate: wrote " + xml.string() + ": the MJCF model of " + scene +
                       " for MuJoCo 2.2.2 (mapping calibrated, geometry corners; " +
                       std::to_string(fs::file_size(xml)) + " bytes)\n");
  const std::string written = read_file(xml);
  const Output v3 = capture("generate " + scene + " --engine mujoco3 --mapping compensated -o '" +
                            xml.string() + "'");
  if (v3.status == 0) {  // MuJoCo 3 (node) may be missing
    EXPECT_NE(v3.out.find(" for MuJoCo 3.14 (mapping compensated,"), std::string::npos) << v3.out;
  }
  const Output piped = capture("generate " + scene);
  ASSERT_EQ(piped.status, 0) << piped.err;
  EXPECT_EQ(piped.out, written) << "the model alone, the same bytes as the file";
  fs::remove(xml);
}
#endif

TEST(Cli, VersionNamesTheProjectVersionAndTheGitRevision) {
  const Output o = capture("--version");
  EXPECT_EQ(o.status, 0);
  EXPECT_EQ(o.err, "");
  // "contact2d 0.1.0 (git 0123456789ab)", "+dirty" with uncommitted changes.
  EXPECT_TRUE(std::regex_match(
      o.out, std::regex(std::string("contact2d ") +
                        std::regex_replace(CONTACT2D_PROJECT_VERSION, std::regex("\\."), "\\.") +
                        "( \\(git [0-9a-f]{12}(\\+dirty)?\\))?\n")))
      << o.out;
  // Built from a git checkout (as this test is): the revision is known.
  if (fs::exists(fs::path(CONTACT2D_SOURCE_DIR) / ".git") &&
      std::system("git --version >/dev/null 2>&1") == 0) {
    EXPECT_NE(o.out.find("(git "), std::string::npos) << o.out;
  }
}

TEST(Cli, HelpShowsTypedMetavariables) {
  const Output simulate = capture("simulate --help");
  EXPECT_NE(simulate.out.find("--dt SECONDS"), std::string::npos) << simulate.out;
  EXPECT_NE(simulate.out.find("--duration SECONDS"), std::string::npos) << simulate.out;
  EXPECT_NE(simulate.out.find("--set KEY=VALUE"), std::string::npos) << simulate.out;
  EXPECT_NE(capture("play --help").out.find("--seed N"), std::string::npos);
  // No option of any subcommand falls back to CLI11's untyped "TEXT".
  for (const char* command :
       {"simulate", "generate", "compare", "sweep", "stability", "play", "report"}) {
    const Output o = capture(std::string(command) + " --help");
    if (o.status != 0) continue;  // generate, compare, report: built with MuJoCo only
    EXPECT_EQ(o.out.find(" TEXT"), std::string::npos) << command << ":\n" << o.out;
  }
}

TEST(Cli, SetErrorsNameTheOptionNotTheSceneFile) {
  const Output o =
      capture("simulate " CONTACT2D_SCENES_DIR "/box.toml --set contact.k=1e20 --duration 0.1");
  EXPECT_EQ(o.status, 2);
  EXPECT_EQ(o.err.rfind("contact2d: --set contact.k=1e20: contact.k = 1e+20 is out of range", 0),
            0u)
      << o.err;
  EXPECT_EQ(o.err.find("box.toml"), std::string::npos) << o.err;
  // Ranges as written, not CLI11's "0.000000 to 0.001000".
  for (const auto& [args, message] : std::vector<std::pair<std::string, std::string>>{
           {"sweep " CONTACT2D_SCENES_DIR "/box.toml --tol 1",
            "contact2d: --tol: 1 is out of range: must be in [1e-15, 1e-3]"},
           {"stability " CONTACT2D_SCENES_DIR "/box.toml --dt-max -1",
            "contact2d: --dt-max: -1 is out of range: must be in (0, 1e5] s"},
           {"stability " CONTACT2D_SCENES_DIR "/box.toml --precision 2",
            "contact2d: --precision: 2 is out of range: must be in [1e-4, 1]"}}) {
    const Output bad = capture(args);
    EXPECT_EQ(bad.status, 2) << args;
    EXPECT_EQ(bad.err.rfind(message, 0), 0u) << args << ": " << bad.err;
    EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  }
}

// --set reaches an obstacle's keys by the name messages give it,
// obstacle[i] (it answered "unknown key 'obstacle[0]'"); obstacle.0.k is
// pointed there. A scene whose [sim] is a value (sim = 5, a file of the
// test's own) is the file's fault, named so: the message blamed --dt.
TEST(Cli, SetReachesAnObstacleAndBlamesTheFileForItsOwnFault) {
  const std::string pitch = CONTACT2D_SCENES_DIR "/game/pitch.toml";
  Output o = capture("generate " + pitch + " --set 'obstacle[1].k=12345'");
  EXPECT_EQ(o.status, 0) << o.err;
  EXPECT_NE(o.out.find("12345"), std::string::npos) << "the override reached the MJCF's header";
  for (const auto& [args, message] : std::vector<std::pair<std::string, std::string>>{
           {"generate " + pitch + " --set 'obstacle[9].k=1'",
            "contact2d: --set obstacle[9].k=1: " + pitch +
                " has no obstacle[9] (4 [[obstacle]] tables, numbered from 0)"},
           {"generate " + pitch + " --set obstacle.1.k=1",
            "contact2d: --set obstacle.1.k=1: 'obstacle' is a list of tables: name one, as "
            "obstacle[1].k"}}) {
    const Output bad = capture(args);
    EXPECT_EQ(bad.status, 2) << args;
    EXPECT_EQ(bad.err, message + "\n") << args;
  }
  const fs::path scene =
      fs::temp_directory_path() / ("contact2d_sim_value_" + std::to_string(::getpid()) + ".toml");
  std::ofstream(scene) << "scene = \"point_mass\"\nsim = 5\n";
  o = capture("simulate '" + scene.string() + "' --dt 1e-3");
  EXPECT_EQ(o.status, 2);
  EXPECT_EQ(o.err, "contact2d: " + scene.string() +
                       ": 'sim' is a value, not a table, so --dt 1e-3 cannot set sim.dt (write "
                       "[sim] as a table)\n");
  fs::remove(scene);
}

// An unknown subcommand is named (not "A subcommand is required"), and a
// MuJoCo model given as a scene is called one (not "malformed TOML"): one
// line each, exit 2, nothing on stdout.
TEST(Cli, UnknownSubcommandAndAnMjcfSceneAreNamed) {
  const Output unknown = capture("frob");
  EXPECT_EQ(unknown.status, 2);
  EXPECT_EQ(unknown.err.rfind("contact2d: frob: unknown subcommand (one of compare", 0), 0u)
      << unknown.err;
  EXPECT_EQ(std::count(unknown.err.begin(), unknown.err.end(), '\n'), 1) << unknown.err;
  EXPECT_TRUE(unknown.out.empty()) << unknown.out;
  const fs::path xml =
      fs::temp_directory_path() / ("contact2d_cli_model_" + std::to_string(::getpid()) + ".xml");
  std::ofstream(xml) << "\n  <mujoco model=\"m\"><worldbody/></mujoco>\n";
  const Output mjcf = capture("simulate '" + xml.string() + "'");
  fs::remove(xml);
  EXPECT_EQ(mjcf.status, 2);
  EXPECT_NE(mjcf.err.find(": this is an MJCF (XML) file: contact2d reads scenes (TOML"),
            std::string::npos)
      << mjcf.err;
  EXPECT_EQ(mjcf.err.find("malformed TOML"), std::string::npos) << mjcf.err;
  EXPECT_EQ(std::count(mjcf.err.begin(), mjcf.err.end(), '\n'), 1) << mjcf.err;
}

TEST(Cli, SimulateNamesMujocoIntegratorsByTheSceneNameAndMujocosOwn) {
#ifdef CONTACT2D_WITH_MUJOCO
  const Output o =
      capture("simulate " CONTACT2D_SCENES_DIR "/box.toml --engine mujoco --duration 0.05");
  EXPECT_EQ(o.status, 0) << o.err;
  EXPECT_NE(o.out.find("[mujoco, semi_implicit_euler (MuJoCo Euler), "), std::string::npos)
      << o.out;
#endif
  const Output r = capture("simulate " CONTACT2D_SCENES_DIR "/box.toml --duration 0.05");
  EXPECT_NE(r.out.find("[ref, semi_implicit_euler, "), std::string::npos) << r.out;
  // Durations read as durations: "0.05 s in 3.2 ms", never "1e+03 ms".
  EXPECT_TRUE(std::regex_search(r.out, std::regex(" s in [0-9.]+ (µs|ms|s)\\]"))) << r.out;
}

// A duration that is no whole number of steps runs the nearest whole number
// (step_count): at dt = 0.3 s, 1 s is 3 steps, 0.9 s (without gravity the
// box flies on, touching nothing). The summary said "1 s"
// while the run and its CSV ended at 0.9 s (1.2 s at dt = 0.6); now it
// names the time run. A duration of whole steps keeps its short form.
TEST(Cli, ADurationOfNoWholeNumberOfStepsSaysTheTimeRun) {
  Output o = capture("simulate " CONTACT2D_SCENES_DIR
                     "/box.toml --duration 1 --dt 0.3 --set sim.gravity=0");
  EXPECT_NE(o.out.find(", 0.9 s (3 steps: the whole number nearest to the duration, 1 s) in "),
            std::string::npos)
      << o.out << o.err;
  o = capture("simulate " CONTACT2D_SCENES_DIR "/box.toml --duration 0.05");
  EXPECT_NE(o.out.find("dt = 0.0001 s, 0.05 s in "), std::string::npos) << o.out;
}

// Progress when stderr is a pipe: lines with the time left (every
// CONTACT2D_PROGRESS_SECONDS, here at every run) and a last "done in" line;
// nothing with --quiet.
TEST(Cli, SweepProgressOnAPipeEstimatesTheTimeLeft) {
  const std::string args = "sweep " CONTACT2D_SCENES_DIR
                           "/point_mass.toml --duration 0.2 --integrators semi_implicit_euler "
                           "--dts 1e-3,5e-4,2e-4 --repeats 1 --threads 1";
  const Output o = capture(args, "CONTACT2D_PROGRESS_SECONDS=0");
  EXPECT_EQ(o.status, 0) << o.err;
  EXPECT_NE(o.err.find("sweep point_mass: 1/"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find(" left\n"), std::string::npos) << o.err;
  EXPECT_TRUE(std::regex_search(o.err, std::regex("sweep point_mass: ([0-9]+)/\\1 done in ")))
      << o.err;
  EXPECT_EQ(o.err.find('\r'), std::string::npos) << "no terminal codes on a pipe";
  const Output quiet = capture(args + " --quiet", "CONTACT2D_PROGRESS_SECONDS=0");
  EXPECT_EQ(quiet.status, 0);
  EXPECT_EQ(quiet.err, "");
  // The default interval (5 s) prints nothing on a run this short.
  EXPECT_EQ(capture(args).err, "");
}

// Every plot the program draws, on scenes that exercise the edge cases
// (the point mass: no θ; a single Δt; one k), must leave gnuplot silent:
// run_gnuplot passes on anything gnuplot prints on stderr.
TEST(Cli, EveryPlotDrawsWithoutAGnuplotWarning) {
  CONTACT2D_NEEDS(std::system("gnuplot --version >/dev/null 2>&1") == 0, "no gnuplot");
  struct Case {
    std::string name, args;
  };
  std::vector<Case> cases = {
      {"sweep", "sweep " CONTACT2D_SCENES_DIR
                "/box.toml --duration 0.3 --integrators semi_implicit_euler,rk4 --dts "
                "1e-3,5e-4,2e-4 --repeats 1 --quiet"},
      {"sweep_one_dt", "sweep " CONTACT2D_SCENES_DIR
                       "/point_mass.toml --duration 0.2 --integrators rk4 --dts 1e-3 --repeats 1 "
                       "--quiet"},
      {"stability", "stability " CONTACT2D_SCENES_DIR
                    "/point_mass.toml --duration 0.2 --ks 1e4,1e6 --integrators "
                    "explicit_euler,semi_implicit_euler,rk4 --quiet"},
      {"stability_one_k", "stability " CONTACT2D_SCENES_DIR
                          "/box.toml --duration 0.2 --ks 1e5 --integrators implicit_euler --quiet"},
  };
#ifdef CONTACT2D_WITH_MUJOCO
  for (const char* scene : {"point_mass", "box", "tshape", "circle"}) {
    cases.push_back(
        {std::string("compare_") + scene, std::string("compare " CONTACT2D_SCENES_DIR "/") + scene +
                                              ".toml --duration 0.3 --no-diagnosis"});
  }
  cases.push_back({"sweep_mujoco", "sweep " CONTACT2D_SCENES_DIR
                                   "/box.toml --duration 0.2 --integrators semi_implicit_euler "
                                   "--dts 1e-3,5e-4 --engines ref,mujoco:seed,mujoco:exact "
                                   "--repeats 1 --quiet"});
#endif
  for (const Case& c : cases) {
    const fs::path png = temp_png(c.name);
    fs::remove(png);
    const Output o = capture(c.args + " --plot '" + png.string() + "'");
    EXPECT_EQ(o.status, 0) << c.name << ": " << o.err;
    // run_gnuplot passes gnuplot's stderr on as "contact2d: gnuplot warning …"
    // (tests/io/test_plot.cpp checks that it does).
    EXPECT_EQ(o.err.find("gnuplot"), std::string::npos) << c.name << ":\n" << o.err;
    expect_png(png);
    fs::remove(png);
  }
}

TEST(Cli, AllBuiltInScenesRunWithEveryIntegrator) {
  for (const char* scene : {"point_mass", "box", "tshape", "circle"}) {
    for (const char* integrator :
         {"explicit_euler", "semi_implicit_euler", "implicit_euler", "rk4"}) {
      EXPECT_EQ(run(std::string("simulate " CONTACT2D_SCENES_DIR "/") + scene +
                    ".toml --integrator " + integrator + " >/dev/null"),
                0)
          << scene << " " << integrator;
    }
  }
}

TEST(Cli, AnUnknownSubcommandIsNamed) {
  const Output o = capture("frob");
  EXPECT_EQ(o.status, 2);
  // In the order of --help: what users come for first.
  EXPECT_EQ(o.err.rfind("contact2d: frob: unknown subcommand (one of compare, report, solref, ", 0),
            0u)
      << o.err;
  EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
}

}  // namespace
