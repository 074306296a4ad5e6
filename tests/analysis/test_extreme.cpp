// The extreme-case scenes (validation/scenes/extreme/*.toml) through the real
// contact2d program. Each file states its expected outcome in comment lines
// of the form "# expect: …"; this test runs `contact2d simulate FILE --engine
// ref --csv OUT` and checks every one of them, and that no output (stdout,
// stderr, CSV) ever holds a NaN (nor the CSV an infinity).
//
// Expectations (every number is the file's own claim, derived there):
//   exit N                          exit status: 0 ran, 3 diverged
//   diagnostic "TEXT"               stderr holds TEXT (exit 3)
//   final COL in [A, B]             last CSV row, column COL (t,x,y,theta,vx,vy,omega)
//   final |COL| <= V, final COL >= V
//   [after T:] max COL <= V         over rows with t ≥ T (|COL| for the magnitude)
//   [after T:] range COL <= V       max − min over those rows (drift, creep)
//   [after T:] sign changes COL <= N   sign flips among nonzero values (chatter)
//   penetration <= V                deepest contact point over all rows
//   max energy ratio <= V           max over rows of E(t)/E(0), E = core energy()
// An unknown expectation fails the test, and a file that runs (exit 0) must
// state at least one expectation about its trajectory, so that no scene
// passes by saying nothing.
//
// When contact2d was built with MuJoCo, every scene also runs with
// --engine mujoco: there only the universal promises are checked (a clean
// exit status 0, 2 or 3 with a message, and no NaN anywhere), since MuJoCo's
// model is not the reference's and its outcome on these cases is a finding,
// not a specification.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "core/dynamics.hpp"
#include "io/scene_file.hpp"
#include "support/needs.hpp"

namespace fs = std::filesystem;

namespace contact2d {
namespace {

std::vector<std::string> extreme_files() {
  std::vector<std::string> files;
  const fs::path dir = fs::path(CONTACT2D_SCENES_DIR) / "extreme";
  if (fs::exists(dir)) {
    for (const auto& entry : fs::directory_iterator(dir)) {
      if (entry.path().extension() == ".toml") files.push_back(entry.path().string());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct ProgramRun {
  int status = -1;
  std::string out, err, csv;
  bool csv_written = false;
};

ProgramRun run_program(const std::string& scene, const std::string& engine) {
  const fs::path tmp =
      fs::temp_directory_path() /
      ("contact2d_extreme_" + std::to_string(::getpid()) + "_" + fs::path(scene).stem().string());
  const fs::path out = tmp.string() + ".out", err = tmp.string() + ".err",
                 csv = tmp.string() + ".csv";
  fs::remove(csv);
  const std::string cmd = std::string("'") + CONTACT2D_EXE + "' simulate '" + scene +
                          "' --engine " + engine + " --csv '" + csv.string() + "' >'" +
                          out.string() + "' 2>'" + err.string() + "'";
  const int raw = std::system(cmd.c_str());
  ProgramRun run;
  run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  run.out = read_file(out);
  run.err = read_file(err);
  run.csv_written = fs::exists(csv);
  if (run.csv_written) run.csv = read_file(csv);
  fs::remove(out);
  fs::remove(err);
  fs::remove(csv);
  return run;
}

// "nan" (and, for numeric output, "inf") as a token, any case ("-nan",
// "NaN", "inf"; not "info"). Messages may say that a limit is infinite
// (implicit Euler's), so only the CSV is held to finite numbers throughout.
bool has_nan(const std::string& text) {
  static const std::regex token(R"((^|[^A-Za-z])nan([^A-Za-z]|$))", std::regex::icase);
  return std::regex_search(text, token);
}
bool has_non_finite(const std::string& text) {
  static const std::regex token(R"((^|[^A-Za-z])(nan|inf)([^A-Za-z]|$))", std::regex::icase);
  return std::regex_search(text, token);
}

struct Table {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
  int column(const std::string& name) const {
    const auto it = std::find(columns.begin(), columns.end(), name);
    return it == columns.end() ? -1 : static_cast<int>(it - columns.begin());
  }
};

Table parse_csv(const std::string& text) {
  Table table;
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  std::stringstream header(line);
  for (std::string field; std::getline(header, field, ',');) table.columns.push_back(field);
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream fields(line);
    for (std::string field; std::getline(fields, field, ',');) row.push_back(std::stod(field));
    table.rows.push_back(row);
  }
  return table;
}

State state_of(const Table& t, const std::vector<double>& row) {
  State s;
  s.q = Vec3(row[t.column("x")], row[t.column("y")], row[t.column("theta")]);
  s.v = Vec3(row[t.column("vx")], row[t.column("vy")], row[t.column("omega")]);
  return s;
}

class ExtremeScene : public ::testing::TestWithParam<std::string> {};

TEST_P(ExtremeScene, MeetsItsStatedExpectations) {
  const std::string path = GetParam();
  const std::string text = read_file(path);
  std::vector<std::string> expectations;
  {
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
      const std::string prefix = "# expect:";
      if (line.rfind(prefix, 0) == 0) expectations.push_back(line.substr(prefix.size() + 1));
    }
  }
  std::smatch m;
  int expected_status = -1;
  for (const std::string& e : expectations) {
    if (std::regex_match(e, m, std::regex(R"(exit (\d+))"))) expected_status = std::stoi(m[1]);
  }
  ASSERT_TRUE(expected_status == 0 || expected_status == 3)
      << path << ": needs '# expect: exit 0' or 'exit 3'";

  const ProgramRun run = run_program(path, "ref");
  EXPECT_EQ(run.status, expected_status) << run.out << run.err;
  EXPECT_FALSE(has_nan(run.out)) << run.out;
  EXPECT_FALSE(has_nan(run.err)) << run.err;
  EXPECT_FALSE(has_non_finite(run.csv)) << "NaN or inf in the CSV";
  if (expected_status == 3) {
    EXPECT_NE(run.err.find("simulation diverged"), std::string::npos) << run.err;
    EXPECT_FALSE(run.csv_written) << "a diverged run must leave no CSV";
  } else {
    ASSERT_TRUE(run.csv_written) << run.err;
  }

  const Scene scene = load_scene(path);
  const Model model = make_model(scene);
  const Table table = run.csv_written ? parse_csv(run.csv) : Table{};
  if (run.csv_written) {
    ASSERT_FALSE(table.rows.empty());
  }
  auto rows_after = [&](double t0) {
    std::vector<const std::vector<double>*> out;
    for (const auto& row : table.rows) {
      if (row[0] >= t0) out.push_back(&row);
    }
    return out;
  };
  auto column = [&](const std::string& name) {
    const int c = table.column(name);
    if (c < 0) ADD_FAILURE() << "unknown column " << name;
    return std::max(c, 0);
  };
  const std::string num = R"(([-+0-9.eE]+))";
  const std::string after = R"((?:after ([-+0-9.eE]+): )?)";
  int trajectory_checks = 0;
  for (const std::string& e : expectations) {
    SCOPED_TRACE(path + ": expect: " + e);
    if (std::regex_match(e, m, std::regex(R"(exit (\d+))"))) continue;
    if (std::regex_match(e, m, std::regex(R"x(diagnostic "(.*)")x"))) {
      EXPECT_NE(run.err.find(m[1].str()), std::string::npos) << run.err;
      continue;
    }
    if (!run.csv_written) {
      ADD_FAILURE() << "a trajectory expectation on a run without a CSV";
      continue;
    }
    ++trajectory_checks;
    const std::vector<double>& last = table.rows.back();
    if (std::regex_match(e, m, std::regex(R"(final (\w+) in \[)" + num + ", " + num + R"(\])"))) {
      const double v = last[column(m[1])];
      EXPECT_GE(v, std::stod(m[2]));
      EXPECT_LE(v, std::stod(m[3]));
    } else if (std::regex_match(e, m, std::regex(R"(final \|(\w+)\| <= )" + num))) {
      EXPECT_LE(std::abs(last[column(m[1])]), std::stod(m[2]));
    } else if (std::regex_match(e, m, std::regex(R"(final (\w+) >= )" + num))) {
      EXPECT_GE(last[column(m[1])], std::stod(m[2]));
    } else if (std::regex_match(e, m, std::regex(after + R"(max (\|?)(\w+)\|? <= )" + num))) {
      const double t0 = m[1].matched ? std::stod(m[1]) : -INFINITY;
      const bool magnitude = !m[2].str().empty();
      const int c = column(m[3]);
      double worst = -INFINITY;
      for (const auto* row : rows_after(t0))
        worst = std::max(worst, magnitude ? std::abs((*row)[c]) : (*row)[c]);
      EXPECT_LE(worst, std::stod(m[4]));
    } else if (std::regex_match(e, m, std::regex(after + R"(range (\w+) <= )" + num))) {
      const double t0 = m[1].matched ? std::stod(m[1]) : -INFINITY;
      const int c = column(m[2]);
      double lo = INFINITY, hi = -INFINITY;
      for (const auto* row : rows_after(t0)) {
        lo = std::min(lo, (*row)[c]);
        hi = std::max(hi, (*row)[c]);
      }
      EXPECT_LE(hi - lo, std::stod(m[3]));
    } else if (std::regex_match(e, m, std::regex(after + R"(sign changes (\w+) <= (\d+))"))) {
      const double t0 = m[1].matched ? std::stod(m[1]) : -INFINITY;
      const int c = column(m[2]);
      int changes = 0;
      double previous = 0.0;
      for (const auto* row : rows_after(t0)) {
        const double v = (*row)[c];
        if (v == 0.0) continue;
        if (previous != 0.0 && (v > 0.0) != (previous > 0.0)) ++changes;
        previous = v;
      }
      EXPECT_LE(changes, std::stoi(m[3]));
    } else if (std::regex_match(e, m, std::regex(R"(penetration <= )" + num))) {
      double deepest = 0.0;
      for (const auto& row : table.rows)
        deepest = std::max(deepest, max_penetration(model, state_of(table, row).q));
      EXPECT_LE(deepest, std::stod(m[1]));
    } else if (std::regex_match(e, m, std::regex(R"(max energy ratio <= )" + num))) {
      const double e0 = energy(model, state_of(table, table.rows.front()));
      double worst = -INFINITY;
      for (const auto& row : table.rows)
        worst = std::max(worst, energy(model, state_of(table, row)) / e0);
      EXPECT_LE(worst, std::stod(m[1]));
    } else {
      --trajectory_checks;
      ADD_FAILURE() << "unknown expectation";
    }
  }
  if (expected_status == 0) {
    EXPECT_GT(trajectory_checks, 0) << path << " states nothing about its trajectory";
  }
}

// Whatever MuJoCo makes of these scenes, it answers cleanly.
TEST_P(ExtremeScene, MujocoAnswersCleanly) {
  const ProgramRun run = run_program(GetParam(), "mujoco");
  CONTACT2D_NEEDS(!(run.status == 2 && run.err.find("not available") != std::string::npos),
                  "contact2d was built without MuJoCo");
  EXPECT_TRUE(run.status == 0 || run.status == 2 || run.status == 3) << run.status << run.err;
  if (run.status != 0) {
    EXPECT_FALSE(run.err.empty());
  }
  EXPECT_FALSE(has_nan(run.out)) << run.out;
  EXPECT_FALSE(has_nan(run.err)) << run.err;
  EXPECT_FALSE(has_non_finite(run.csv)) << "NaN or inf in the CSV";
}

// The suite must not pass by finding no files.
TEST(ExtremeScenes, AreThere) { EXPECT_GE(extreme_files().size(), 10u); }

INSTANTIATE_TEST_SUITE_P(Files, ExtremeScene, ::testing::ValuesIn(extreme_files()),
                         [](const auto& info) { return fs::path(info.param).stem().string(); });

}  // namespace
}  // namespace contact2d
