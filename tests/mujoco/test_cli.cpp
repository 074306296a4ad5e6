// The MuJoCo subcommands through the real program: exit status, one-line
// messages, files written only on success, and the machine-readable output.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "analysis/comparison.hpp"
#include "mj_test_util.hpp"
#include "mujoco/mjcf.hpp"
#include "support/needs.hpp"

namespace contact2d {
namespace {

namespace fs = std::filesystem;

struct Result {
  int status = -1;
  std::string out;
  std::string err;
};

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("contact2d_mj_cli_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }

  // Runs contact2d with the arguments (already quoted), in the test's directory.
  Result run(const std::string& args) const {
    const std::string out = (dir_ / "stdout").string(), err = (dir_ / "stderr").string();
    const std::string command = "cd '" + dir_.string() + "' && '" CONTACT2D_BINARY "' " + args +
                                " >'" + out + "' 2>'" + err + "'";
    const int raw = std::system(command.c_str());
    return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, read(out), read(err)};
  }

  // Files in the test directory other than the scenes and captured output.
  std::vector<std::string> leftovers() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) {
      const std::string name = e.path().filename().string();
      if (name != "stdout" && name != "stderr" && e.path().extension() != ".toml")
        names.push_back(name);
    }
    return names;
  }

  fs::path dir_;
};

const char* kBox =
    "scene = \"box\"\n[contact]\nk = 1e4\nc = 200\nmu = 0.5\ndamping = \"kelvin_voigt\"\n"
    "[initial]\ny = 0.5\ntheta = 0.3\n[sim]\ndt = 1e-4\nduration = 0.5\n";

void expect_one_line(const std::string& err, const std::string& needle) {
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_NE(err.find(needle), std::string::npos) << err;
}

TEST_F(Cli, GenerateWritesTheSameBytesAsTheLibrary) {
  write("box.toml", kBox);
  const Result r = run("generate box.toml --mapping exact -o box.xml");
  ASSERT_EQ(r.status, 0) << r.err;
  mujoco::MjcfOptions options;
  options.mapping = mujoco::Mapping::Exact;
  options.source = "box.toml";
  EXPECT_EQ(read(dir_ / "box.xml"), mujoco::generate_mjcf(test::scene_from(kBox), options).xml);
  EXPECT_EQ(leftovers(), std::vector<std::string>{"box.xml"});
}

// m = 1e-16 kg is a valid 2D scene, but MuJoCo's compiler rejects bodies
// lighter than mjMINVAL = 1e-15.
TEST_F(Cli, SceneMujocoCannotLoadIsBadInput) {
  write("light.toml", "scene = \"point_mass\"\n[body]\nmass = 1e-16\n");
  for (const std::string args :
       {"generate light.toml -o light.xml", "compare light.toml --csv both.csv",
        "simulate light.toml --engine mujoco --csv one.csv"}) {
    const Result r = run(args);
    EXPECT_EQ(r.status, 2) << args;
    expect_one_line(r.err,
                    "MuJoCo cannot load the model: Error: mass and inertia of moving bodies");
    EXPECT_TRUE(leftovers().empty()) << args;
  }
}

// A disc of 1 g sunk to its centre into a 1e12 N/m ground: the compiler's
// test step computes an acceleration of k·R/m = 1e17 m/s², MuJoCo flags it
// ("huge value in QACC") and mj_loadXML returns the model with a warning.
TEST_F(Cli, SceneMujocoWarnsOnIsBadInput) {
  write("hard.toml",
        "scene = \"circle\"\n[body]\nmass = 1e-3\n[contact]\nk = 1e12\nc = 0\n[initial]\ny = 0\n"
        "[sim]\ndt = 1e-3\nduration = 0.01\n");
  const Result r = run("generate hard.toml -o hard.xml");
  EXPECT_EQ(r.status, 2);
  expect_one_line(r.err,
                  "hard.toml (its generated MJCF): MuJoCo warns while loading the model: Nan, Inf "
                  "or huge value in QACC");
  EXPECT_TRUE(leftovers().empty());
}

// Obstacles run on both engines: a box sliding at 6 m/s into a
// wall whose face is at x = 1.9 m stops against it on both (centre within
// the half-width 0.2 m plus the deepest penetration, 1.7 cm, of the face;
// without the wall μ = 0.5 would let it slide to x = 3.7 m). compare has no
// converged reference for it and says so, measuring ref <-> MuJoCo only.
TEST_F(Cli, ObstacleScenesRunOnMujoco) {
  std::string box = kBox;
  box.replace(box.find("theta = 0.3\n"), 12, "theta = 0.3\nvx = 6\n");
  write("wall.toml",
        box + "[[obstacle]]\ntype = \"box\"\nx = 2\ny = 0.5\nwidth = 0.2\nheight = 1\n");
  for (const std::string engine : {"ref", "mujoco"}) {
    const Result r = run("simulate wall.toml --engine " + engine);
    ASSERT_EQ(r.status, 0) << r.err;
    const size_t at = r.out.find("final x = ");
    ASSERT_NE(at, std::string::npos) << r.out;
    const double x = std::stod(r.out.substr(at + 10));
    EXPECT_GT(x, 1.6) << engine << ": the box reached the wall";
    EXPECT_LT(x, 1.72) << engine << ": and stopped at it";
  }
  const Result r = run("compare wall.toml");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("converged solution: not available (static obstacles"), std::string::npos)
      << r.out;
}

TEST_F(Cli, ExplicitEulerIsBadInputForMujoco) {
  write("box.toml", kBox);
  for (const std::string args : {"generate box.toml --integrator explicit_euler",
                                 "compare box.toml --integrator explicit_euler",
                                 "simulate box.toml --engine mujoco --integrator explicit_euler"}) {
    const Result r = run(args);
    EXPECT_EQ(r.status, 2) << args;
    expect_one_line(r.err, "sim.integrator = explicit_euler has no MuJoCo 2.2 counterpart");
  }
}

double json_number(const std::string& json, const std::string& key) {
  const std::string needle = "\"" + key + "\": ";
  const size_t at = json.find(needle);
  if (at == std::string::npos) {
    ADD_FAILURE() << "no number " << key << " in " << json;
    return NAN;
  }
  return std::strtod(json.c_str() + at + needle.size(), nullptr);
}

TEST_F(Cli, CompareJsonHasTheAgreedKeysAndTheLibrarysNumbers) {
  write("box.toml", kBox);
  const Result r = run("compare box.toml --json --mapping calibrated");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1);
  for (const char* key :
       {"\"scene\": \"box.toml\"", "\"mapping\": \"calibrated\"",
        "\"integrators\": {\"ref\": \"semi_implicit_euler\", \"mujoco\": \"Euler\"}"}) {
    EXPECT_NE(r.out.find(key), std::string::npos) << key << " in " << r.out;
  }
  // The JSON carries 10 significant digits (format_number(v, 10) in
  // cli/cmd_compare.cpp), so a number read back differs from the library's
  // by at most half a unit in the 10th digit, 5e-10 relative: tolerance
  // 1e-9 relative, twice that, and far below any real difference between
  // the program's run and the library's.
  const test::BothRuns runs = test::run_both(test::scene_from(kBox));
  EXPECT_NEAR(json_number(r.out, "max_pos_err"), runs.errors.max_pos, 1e-9 * runs.errors.max_pos);
  EXPECT_NEAR(json_number(r.out, "rms_pos_err"), runs.errors.rms_pos, 1e-9 * runs.errors.rms_pos);
  EXPECT_NEAR(json_number(r.out, "max_angle_err"), runs.errors.max_angle,
              1e-9 * runs.errors.max_angle);
  EXPECT_EQ(json_number(r.out, "dt"), 1e-4);
  EXPECT_GT(json_number(r.out, "ref_seconds"), 0.0);
  EXPECT_GT(json_number(r.out, "mujoco_seconds"), 0.0);
  // The three-way keys: the same runs against the converged solution at the
  // default tolerance, to the JSON's 10 digits.
  EXPECT_EQ(json_number(r.out, "converged_tol"), 1e-12);
  const analysis::ThreeWay three =
      analysis::three_way(test::scene_from(kBox), runs.ref, runs.mj.trajectory, 1e-12);
  for (const auto& [key, value] :
       {std::pair{"ref_vs_converged_max_pos_err", three.ref_vs_converged.max_pos},
        std::pair{"mujoco_vs_converged_max_pos_err", three.mujoco_vs_converged.max_pos},
        std::pair{"ref_vs_converged_max_angle_err", three.ref_vs_converged.max_angle},
        std::pair{"mujoco_vs_converged_max_angle_err", three.mujoco_vs_converged.max_angle},
        std::pair{"ref_vs_mujoco_max_pos_err", three.ref_vs_mujoco.max_pos}}) {
    EXPECT_NEAR(json_number(r.out, key), value, 1e-9 * value) << key;
  }
  EXPECT_NE(r.out.find("\"diagnosis\": ["), std::string::npos);
}

TEST_F(Cli, CompareCsvHasBothTrajectoriesAtTheSameTimes) {
  write("box.toml", kBox);
  const Result r = run("compare box.toml --csv both.csv");
  ASSERT_EQ(r.status, 0) << r.err;
  std::istringstream csv(read(dir_ / "both.csv"));
  std::string header, line;
  std::getline(csv, header);
  EXPECT_EQ(header,
            "t,x_ref,y_ref,theta_ref,vx_ref,vy_ref,omega_ref,x_mujoco,y_mujoco,theta_mujoco,vx_"
            "mujoco,vy_mujoco,"
            "omega_mujoco,x_converged,y_converged,theta_converged,vx_converged,vy_converged,"
            "omega_converged");
  int rows = 0;
  while (std::getline(csv, line)) ++rows;
  EXPECT_EQ(rows, 501);  // t = 0 and every 1e-3 s over 0.5 s
}

// --engines: one column pair per engine in the table, six CSV columns per
// engine named by its key, and options either in the names or as flags.
TEST_F(Cli, CompareTakesAListOfEngines) {
  write("box.toml", kBox);
  const Result r =
      run("compare box.toml --engines mujoco:exact,mujoco:calibrated:boxes --csv all.csv "
          "--no-diagnosis --allow-nonphysical");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* column : {"ref <-> mujoco:exact", "mujoco:exact <-> converged",
                             "ref <-> mujoco:calibrated:boxes", "energy mujoco:calibrated:boxes"})
    EXPECT_NE(r.out.find(column), std::string::npos) << column << " in " << r.out;
  std::istringstream csv(read(dir_ / "all.csv"));
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(std::count(header.begin(), header.end(), ','), 6 * 4);  // t + 3 engines + converged
  EXPECT_NE(header.find(",x_mujoco_exact,"), std::string::npos) << header;
  EXPECT_NE(header.find(",omega_mujoco_calibrated_boxes,"), std::string::npos) << header;
  const Result both = run("compare box.toml --engines mujoco:exact --mapping seed");
  EXPECT_EQ(both.status, 2);
  EXPECT_NE(both.err.find("--mapping seed: the engine's name mujoco:exact gives mapping exact"),
            std::string::npos)
      << both.err;
  EXPECT_EQ(leftovers(), std::vector<std::string>{"all.csv"});
}

TEST_F(Cli, ComparePlotWritesAPng) {
  CONTACT2D_NEEDS(std::system("command -v gnuplot >/dev/null 2>&1") == 0,
                  "gnuplot (gnuplot-nox) not installed");
  write("box.toml", kBox);
  const Result r = run("compare box.toml --plot box.png");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(read(dir_ / "box.png").substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(leftovers(), std::vector<std::string>{"box.png"});
}

TEST_F(Cli, SimulateWithMujocoWritesTheReferencesSampleTimes) {
  write("box.toml", kBox);
  const Result mj = run("simulate box.toml --engine mujoco --csv mj.csv");
  const Result ref = run("simulate box.toml --engine ref --csv ref.csv");
  ASSERT_EQ(mj.status, 0) << mj.err;
  ASSERT_EQ(ref.status, 0) << ref.err;
  std::istringstream a(read(dir_ / "mj.csv")), b(read(dir_ / "ref.csv"));
  std::string la, lb;
  int rows = 0;
  while (std::getline(a, la) && std::getline(b, lb)) {
    EXPECT_EQ(la.substr(0, la.find(',')), lb.substr(0, lb.find(',')));  // same t column
    ++rows;
  }
  EXPECT_EQ(rows, 502);  // header + 501 samples
}

// k = 1e8 N/m on 1 kg at dt = 1e-3: ω·Δt = 10, far past semi-implicit
// Euler's limit; both engines blow up and compare reports it (status 3).
TEST_F(Cli, CompareReportsDivergence) {
  write("stiff.toml",
        "scene = \"point_mass\"\n[contact]\nk = 1e8\nc = 0\ndamping = "
        "\"kelvin_voigt\"\n[initial]\ny = 0.06\n"
        "[sim]\ndt = 1e-3\nduration = 1\n");
  const Result r = run("compare stiff.toml --mapping calibrated --csv both.csv");
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_NE(r.err.find("diverged"), std::string::npos) << r.err;
  EXPECT_TRUE(leftovers().empty());
}

}  // namespace
}  // namespace contact2d
