// Output paths through the real program: every output option of every
// subcommand is checked before the run starts. One of them unwritable (a
// directory that does not exist, a path through a regular file, an empty
// path) is one stderr line naming that option, exit status 2, and no file
// at all: not the other outputs, not a temporary, not ffmpeg's own message.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "support/files.hpp"

namespace fs = std::filesystem;

namespace {

using contact2d::test::read_file;

struct OutputCase {
  const char* name;
  std::string args;    // after the program name, run inside an empty directory
  const char* option;  // the option the one line must name
};

void PrintTo(const OutputCase& c, std::ostream* os) { *os << c.name; }

class BadOutput : public ::testing::TestWithParam<OutputCase> {};

TEST_P(BadOutput, OneLineNamingTheOptionExit2AndNothingWritten) {
  const OutputCase& c = GetParam();
  const fs::path dir = fs::temp_directory_path() / ("contact2d_outputs_" + std::string(c.name) +
                                                    "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  // A regular file, so that "file/x" is a path through a non-directory (which
  // fails for root too, unlike a read-only directory).
  std::ofstream(dir / "file") << "not a directory\n";
  const fs::path err = dir.string() + ".stderr";
  const std::string command = "cd '" + dir.string() + "' && '" + CONTACT2D_EXE + "' " + c.args +
                              " >/dev/null 2>'" + err.string() + "'";
  const int raw = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(raw));
  EXPECT_EQ(WEXITSTATUS(raw), 2);
  const std::string text = read_file(err);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << text;
  EXPECT_EQ(text.rfind(std::string("contact2d: ") + c.option, 0), 0u) << text;
  std::vector<std::string> left;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.path().filename() != "file") left.push_back(entry.path().string());
  EXPECT_TRUE(left.empty()) << "written: " << (left.empty() ? "" : left.front());
  fs::remove_all(dir);
  fs::remove(err);
}

const std::string kOutputScenes = CONTACT2D_SCENES_DIR;
const std::string kPointMass = "'" + kOutputScenes + "/point_mass.toml'";

std::vector<OutputCase> output_cases() {
  std::vector<OutputCase> out = {
      {"simulate_csv_missing_dir", "simulate " + kPointMass + " --csv no/out.csv", "--csv"},
      {"simulate_csv_empty", "simulate " + kPointMass + " --csv ''", "--csv"},
      {"simulate_csv_is_directory", "simulate " + kPointMass + " --csv .", "--csv"},
      {"sweep_plot", "sweep " + kPointMass + " --csv a.csv --plot no/p.png --quiet", "--plot"},
      {"sweep_orders_csv", "sweep " + kPointMass + " --csv a.csv --orders-csv file/o.csv --quiet",
       "--orders-csv"},
      {"sweep_study_csv", "sweep " + kPointMass + " --study-csv no/s.csv --quiet", "--study-csv"},
      {"stability_plot", "stability " + kPointMass + " --csv a.csv --plot no/p.png --quiet",
       "--plot"},
      {"play_record_input", "play --headless --seed 1 --record-input no/r.txt", "--record-input"},
  };
#ifdef CONTACT2D_WITH_MUJOCO
  const std::string spec = "'" CONTACT2D_SOURCE_DIR "/tests/slurm/tiny.toml'";
  out.insert(
      out.end(),
      {
          {"generate_output", "generate " + kPointMass + " -o no/m.xml", "--output"},
          {"compare_plot",
           "compare " + kPointMass + " --no-diagnosis --csv cmp.csv --plot no/p.png", "--plot"},
          {"compare_video",
           "compare " + kPointMass + " --no-diagnosis --csv cmp.csv --video no/v.mp4", "--video"},
          {"compare_csv_empty", "compare " + kPointMass + " --no-diagnosis --csv ''", "--csv"},
          {"atlas_out", "atlas " + spec + " --quiet --out file/shard", "--out"},
          {"atlas_merge_out", "atlas merge . --out file/merged", "--out"},
      });
#endif
  return out;
}

INSTANTIATE_TEST_SUITE_P(Commands, BadOutput, ::testing::ValuesIn(output_cases()),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace

namespace {

// The program's own standard output as an output path (io/atomic_file.hpp:
// a link into /proc is written through this process's descriptor): the
// trajectory and the summary line land in the redirected file one after
// the other, nothing is renamed onto the path. /proc/self/fd/1 rather than
// /dev/stdout, so that a regression could not replace a file of the
// machine's /dev (renaming onto /proc fails).
TEST(OutputThroughStdout, SimulateWritesItsCsvAndSummaryInOrder) {
  const fs::path dir =
      fs::temp_directory_path() / ("contact2d_stdout_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string command = "cd '" + dir.string() + "' && '" + CONTACT2D_EXE + "' simulate " +
                              kPointMass +
                              " --duration 0.01 --csv /proc/self/fd/1 >out.txt 2>err.txt";
  ASSERT_EQ(std::system(command.c_str()), 0) << read_file(dir / "err.txt");
  const std::string out = read_file(dir / "out.txt");
  const size_t header = out.find("t,x,y,theta,vx,vy,omega\n");
  const size_t summary = out.find("point_mass [ref, ");
  EXPECT_EQ(header, 0u) << out;
  EXPECT_NE(summary, std::string::npos) << out;
  EXPECT_GT(summary, header) << out;
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1 + 11 + 1)
      << out;  // header, 11 rows, summary
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"err.txt", "out.txt"}));
  fs::remove_all(dir);
}

}  // namespace
