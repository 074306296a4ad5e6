// The contact2d program on good input: the trajectory CSV format and --help.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {

int run(const std::string& args) {
  const int raw = std::system((std::string("'") + CONTACT2D_EXE + "' " + args).c_str());
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
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

}  // namespace
