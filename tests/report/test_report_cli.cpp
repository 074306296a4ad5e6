// `contact2d report` on bad input, through the real program: one line on
// standard error and exit status 2, before any run starts.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <string>

namespace {

struct Result {
  int status = -1;
  std::string output;
};

Result run(const std::string& command) {
  Result r;
  std::FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buffer{};
  for (size_t n; (n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0;)
    r.output.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

const std::string kExe = CONTACT2D_EXE;
const std::string kRoot = CONTACT2D_SOURCE_DIR;

void expect_bad_input(const Result& r, const std::string& says) {
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_NE(r.output.find(says), std::string::npos) << r.output;
}

TEST(ReportCli, OutsideTheRepositoryRoot) {
  expect_bad_input(run("cd / && " + kExe + " report"),
                   "run contact2d report from the repository root");
}

TEST(ReportCli, OutputDirectoryThatCannotBeMade) {
  expect_bad_input(run("cd " + kRoot + " && " + kExe + " report --out /proc/contact2d-report"),
                   "--out /proc/contact2d-report: cannot create directory");
}

TEST(ReportCli, BenchThatIsNotAProgram) {
  expect_bad_input(run("cd " + kRoot + " && " + kExe + " report --bench /nonexistent/bench"),
                   "--bench /nonexistent/bench: not an executable file");
}

TEST(ReportCli, UnknownOption) {
  expect_bad_input(run("cd " + kRoot + " && " + kExe + " report --quick"), "--quick");
}

}  // namespace
