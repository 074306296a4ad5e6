// mujoco3 through the program: it runs where MuJoCo runs, and what is
// missing or dies is one line, an exit status and no file. The broken
// installs are private folders the test makes (CONTACT2D_MUJOCO3_DIR points
// the program at them); the real package is only linked from there.
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "mujoco3_test_util.hpp"

namespace contact2d {
namespace {

namespace fs = std::filesystem;

struct Result {
  int status = -1;
  std::string out, err;
};

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

class Mujoco3Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("contact2d_mj3_cli_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "work");
    std::ofstream(dir_ / "work" / "box.toml")
        << "scene = \"box\"\n[contact]\nk = 1e4\nc = 200\nmu = 0.5\ndamping = \"kelvin_voigt\"\n"
           "[initial]\ny = 0.5\ntheta = 0.3\n[sim]\ndt = 1e-4\nduration = 0.5\n";
  }
  void TearDown() override { fs::remove_all(dir_); }

  // contact2d with the arguments, in work/, with `env` before it.
  Result run(const std::string& args, const std::string& env = "") const {
    const std::string out = (dir_ / "stdout").string(), err = (dir_ / "stderr").string();
    const std::string command = "cd '" + (dir_ / "work").string() + "' && " + env + " '" +
                                CONTACT2D_BINARY "' " + args + " >'" + out + "' 2>'" + err + "'";
    const int raw = std::system(command.c_str());
    return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(out), slurp(err)};
  }
  std::vector<std::string> work_files() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_ / "work"))
      names.push_back(e.path().filename());
    std::sort(names.begin(), names.end());
    return names;
  }
  // A copy of the driver (plus `extra`, appended) beside a node_modules that
  // is the real one, or one whose package.json says `version`.
  fs::path install(const std::string& extra, const std::string& version = "") const {
    const fs::path real = mujoco3::package_directory();
    const fs::path fake = dir_ / "mujoco3";
    fs::create_directories(fake);
    std::ofstream(fake / "driver.mjs") << slurp(real / "driver.mjs") << extra;
    if (version.empty()) {
      fs::create_directory_symlink(real / "node_modules", fake / "node_modules");
    } else {
      fs::create_directories(fake / "node_modules/@mujoco/mujoco");
      std::ofstream(fake / "node_modules/@mujoco/mujoco/package.json")
          << "{\"name\": \"@mujoco/mujoco\", \"version\": \"" << version << "\"}\n";
    }
    return fake;
  }

  fs::path dir_;
};

// Energy gained beyond the stability limit fails on 3.14 as on 2.2.2
// (tests/cli/test_nonphysical.cpp, MujocoBeyondItsLimitFailsToo: the same
// box, ω = 200 rad/s, ζ = 0.5, limit 1.236 at ω·Δt = 1.4).
TEST_F(Mujoco3Cli, EnergyGainedBeyondTheStabilityLimitFails) {
  std::ofstream(dir_ / "work" / "tilted.toml")
      << "scene = \"box\"\n[body]\nmass = 1.0\nwidth = 0.4\nheight = 0.2\n[contact]\n"
         "k = 1e4\nc = 50.0\nmu = 0.5\nalpha = 100.0\ndamping = \"compression\"\n"
         "[initial]\ny = 0.6\ntheta = 0.3\nvx = 1.0\n[sim]\ndt = 0.007\nduration = 2.0\n"
         "integrator = \"implicit_euler\"\n";
  const Result r = run("simulate tilted.toml --engine mujoco3 --csv out.csv");
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_NE(r.err.find("not physics: energy rose by"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("beyond the semi-implicit Euler limit 1.24"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "work" / "out.csv"));
}

void expect_one_line(const std::string& err, const std::string& needle) {
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_NE(err.find(needle), std::string::npos) << err;
}

TEST_F(Mujoco3Cli, SimulateAndCompareRunIt) {
  CONTACT2D_NEEDS_MUJOCO3();
  Result r = run("simulate box.toml --engine mujoco3 --mapping compensated --csv box.csv");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("box [mujoco3, semi_implicit_euler (MuJoCo 3 Euler)"), std::string::npos)
      << r.out;
  EXPECT_EQ(work_files(), (std::vector<std::string>{"box.csv", "box.toml"}));
  r = run(
      "compare box.toml --engines mujoco:compensated,mujoco3:compensated --no-diagnosis --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\"ref_vs_mujoco3_max_pos_err\""), std::string::npos) << r.out;
  // The versions side by side: their distance and its cause.
  EXPECT_NE(r.out.find("\"version_notes\": [\"MuJoCo (MuJoCo 2.2.2) <-> MuJoCo 3 (MuJoCo 3.14): "),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("The same contact law on both"), std::string::npos) << r.out;
  r =
      run("compare box.toml --engines mujoco:compensated,mujoco3:compensated:corners:damper "
          "--no-diagnosis --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("friction damper (--friction damper) is the cause"), std::string::npos)
      << r.out;
}

// The Nodes a run keeps for reuse died with the program (the kernel's
// parent-death signal) but nobody reaped them: each stayed a zombie, handed
// to init, for 0.5–2 s (for ever under a PID 1 that reaps nothing). Now
// the program kills and reaps them as it ends. This test makes itself the
// "init" of the run (a child subreaper): a process of the run handed to it
// after the run ended is one the program left behind. A two-Node compare
// and a one-Node simulate; none is left.
TEST_F(Mujoco3Cli, NoNodeIsLeftForAnotherProcessToReap) {
  CONTACT2D_NEEDS_MUJOCO3();
  ASSERT_EQ(::prctl(PR_SET_CHILD_SUBREAPER, 1), 0);
  for (const char* args : {"compare box.toml --engines mujoco3 --threads 2 --no-diagnosis",
                           "simulate box.toml --engine mujoco3"}) {
    const Result r = run(args);
    EXPECT_EQ(r.status, 0) << r.err;
    // Orphans arrive as their parent ends; a killed Node is a zombie within
    // milliseconds: 2 s of looking is plenty.
    std::vector<pid_t> handed;
    for (int i = 0; i < 200; ++i) {
      const pid_t pid = ::waitpid(-1, nullptr, WNOHANG);
      if (pid > 0) handed.push_back(pid);
      if (pid < 0 && errno == ECHILD) break;  // no child at all: none can come
      ::usleep(10000);
    }
    EXPECT_TRUE(handed.empty()) << args << ": " << handed.size()
                                << " process(es) of the run outlived it";
  }
  ::prctl(PR_SET_CHILD_SUBREAPER, 0);
}

// compare --engine NAME takes --mapping, --geometry and --friction as
// simulate's --engine does (before: refused, "options are part of its
// name", while the help said it took them): the same run as the options
// written into the name; an option the name already gives is refused.
TEST_F(Mujoco3Cli, CompareEngineTakesTheEngineOptions) {
  CONTACT2D_NEEDS_MUJOCO3();
  const Result options = run(
      "compare box.toml --engine mujoco3 --mapping compensated --friction damper --no-diagnosis "
      "--json");
  ASSERT_EQ(options.status, 0) << options.err;
  const Result named =
      run("compare box.toml --engine mujoco3:compensated:corners:damper --no-diagnosis --json");
  ASSERT_EQ(named.status, 0) << named.err;
  auto without_times = [](std::string json) {  // wall-clock seconds differ run to run
    return std::regex_replace(json, std::regex(R"("[a-z0-9_]*seconds": [0-9.e+-]+)"), "");
  };
  EXPECT_EQ(without_times(options.out), without_times(named.out));
  const Result twice = run("compare box.toml --engine mujoco3:exact --mapping seed --no-diagnosis");
  EXPECT_EQ(twice.status, 2) << twice.err;
  EXPECT_NE(twice.err.find("--mapping seed: the engine's name mujoco3:exact gives mapping exact"),
            std::string::npos)
      << twice.err;
}

// compare --threads: each thread that runs MuJoCo 3 starts a Node process of
// its own, so a diagnosed compare with --threads 1 starts one, with
// --threads 2 two (the base run and the diagnosis's early re-runs side by
// side), and both print the same numbers. The driver, copied, appends its
// pid to a file of the test's when it starts.
TEST_F(Mujoco3Cli, CompareThreadsSetsTheNodesStartedNotTheResult) {
  CONTACT2D_NEEDS_MUJOCO3();
  const fs::path started = dir_ / "started";
  const fs::path fake =
      install("\nimport {appendFileSync as logStart} from 'node:fs';\nlogStart('" +
              started.string() + "', process.pid + '\\n');\n");
  auto without_times = [](std::string json) {  // wall-clock seconds differ run to run
    return std::regex_replace(json, std::regex(R"("[a-z0-9_]*seconds": [0-9.e+-]+)"), "");
  };
  std::string first_json;
  for (const int threads : {1, 2}) {
    fs::remove(started);
    const Result r =
        run("compare box.toml --engine mujoco3 --json --threads " + std::to_string(threads),
            "CONTACT2D_MUJOCO3_DIR='" + fake.string() + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string pids = slurp(started);
    EXPECT_EQ(std::count(pids.begin(), pids.end(), '\n'), threads) << pids;
    EXPECT_NE(r.out.find("\"diagnosis\""), std::string::npos) << r.out;
    if (threads == 1)
      first_json = without_times(r.out);
    else
      EXPECT_EQ(without_times(r.out), first_json);
  }
  for (const char* bad : {"0", "257", "two"}) {
    const Result r = run(std::string("compare box.toml --no-diagnosis --threads ") + bad);
    EXPECT_EQ(r.status, 2) << bad;
    EXPECT_NE(r.err.find("--threads"), std::string::npos) << r.err;
  }
}

// The atlas on MuJoCo 3 (engine = "mujoco3" in the spec): the same rows as
// on 2.2.2 but for rounding, column by column; another engine is one line.
TEST_F(Mujoco3Cli, TheAtlasRunsOnMujoco3) {
  CONTACT2D_NEEDS_MUJOCO3();
  const std::string spec = slurp(std::string(CONTACT2D_SOURCE_DIR) + "/tests/slurm/tiny.toml");
  const std::string head = "[atlas]\n";
  const size_t at = spec.find(head);
  ASSERT_NE(at, std::string::npos);
  auto with_engine = [&](const std::string& engine) {
    std::string s = spec;
    s.insert(at + head.size(), "engine = \"" + engine + "\"\n");
    return s;
  };
  std::ofstream(dir_ / "work" / "two.toml") << spec;
  std::ofstream(dir_ / "work" / "three.toml") << with_engine("mujoco3");
  std::ofstream(dir_ / "work" / "bad.toml") << with_engine("bullet");
  ASSERT_EQ(run("atlas two.toml --out two").status, 0);
  ASSERT_EQ(run("atlas three.toml --out three").status, 0);
  auto column = [&](const std::string& dir, const std::string& name) {
    std::istringstream lines(slurp(dir_ / "work" / dir / "points.csv"));
    std::string header, line;
    std::getline(lines, header);
    size_t index = 0;
    for (std::istringstream h(header); std::getline(h, line, ',') && line != name;) ++index;
    std::vector<double> values;
    while (std::getline(lines, line)) {
      std::istringstream cells(line);
      std::string cell;
      for (size_t i = 0; i <= index; ++i) std::getline(cells, cell, ',');
      values.push_back(std::stod(cell));
    }
    return values;
  };
  const std::vector<double> two = column("two", "ref_mujoco_max_pos");
  const std::vector<double> three = column("three", "ref_mujoco_max_pos");
  ASSERT_EQ(two.size(), 8u);
  ASSERT_EQ(three.size(), two.size());
  // Versions differ by rounding (test_versions.cpp): 1e-9 m on these short runs.
  for (size_t i = 0; i < two.size(); ++i) EXPECT_NEAR(three[i], two[i], 1e-9) << "point " << i;
  const Result bad = run("atlas bad.toml --out bad");
  EXPECT_EQ(bad.status, 2);
  expect_one_line(bad.err, "atlas.engine = \"bullet\" is not a MuJoCo engine");
}

TEST_F(Mujoco3Cli, WithoutTheDriverOrThePackageItSaysWhatFixesIt) {
  fs::create_directories(dir_ / "empty");
  Result r = run("simulate box.toml --engine mujoco3 --csv box.csv",
                 "CONTACT2D_MUJOCO3_DIR='" + (dir_ / "empty").string() + "'");
  EXPECT_EQ(r.status, 2);
  expect_one_line(r.err, "driver.mjs is missing");
  const fs::path fake = dir_ / "nopackage";
  fs::create_directories(fake);
  std::ofstream(fake / "driver.mjs") << "\n";
  r = run("simulate box.toml --engine mujoco3 --csv box.csv",
          "CONTACT2D_MUJOCO3_DIR='" + fake.string() + "'");
  EXPECT_EQ(r.status, 2);
  expect_one_line(r.err, "@mujoco/mujoco is not installed in " + fake.string() +
                             "/node_modules: run scripts/setup, or: npm ci --prefix " +
                             fake.string());
  EXPECT_EQ(work_files(), std::vector<std::string>{"box.toml"});
  // The reference still runs.
  EXPECT_EQ(run("simulate box.toml", "CONTACT2D_MUJOCO3_DIR='" + fake.string() + "'").status, 0);
}

TEST_F(Mujoco3Cli, WithoutNodeItSaysSo) {
  const Result r = run("simulate box.toml --engine mujoco3", "PATH='" + dir_.string() + "'");
  EXPECT_EQ(r.status, 2);
  expect_one_line(r.err, "Node.js (the command node) is not installed: run scripts/setup");
}

TEST_F(Mujoco3Cli, AnotherVersionOfThePackageIsRefused) {
  const fs::path fake = install("", "3.13.0");
  const Result r =
      run("simulate box.toml --engine mujoco3", "CONTACT2D_MUJOCO3_DIR='" + fake.string() + "'");
  EXPECT_EQ(r.status, 2);
  expect_one_line(r.err, "has @mujoco/mujoco 3.13.0, contact2d is pinned to 3.14.0");
}

// Node killed while it steps (SIGKILL on the fourth request it reads:
// hello, load, reset, then the first batch): exit 3, one line, no file.
TEST_F(Mujoco3Cli, NodeKilledMidRunLeavesNoFile) {
  CONTACT2D_NEEDS_MUJOCO3();
  const fs::path fake = install(
      "\nlet requests = 0;\ninput.prependListener('line', () => { if (++requests === 4) "
      "process.kill(process.pid, 'SIGKILL'); });\n");
  for (const std::string& args :
       {std::string("simulate box.toml --engine mujoco3 --csv box.csv"),
        std::string(
            "compare box.toml --engines mujoco3 --no-diagnosis --csv cmp.csv --plot cmp.png")}) {
    const Result r = run(args, "CONTACT2D_MUJOCO3_DIR='" + fake.string() + "'");
    EXPECT_EQ(r.status, 3) << args << "\n" << r.err;
    expect_one_line(r.err, "killed by signal 9");
    EXPECT_EQ(work_files(), std::vector<std::string>{"box.toml"}) << args;
  }
}

}  // namespace
}  // namespace contact2d
