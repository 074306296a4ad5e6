// contact2d atlas (analysis/atlas.hpp, io/atlas_spec.hpp): the spec expands
// to the points it describes, bad fields are refused with their name and
// range, the same points give the same bytes whatever the sharding and
// thread count, and the merge refuses a missing or duplicated shard.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/atlas.hpp"
#include "core/input_error.hpp"
#include "io/atlas_spec.hpp"
#include "report/pages.hpp"
#include "support/files.hpp"

namespace contact2d::analysis {
namespace {

namespace fs = std::filesystem;

AtlasSpec parse(const std::string& text) { return parse_atlas_spec(text, "spec.toml", "."); }

using contact2d::test::read_file;

// The error message of parsing `text`, or "" when it parses.
std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const std::string kGrid = R"(
[atlas]
bodies = ["point_mass", "box"]
mappings = ["calibrated", "seed"]
duration = 0.5
[axes]
k = [1e4, 1e5, 1e6]
zeta = [0.2, 1.0]
mu = [0.0, 0.5]
dt = 1e-4
)";

TEST(AtlasSpec, GridExpandsToTheProductOfItsLists) {
  const AtlasSpec spec = parse(kGrid);
  // 2 bodies × 2 mappings × 1 damping law × 3 k × 2 ζ × 2 μ.
  EXPECT_EQ(atlas_point_count(spec), 48);
  // The last axis varies fastest: μ, then ζ, then k, then the mapping.
  const AtlasPoint p0 = atlas_point(spec, 0), p1 = atlas_point(spec, 1);
  const AtlasPoint p2 = atlas_point(spec, 2), p12 = atlas_point(spec, 12);
  EXPECT_EQ(p0.mu, 0.0);
  EXPECT_EQ(p1.mu, 0.5);
  EXPECT_EQ(p1.zeta, 0.2);
  EXPECT_EQ(p2.zeta, 1.0);
  EXPECT_EQ(p2.k, 1e4);
  EXPECT_EQ(p0.mapping, "calibrated");
  EXPECT_EQ(p12.mapping, "seed");
  EXPECT_EQ(p12.body, "point_mass");
  EXPECT_EQ(atlas_point(spec, 24).body, "box");
  // c follows from ζ with the body's mass: c = 2ζ√(k·m), m = 1 kg.
  EXPECT_DOUBLE_EQ(p2.c, 2.0 * 1.0 * std::sqrt(1e4 * 1.0));
  EXPECT_EQ(p0.scene.contact.damping, DampingLaw::KelvinVoigt);
  EXPECT_EQ(p0.scene.sim.duration, 0.5);
  // Every point is distinct.
  std::set<std::string> seen;
  for (long long i = 0; i < 48; ++i) {
    const AtlasPoint p = atlas_point(spec, i);
    seen.insert(p.body + p.mapping + std::to_string(p.k) + std::to_string(p.zeta) +
                std::to_string(p.mu));
  }
  EXPECT_EQ(seen.size(), 48u);
}

TEST(AtlasSpec, RandomSampleIsSeededAndSharedByTheMappings) {
  const AtlasSpec spec = parse(R"(
[atlas]
sample = "random"
bodies = ["box"]
mappings = ["calibrated", "exact"]
count = 20
seed = 7
[axes]
k = { min = 1e3, max = 1e6 }
zeta = { min = 0.1, max = 2 }
mu = [0, 0.5]
)");
  EXPECT_EQ(atlas_point_count(spec), 40);
  for (long long j = 0; j < 20; ++j) {
    const AtlasPoint a = atlas_point(spec, j), b = atlas_point(spec, 20 + j);
    EXPECT_EQ(a.mapping, "calibrated");
    EXPECT_EQ(b.mapping, "exact");
    EXPECT_EQ(a.k, b.k);  // the same sample under both mappings
    EXPECT_EQ(a.zeta, b.zeta);
    EXPECT_GE(a.k, 1e3);
    EXPECT_LE(a.k, 1e6);
    EXPECT_GE(a.zeta, 0.1);
    EXPECT_LE(a.zeta, 2.0);
    EXPECT_TRUE(a.mu == 0.0 || a.mu == 0.5);
  }
  EXPECT_NE(atlas_point(spec, 0).k, atlas_point(spec, 1).k);
  // Another seed, other samples.
  const AtlasSpec other = parse(R"(
[atlas]
sample = "random"
bodies = ["box"]
mappings = ["calibrated", "exact"]
count = 20
seed = 8
[axes]
k = { min = 1e3, max = 1e6 }
)");
  EXPECT_NE(atlas_point(other, 0).k, atlas_point(spec, 0).k);
}

TEST(AtlasSpec, BadFieldsAreNamedWithTheirRange) {
  const std::string head = "[atlas]\nbodies = [\"box\"]\nmappings = [\"calibrated\"]\n";
  struct Case {
    std::string text;
    std::vector<std::string> words;
  };
  const std::vector<Case> cases = {
      {head + "[axes]\nk = -1\n", {"axes.k", "(0, 1e12] N/m"}},
      {head + "[axes]\nk = [1e4, 0]\n", {"axes.k[1]", "(0, 1e12] N/m"}},
      {head + "[axes]\nmass = 0\n", {"axes.mass", "(0, 1e9] kg"}},
      {head + "[axes]\nmu = 200\n", {"axes.mu", "[0, 100]"}},
      {head + "[axes]\nmu_roll = -1\n", {"axes.mu_roll", "[0, 10] m"}},
      {head + "[axes]\ndt = 2\n", {"axes.dt", "(0, 1] s"}},
      {head + "[axes]\nzeta = 0.5\nc = 10\n", {"axes.zeta", "axes.c"}},
      {head + "[axes]\nbogus = 1\n", {"axes.bogus", "mass, k, zeta, c, mu, mu_roll, dt"}},
      {head + "[axes]\nk = { min = 1, max = 2 }\n", {"axes.k", "random"}},
      {head + "sample = \"sobol\"\n", {"atlas.sample", "grid", "random"}},
      {head + "sample = \"random\"\n", {"atlas.count", "required"}},
      {head + "sample = \"random\"\ncount = 0\n", {"atlas.count", "[1, 1e7]"}},
      {head + "duration = 0\n", {"atlas.duration", "(0, 1e4] s"}},
      {head + "converged_tol = 1e-3\n", {"atlas.converged_tol", "[1e-14, 1e-6]"}},
      {head + "integrator = \"explicit_euler\"\n", {"atlas.integrator", "MuJoCo"}},
      {head + "color = 1\n", {"atlas.color", "allowed here"}},
      {"[atlas]\nbodies = [\"cube\"]\nmappings = [\"calibrated\"]\n", {"atlas.bodies", "cube"}},
      {"[atlas]\nbodies = [\"box\"]\nmappings = [\"fancy\"]\n", {"atlas.mappings", "fancy"}},
      {"[atlas]\nmappings = [\"seed\"]\n", {"atlas.bodies", "required"}},
      {"[atlas]\nbodies = [\"box\"]\nmappings = [\"seed\"]\ndamping = [\"x\"]\n",
       {"atlas.damping", "kelvin_voigt"}},
      {head + "[axes]\nk = { min = 1e4, max = 1e3 }\n", {"axes.k"}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.text);
    const std::string message = error_of(c.text);
    ASSERT_FALSE(message.empty());
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(message.rfind("spec.toml", 0), 0u) << message;
    for (const std::string& w : c.words) EXPECT_NE(message.find(w), std::string::npos) << message;
  }
  // A random { min, max } range is accepted where a grid refuses it.
  EXPECT_EQ(error_of(head + "sample = \"random\"\ncount = 3\n[axes]\nk = { min = 1, max = 2 }\n"),
            "");
  // A combination out of the core's range is named with the point: c = 2ζ√(k·m) > 1e9.
  const AtlasSpec big = parse(head + "[axes]\nk = 1e12\nmass = 1e6\nzeta = 1000\n");
  try {
    atlas_point(big, 0);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("point 0"), std::string::npos) << m;
    EXPECT_NE(m.find("axes.zeta"), std::string::npos) << m;
    EXPECT_NE(m.find("[0, 1e9]"), std::string::npos) << m;
  }
}

TEST(AtlasShard, ParsesAndPartitions) {
  const Shard s = parse_shard("2/3");
  EXPECT_EQ(s.index, 2);
  EXPECT_EQ(s.count, 3);
  EXPECT_TRUE(s.holds(1));
  EXPECT_TRUE(s.holds(4));
  EXPECT_FALSE(s.holds(0));
  for (const char* bad : {"0/3", "4/3", "1/0", "a/b", "3", "1/2/3", "-1/2", ""})
    EXPECT_THROW(parse_shard(bad), InputError) << bad;
}

TEST(AtlasCsv, QuotedFieldsSplitBack) {
  EXPECT_EQ(split_csv_line("1,a,\"x, \"\"y\"\"\","),
            (std::vector<std::string>{"1", "a", "x, \"y\"", ""}));
}

// A tiny atlas: 2 bodies × 2 k × 2 μ × 2 Δt = 16 points of 0.3 s, thrown
// onto the ground; those at k = 1e9 diverge (ω·Δt = 3.2 and 32, past the
// semi-implicit limit).
const std::string kTiny = R"(
[atlas]
bodies = ["point_mass", "box"]
mappings = ["calibrated"]
duration = 0.3
converged_tol = 1e-9
[axes]
k = [1e4, 1e9]
zeta = 0.5
mu = [0.0, 0.5]
dt = [1e-4, 1e-3]
[initial]
y = 0.15
vx = 0.5
vy = -1.0
theta = 0.2
)";

class AtlasRun : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("contact2d_atlas_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string run(const AtlasSpec& spec, const std::string& name, const std::string& shard,
                  unsigned threads) {
    AtlasRunOptions options;
    options.shard = parse_shard(shard);
    options.threads = threads;
    const std::string out = (dir_ / name).string();
    run_atlas(spec, out, options);
    return out;
  }
  fs::path dir_;
};

TEST_F(AtlasRun, SameRowsWhateverTheShardingAndThreads) {
  const AtlasSpec spec = parse(kTiny);
  ASSERT_EQ(atlas_point_count(spec), 16);
  const std::string whole = run(spec, "whole", "1/1", 1);
  const std::string whole2 = run(spec, "whole2", "1/1", 2);
  const std::string s1 = run(spec, "s1", "1/3", 2);
  const std::string s2 = run(spec, "s2", "2/3", 1);
  const std::string s3 = run(spec, "s3", "3/3", 2);
  const std::string reference = read_file(fs::path(whole) / "points.csv");
  EXPECT_EQ(read_file(fs::path(whole2) / "points.csv"), reference);
  // Shards given in any order.
  const AtlasData merged = read_atlas_shards({s3, s1, s2});
  write_atlas_data(merged, (dir_ / "merged").string());
  EXPECT_EQ(read_file(dir_ / "merged" / "points.csv"), reference);
  // 16 rows and a header; every status is one of the three, and the
  // diverging points are rows, not a crash.
  ASSERT_EQ(merged.rows.size(), 16u);
  int diverged = 0, ok = 0;
  for (const AtlasRow& row : merged.rows) {
    if (row.status == "diverged") ++diverged;
    if (row.status == "ok") {
      ++ok;
      EXPECT_TRUE(std::isfinite(row.mujoco_conv_pos)) << row.line;
      EXPECT_TRUE(std::isfinite(row.ref_conv_pos)) << row.line;
      // The converged solution's own error is below what it measures.
      EXPECT_LT(row.converged_own_error, row.ref_conv_pos) << row.line;
    }
  }
  EXPECT_GT(diverged, 0);
  EXPECT_GT(ok, 0);
  // The summary and heat maps are drawn from the merged rows.
  AtlasSummary summary = summarize_atlas(merged);
  EXPECT_EQ(summary.points, 16);
  EXPECT_EQ(summary.groups.size(), 2u);
  draw_atlas_heatmaps(merged, summary, (dir_ / "merged").string());
  for (const AtlasGroup& g : summary.groups) {
    EXPECT_FALSE(g.heatmap.empty());
    EXPECT_TRUE(fs::exists(dir_ / "merged" / g.heatmap)) << g.heatmap;
  }
  const std::string md = report::atlas_summary_markdown(summary);
  EXPECT_NE(md.find("| point_mass | calibrated | kelvin_voigt | 8 |"), std::string::npos) << md;
  // The report's page: how it ran, then the same summary.
  const report::AtlasRunInfo info{"tiny.toml", 16, 2, 1.5, 0.01, 100.0};
  const std::string page = report::atlas_page(summary, info);
  EXPECT_EQ(page.rfind("# A small fidelity atlas\n", 0), 0u);
  EXPECT_NE(page.find("16 points in 1.5 s on 2 thread(s), 10 ms of CPU per point (100 points/s "
                      "per core)"),
            std::string::npos)
      << page;
  EXPECT_NE(page.find(md), std::string::npos);
}

TEST_F(AtlasRun, MergeRefusesAMissingOrDuplicatedShard) {
  const AtlasSpec spec = parse(R"(
[atlas]
bodies = ["point_mass"]
mappings = ["calibrated"]
duration = 0.05
converged_tol = 1e-9
[axes]
k = [1e4, 2e4, 4e4]
)");
  const std::string s1 = run(spec, "s1", "1/3", 1);
  const std::string s2 = run(spec, "s2", "2/3", 1);
  const std::string s3 = run(spec, "s3", "3/3", 1);
  try {
    read_atlas_shards({s1, s3});
    ADD_FAILURE() << "a missing shard was accepted";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("1 of 3 points missing (1)"), std::string::npos) << m;
    EXPECT_NE(m.find("shard 2/3 not given"), std::string::npos) << m;
  }
  try {
    read_atlas_shards({s1, s2, s3, s2});
    ADD_FAILURE() << "a duplicated shard was accepted";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("point 1 is in both"), std::string::npos) << m;
  }
  // A shard of another spec.
  const AtlasSpec other = parse(R"(
[atlas]
bodies = ["point_mass"]
mappings = ["seed"]
duration = 0.05
converged_tol = 1e-9
[axes]
k = [1e4, 2e4, 4e4]
)");
  const std::string o2 = run(other, "o2", "2/3", 1);
  EXPECT_THROW(read_atlas_shards({s1, o2, s3}), InputError);
  // An unfinished run (no shard.txt) is refused.
  fs::remove(fs::path(s3) / "shard.txt");
  EXPECT_THROW(read_atlas_shards({s1, s2, s3}), InputError);
  // A damaged points.csv (a row lost) is refused.
  {
    std::ofstream out(fs::path(s2) / "points.csv", std::ios::trunc);
    out << atlas_csv_header() << "\n";
  }
  EXPECT_THROW(read_atlas_shards({s1, s2}), InputError);
}

// The program: a bad spec is one line on stderr and exit status 2, with no
// output directory made; a good one writes the three files and says how
// fast it went.
TEST_F(AtlasRun, CommandLineExitStatusAndFiles) {
  const fs::path bad = dir_ / "bad.toml";
  {
    std::ofstream out(bad);
    out << "[atlas]\nbodies = [\"box\"]\nmappings = [\"calibrated\"]\n[axes]\nzeta = -1\n";
  }
  const fs::path out_dir = dir_ / "out";
  const std::string exe = CONTACT2D_EXE;
  const std::string err = (dir_ / "stderr").string();
  int status = std::system(
      (exe + " atlas " + bad.string() + " --out " + out_dir.string() + " 2>" + err).c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
  const std::string message = read_file(err);
  EXPECT_EQ(message, "contact2d: " + bad.string() +
                         ": axes.zeta = -1 is out of range: must be in [0, 1e3]\n");
  EXPECT_FALSE(fs::exists(out_dir));
  status = std::system((exe + " atlas " + bad.string() + " --shard 3/2 2>" + err).c_str());
  EXPECT_EQ(WEXITSTATUS(status), 2);
  EXPECT_NE(read_file(err).find("--shard 3/2"), std::string::npos);

  const fs::path good = dir_ / "good.toml";
  {
    std::ofstream out(good);
    out << "[atlas]\nbodies = [\"point_mass\"]\nmappings = [\"calibrated\"]\nduration = "
           "0.05\n[axes]\nk = [1e4, 1e5]\n";
  }
  const std::string log = (dir_ / "stdout").string();
  status = std::system((exe + " atlas " + good.string() + " --out " + out_dir.string() +
                        " --quiet >" + log + " 2>" + err)
                           .c_str());
  EXPECT_EQ(WEXITSTATUS(status), 0) << read_file(err);
  EXPECT_EQ(read_file(err), "");
  EXPECT_NE(read_file(log).find("2 of 2 points (2 ok, 0 diverged, 0 failed)"), std::string::npos)
      << read_file(log);
  EXPECT_NE(read_file(log).find("points/s per core"), std::string::npos);
  for (const char* file : {"points.csv", "times.csv", "shard.txt"})
    EXPECT_TRUE(fs::exists(out_dir / file)) << file;
  // Nothing temporary is left beside them.
  int files = 0;
  for (const auto& entry : fs::directory_iterator(out_dir)) {
    (void)entry;
    ++files;
  }
  EXPECT_EQ(files, 3);
}

// SIGTERM in the middle of a run: exit status 143 and no file at all
// (points.csv and times.csv are temporaries until the last point).
TEST_F(AtlasRun, InterruptedRunLeavesNoFile) {
  const fs::path spec = dir_ / "long.toml";
  {
    // 48 points of 2 s: over a second of work on two fast cores.
    std::ofstream out(spec);
    out << "[atlas]\nbodies = [\"point_mass\", \"box\", \"tshape\", \"circle\"]\n"
           "mappings = [\"calibrated\"]\nduration = 2.0\n[axes]\nk = [1e4, 1e5, 1e6]\n"
           "zeta = [0.2, 1.0]\nmu = [0.0, 0.5]\n[initial]\ny = 0.6\nvx = 0.5\n";
  }
  const fs::path out_dir = dir_ / "out";
  const std::string script =
      std::string(CONTACT2D_EXE) + " atlas " + spec.string() + " --out " + out_dir.string() +
      " --quiet 2>/dev/null & pid=$!; sleep 0.3; kill -TERM $pid; wait $pid; "
      "exit $?";
  const int status = std::system(("sh -c '" + script + "'").c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 143);
  // (The directory exists unless the signal came before the points were
  // checked; either way it holds nothing.)
  if (fs::exists(out_dir)) {
    EXPECT_TRUE(fs::is_empty(out_dir));
  }
}

// Two shards into one --out: while the first runs (stopped with SIGSTOP once
// it holds the directory's lock, so that it cannot finish meanwhile), a
// second one exits 2 with one line naming --out and the first one's PID,
// and touches nothing; the first then finishes with all its rows and
// removes the lock file.
TEST_F(AtlasRun, ASecondRunIntoALockedDirectoryExits2AndTheFirstSurvives) {
  const fs::path spec = dir_ / "long.toml";
  {
    std::ofstream out(spec);  // 48 points of 2 s: seconds of work
    out << "[atlas]\nbodies = [\"point_mass\", \"box\", \"tshape\", \"circle\"]\n"
           "mappings = [\"calibrated\"]\nduration = 2.0\n[axes]\nk = [1e4, 1e5, 1e6]\n"
           "zeta = [0.2, 1.0]\nmu = [0.0, 0.5]\n[initial]\ny = 0.6\nvx = 0.5\n";
  }
  const fs::path out_dir = dir_ / "out";
  const fs::path lock = out_dir / ".contact2d.lock";
  const pid_t first = ::fork();
  ASSERT_GE(first, 0);
  if (first == 0) {
    if (!std::freopen("/dev/null", "w", stdout) || !std::freopen("/dev/null", "w", stderr))
      ::_exit(121);
    ::execl(CONTACT2D_EXE, CONTACT2D_EXE, "atlas", spec.c_str(), "--out", out_dir.c_str(),
            "--threads", "1", "--quiet", static_cast<char*>(nullptr));
    ::_exit(122);
  }
  // The lock is held once the file names the first run's PID (written after
  // flock succeeded). No deadline: the first run ending first is a failure.
  const std::string pid = std::to_string(first);
  int status = 0;
  bool locked = false;
  while (!locked) {
    locked = read_file(lock) == pid;
    if (!locked && ::waitpid(first, &status, WNOHANG) == first) break;
    if (!locked) ::usleep(2000);
  }
  ASSERT_TRUE(locked) << "the first run ended before it was seen holding the lock";
  ::kill(first, SIGSTOP);
  const std::string err = (dir_ / "second.err").string();
  const int second = std::system((std::string(CONTACT2D_EXE) + " atlas " + spec.string() +
                                  " --out " + out_dir.string() + " --quiet >/dev/null 2>" + err)
                                     .c_str());
  const std::string text = read_file(err);
  ::kill(first, SIGCONT);
  ASSERT_EQ(::waitpid(first, &status, 0), first);
  EXPECT_EQ(WEXITSTATUS(second), 2) << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << text;
  EXPECT_NE(text.find("--out " + out_dir.string() + ": another contact2d (pid " + pid +
                      ") is writing into this directory"),
            std::string::npos)
      << text;
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  const std::string points = read_file(out_dir / "points.csv");
  EXPECT_EQ(std::count(points.begin(), points.end(), '\n'), 49) << "header and 48 rows";
  EXPECT_TRUE(fs::exists(out_dir / "shard.txt"));
  EXPECT_FALSE(fs::exists(lock));
}

// A heat map's colours: decades from the goal on ± whole decades covering
// every cell (at least one), so that a map whose cells lie within a decade
// of each other still spans its whole palette; values that are not finite
// (an exact 0's log) do not stretch it.
TEST(AtlasHeatmaps, ColourSpanCoversEveryCellInWholeDecades) {
  EXPECT_EQ(atlas_colour_span({}), 1.0);
  EXPECT_EQ(atlas_colour_span({0.3, -0.2}), 1.0);
  EXPECT_EQ(atlas_colour_span({-7.5, 1.5}), 8.0);  // 3e-13 and 3e-2 from 1e-5 and 1e-3
  EXPECT_EQ(atlas_colour_span({1.2, -std::numeric_limits<double>::infinity()}), 2.0);
  EXPECT_EQ(atlas_colour_span({std::nan(""), 2.0}), 2.0);
}

}  // namespace
}  // namespace contact2d::analysis
