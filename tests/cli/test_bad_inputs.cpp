// The bad-input matrix: every file under tests/cli/bad_inputs/ is a case run
// through the real contact2d program. Its header says what must happen:
//   # expect-status: N          exit status (2 bad input, 3 diverged)
//   # expect-message: TEXT      must appear in stderr (repeatable)
//   # args: ...                 extra command-line arguments
//   # scene-path: PATH          use PATH instead of the case file
//   # csv-path: PATH            output path (default out.csv)
// Each case runs in a fresh empty directory, which must still be empty
// afterwards (no output file, no temporary), and stderr must be one line.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

struct BadInput {
  std::string name;
  fs::path file;
  int status = -1;
  std::vector<std::string> messages;
  std::string args;
  std::string scene_path;
  std::string csv_path = "out.csv";
};

std::vector<BadInput> load_cases() {
  std::vector<BadInput> cases;
  for (const auto& entry : fs::directory_iterator(CONTACT2D_BAD_INPUTS_DIR)) {
    BadInput c;
    c.name = entry.path().stem().string();
    c.file = entry.path();
    c.scene_path = entry.path().string();
    std::ifstream in(entry.path());
    std::string line;
    auto value = [&](const std::string& tag) { return line.substr(tag.size()); };
    while (std::getline(in, line)) {
      if (line.rfind("# expect-status: ", 0) == 0) c.status = std::stoi(value("# expect-status: "));
      if (line.rfind("# expect-message: ", 0) == 0)
        c.messages.push_back(value("# expect-message: "));
      if (line.rfind("# args: ", 0) == 0) c.args = value("# args: ");
      if (line.rfind("# scene-path: ", 0) == 0) c.scene_path = value("# scene-path: ");
      if (line.rfind("# csv-path: ", 0) == 0) c.csv_path = value("# csv-path: ");
    }
    cases.push_back(c);
  }
  std::sort(cases.begin(), cases.end(),
            [](const auto& a, const auto& b) { return a.name < b.name; });
  return cases;
}

class BadInputs : public ::testing::TestWithParam<BadInput> {};

TEST_P(BadInputs, ExitStatusMessageAndNoOutput) {
  const BadInput& c = GetParam();
  ASSERT_NE(c.status, -1) << c.file << " has no '# expect-status:' line";
  ASSERT_FALSE(c.messages.empty()) << c.file << " has no '# expect-message:' line";
  const fs::path dir =
      fs::temp_directory_path() / ("contact2d_bad_" + c.name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path err = dir.parent_path() / (dir.filename().string() + ".stderr");
  const std::string command = "cd '" + dir.string() + "' && '" + CONTACT2D_EXE + "' simulate '" +
                              c.scene_path + "' --csv '" + c.csv_path + "' " + c.args +
                              " >/dev/null 2>'" + err.string() + "'";
  const int raw = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(raw));
  EXPECT_EQ(WEXITSTATUS(raw), c.status);

  std::ifstream in(err);
  std::stringstream text;
  text << in.rdbuf();
  const std::string stderr_text = text.str();
  for (const std::string& m : c.messages) {
    EXPECT_NE(stderr_text.find(m), std::string::npos)
        << "missing '" << m << "' in: " << stderr_text;
  }
  EXPECT_EQ(std::count(stderr_text.begin(), stderr_text.end(), '\n'), 1) << stderr_text;
  EXPECT_TRUE(fs::is_empty(dir)) << "output left behind in " << dir;
  fs::remove_all(dir);
  fs::remove(err);
}

INSTANTIATE_TEST_SUITE_P(Matrix, BadInputs, ::testing::ValuesIn(load_cases()),
                         [](const auto& info) { return info.param.name; });

}  // namespace
