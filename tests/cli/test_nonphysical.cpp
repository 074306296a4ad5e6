// Runs that stop being physics below the divergence rule, through the real
// program: a body that ends inside the ground fails (exit 3, one line, no
// file) unless --allow-nonphysical keeps it with one warning line; explicit
// Euler's own energy gain in free flight is within its allowance. (The
// failing cases without the flag are also in the bad-input matrix:
// bad_inputs/nonphysical_*.toml.)
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "support/files.hpp"

namespace fs = std::filesystem;

namespace {

using contact2d::test::read_file;

struct Ran {
  int status = -1;
  std::string out, err;
};

Ran run_in(const fs::path& dir, const std::string& args) {
  const fs::path out = dir.string() + ".out", err = dir.string() + ".err";
  const int raw = std::system(("cd '" + dir.string() + "' && '" + CONTACT2D_EXE + "' " + args +
                               " >'" + out.string() + "' 2>'" + err.string() + "'")
                                  .c_str());
  Ran r{WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, read_file(out), read_file(err)};
  fs::remove(out);
  fs::remove(err);
  return r;
}

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() /
                       ("contact2d_nonphysical_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

size_t lines(const std::string& text) {
  return static_cast<size_t>(std::count(text.begin(), text.end(), '\n'));
}

const std::string kSunk = CONTACT2D_BAD_INPUTS_DIR "/nonphysical_sunk.toml";

TEST(Nonphysical, AllowNonphysicalKeepsTheRunWithOneWarningLine) {
  const fs::path dir = fresh_dir("allow");
  const Ran r = run_in(dir, "simulate '" + kSunk + "' --csv out.csv --allow-nonphysical");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("warning: not physics, kept (--allow-nonphysical): the run ended"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(fs::exists(dir / "out.csv"));
  fs::remove_all(dir);
}

TEST(Nonphysical, WithoutTheFlagTheSameRunFailsAndWritesNothing) {
  const fs::path dir = fresh_dir("fail");
  const Ran r = run_in(dir, "simulate '" + kSunk + "' --csv out.csv");
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("not physics: the run ended"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
}

// 1000 kg falling for 2 s from 100 m, never touching, explicit Euler at
// Δt = 0.01 s: it gains exactly ½·m·g²·Δt² = 4.81 J per step, 962 J over the
// 200 steps. The contact's own allowance (ω·Δt = 3.2e-4 on k = 1 N/m) is
// only 310 J of it: without the free-flight term the run would be flagged,
// and nothing touched.
TEST(Nonphysical, ExplicitEulerInFreeFlightIsWithinItsAllowance) {
  const fs::path dir = fresh_dir("flight");
  std::ofstream(dir / "flight.toml")
      << "scene = \"point_mass\"\n[body]\nmass = 1e3\nhalf_height = 0.05\n[contact]\nk = 1\n"
         "[initial]\ny = 100\n[sim]\ndt = 0.01\nduration = 2\nintegrator = \"explicit_euler\"\n";
  const Ran r = run_in(dir, "simulate flight.toml");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_NE(r.out.find("largest rise 962 J"), std::string::npos) << r.out;
  fs::remove_all(dir);
}

#ifdef CONTACT2D_WITH_MUJOCO
TEST(Nonphysical, CompareFailsWhenAnEngineEndsInsideTheGround) {
  const fs::path dir = fresh_dir("compare");
  const Ran r = run_in(dir, "compare '" + kSunk + "' --no-diagnosis --csv cmp.csv");
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_NE(r.err.find(": ref not physics: the run ended"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_empty(dir));
  const Ran kept =
      run_in(dir, "compare '" + kSunk + "' --no-diagnosis --csv cmp.csv --allow-nonphysical");
  EXPECT_EQ(kept.status, 0) << kept.err;
  EXPECT_NE(kept.err.find(": ref warning: not physics, kept"), std::string::npos) << kept.err;
  EXPECT_TRUE(fs::exists(dir / "cmp.csv"));
  fs::remove_all(dir);
}
#endif

}  // namespace
