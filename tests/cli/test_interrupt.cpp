// Interrupted runs leave nothing behind (io/interrupt.hpp): each command is
// started through the real program in an empty directory, signalled as soon
// as its temporary output file exists, and must exit with 128 + the signal,
// print exactly one line, and leave the directory empty.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/files.hpp"
#include "support/stand_in.hpp"

namespace fs = std::filesystem;

namespace {

struct Case {
  const char* name;
  std::vector<std::string> args;  // after the program name; run inside the directory
  int signal;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

using contact2d::test::read_file;

bool has_temporary(const fs::path& dir) {
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().filename().string().find(".tmp") != std::string::npos) return true;
  }
  return false;
}

class Interrupt : public ::testing::TestWithParam<Case> {};

TEST_P(Interrupt, RemovesTheTemporaryFileAndExitsWith128PlusTheSignal) {
  const Case& c = GetParam();
  const fs::path dir = fs::temp_directory_path() / ("contact2d_interrupt_" + std::string(c.name) +
                                                    "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path err = dir.string() + ".stderr";

  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    if (::chdir(dir.c_str()) != 0) ::_exit(120);
    if (!std::freopen("/dev/null", "w", stdout) || !std::freopen(err.c_str(), "w", stderr))
      ::_exit(121);
    std::vector<std::string> args = c.args;
    args.insert(args.begin(), CONTACT2D_EXE);
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(CONTACT2D_EXE, argv.data());
    ::_exit(122);
  }
  // Wait (up to 60 s) for the command to open its output.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  bool opened = false;
  int status = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    if (has_temporary(dir)) {
      opened = true;
      break;
    }
    if (::waitpid(pid, &status, WNOHANG) == pid) break;  // ended before opening: a failure
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(opened) << "no temporary file appeared; stderr: " << read_file(err);
  ::kill(pid, c.signal);
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << "killed instead of exiting";
  EXPECT_EQ(WEXITSTATUS(status), 128 + c.signal);
  EXPECT_TRUE(fs::is_empty(dir)) << "left behind: " << fs::directory_iterator(dir)->path();
  const std::string text = read_file(err);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << text;
  EXPECT_NE(text.find("contact2d: interrupted ("), std::string::npos) << text;
  fs::remove_all(dir);
  fs::remove(err);
}

// SIGKILL cannot be caught: the temporary stays. Its name carries the PID of
// the run that made it ("out.csv.tmp.PID.XXXXXX"), and the next run writing
// the same output removes it once that PID is gone, but leaves a live
// process's temporary and another output's alone.
TEST(StaleTemporary, TheNextRunRemovesWhatAKilledRunLeft) {
  const fs::path dir =
      fs::temp_directory_path() / ("contact2d_sigkill_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    if (::chdir(dir.c_str()) != 0) ::_exit(120);
    if (!std::freopen("/dev/null", "w", stdout) || !std::freopen("/dev/null", "w", stderr))
      ::_exit(121);
    const std::string scene = CONTACT2D_SCENES_DIR "/box.toml";
    ::execl(CONTACT2D_EXE, CONTACT2D_EXE, "simulate", scene.c_str(), "--csv", "out.csv",
            "--duration", "2000", static_cast<char*>(nullptr));
    ::_exit(122);
  }
  // No deadline: the run lasts 2e7 steps, and it ending first is a failure.
  int status = 0;
  bool opened = false;
  while (!(opened = has_temporary(dir))) {
    if (::waitpid(pid, &status, WNOHANG) == pid) break;
    ::usleep(2000);
  }
  ASSERT_TRUE(opened) << "no temporary file appeared";
  ::kill(pid, SIGKILL);
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  std::string left;
  for (const auto& entry : fs::directory_iterator(dir)) left = entry.path().filename().string();
  const std::string prefix = "out.csv.tmp." + std::to_string(pid) + ".";
  ASSERT_EQ(left.rfind(prefix, 0), 0u) << left;
  // A live process's temporary (this test's) and another output's.
  const std::string live = "out.csv.tmp." + std::to_string(::getpid()) + ".abcdef";
  const std::string other = "other.csv.tmp." + std::to_string(pid) + ".abcdef";
  std::ofstream(dir / live) << "x";
  std::ofstream(dir / other) << "x";
  // A file last written long before this test's process started cannot be
  // that process's: its PID was reused, and the file is stale too.
  const std::string reused = "out.csv.tmp." + std::to_string(::getpid()) + ".reused";
  std::ofstream(dir / reused) << "x";
  fs::last_write_time(dir / reused, fs::last_write_time(dir / live) - std::chrono::hours(24 * 365));
  const int raw = std::system(("cd '" + dir.string() + "' && '" + CONTACT2D_EXE +
                               "' simulate '" CONTACT2D_SCENES_DIR
                               "/box.toml' --duration 0.01 --csv out.csv >/dev/null 2>&1")
                                  .c_str());
  ASSERT_TRUE(WIFEXITED(raw));
  EXPECT_EQ(WEXITSTATUS(raw), 0);
  EXPECT_FALSE(fs::exists(dir / left)) << left << " is still there";
  EXPECT_FALSE(fs::exists(dir / reused)) << "a file older than the process with its PID";
  EXPECT_TRUE(fs::exists(dir / live));
  EXPECT_TRUE(fs::exists(dir / other));
  EXPECT_TRUE(fs::exists(dir / "out.csv"));
  fs::remove_all(dir);
}

const std::string kScenes = CONTACT2D_SCENES_DIR;

std::vector<Case> cases() {
  std::vector<Case> out = {
      // 2e7 steps: far longer than the wait for the file.
      {"simulate_sigint",
       {"simulate", kScenes + "/box.toml", "--csv", "out.csv", "--duration", "2000"},
       SIGINT},
      {"sweep_sigterm",
       {"sweep", kScenes + "/point_mass.toml", "--csv", "out.csv", "--plot", "out.png",
        "--duration", "200", "--quiet"},
       SIGTERM},
      {"simulate_sighup",
       {"simulate", kScenes + "/circle.toml", "--csv", "out.csv", "--duration", "2000"},
       SIGHUP},
  };
#ifdef CONTACT2D_WITH_MUJOCO
  // MuJoCo's side of compare: 5e6 mj_step calls.
  out.push_back({"compare_sigterm",
                 {"compare", kScenes + "/box.toml", "--csv", "out.csv", "--duration", "500"},
                 SIGTERM});
#endif
  return out;
}

INSTANTIATE_TEST_SUITE_P(Commands, Interrupt, ::testing::ValuesIn(cases()),
                         [](const auto& info) { return std::string(info.param.name); });

#ifdef CONTACT2D_WITH_MUJOCO
// An interrupt while gnuplot draws: gnuplot is killed (it writes the plot:
// left running, it would create the file after the clean-up removed it) and
// nothing is left, in the directory or in TMPDIR (gnuplot's messages were
// once collected in a $TMPDIR/contact2d_gnuplot_* file). The gnuplot here
// is a stand-in first on PATH that notes its PID and waits; a private
// TMPDIR. Before the fix the stand-in outlived the program and the file
// stayed.
TEST(InterruptDuringAPlot, KillsGnuplotAndLeavesNothing) {
  const fs::path root =
      fs::temp_directory_path() / ("contact2d_interrupt_gnuplot_" + std::to_string(::getpid()));
  fs::remove_all(root);
  const fs::path dir = root / "work", tmp = root / "tmp";
  for (const fs::path& d : {dir, tmp}) fs::create_directories(d);
  const fs::path mark = contact2d::test::write_stand_in(root, "gnuplot");
  const contact2d::test::Interrupted r = contact2d::test::interrupt_while_tool_runs(
      root, dir, mark, CONTACT2D_EXE,
      {"compare", CONTACT2D_SCENES_DIR "/box.toml", "--no-diagnosis", "--plot", "out.png",
       "--duration", "0.1"},
      {{"TMPDIR", tmp.string()}});
  ASSERT_TRUE(r.tool_started) << "gnuplot was not started";
  EXPECT_EQ(r.exit_status, 128 + SIGINT);
  EXPECT_FALSE(r.tool_outlived) << "gnuplot still ran after the program ended";
  EXPECT_TRUE(fs::is_empty(dir)) << "left behind: " << fs::directory_iterator(dir)->path();
  EXPECT_TRUE(fs::is_empty(tmp)) << "left behind: " << fs::directory_iterator(tmp)->path();
  fs::remove_all(root);
}
#endif

}  // namespace
