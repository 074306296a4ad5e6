// An external tool's stand-in for the interrupt tests (gnuplot, ffmpeg): a
// shell script, first on PATH, that writes its PID to a file and waits; the
// program under test started in a folder with that PATH; and what follows
// a SIGINT sent to the program once the stand-in runs.
#pragma once

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "support/files.hpp"

namespace contact2d::test {

// bin/NAME under `root`: notes its PID in root/NAME.pid (written whole, then
// renamed) and sleeps a minute.
inline std::filesystem::path write_stand_in(const std::filesystem::path& root,
                                            const std::string& name) {
  namespace fs = std::filesystem;
  const fs::path bin = root / "bin", mark = root / (name + ".pid");
  fs::create_directories(bin);
  std::ofstream(bin / name) << "#!/bin/sh\necho $$ > '" << mark.string() << ".tmp'\nmv '"
                            << mark.string() << ".tmp' '" << mark.string() << "'\nexec sleep 60\n";
  fs::permissions(bin / name, fs::perms::owner_all);
  return mark;
}

struct Interrupted {
  int exit_status = -1;  // the program's, -1 unless it exited
  bool tool_started = false;
  bool tool_outlived = false;  // the stand-in still ran after the program ended
};

// Runs `program` with `args` in `dir` with root/bin first on PATH and the
// `env` pairs set, its output dropped; once the stand-in's PID file exists
// (within 60 s), sends the program SIGINT and waits for it. A stand-in that
// outlives the program is killed here.
inline Interrupted interrupt_while_tool_runs(
    const std::filesystem::path& root, const std::filesystem::path& dir,
    const std::filesystem::path& mark, const std::string& program,
    const std::vector<std::string>& args,
    const std::vector<std::pair<std::string, std::string>>& env = {}) {
  const std::string path = (root / "bin").string() + ":" + std::getenv("PATH");
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (::chdir(dir.c_str()) != 0) ::_exit(120);
    ::setenv("PATH", path.c_str(), 1);
    for (const auto& [key, value] : env) ::setenv(key.c_str(), value.c_str(), 1);
    if (!std::freopen("/dev/null", "w", stdout) || !std::freopen("/dev/null", "w", stderr))
      ::_exit(121);
    std::vector<std::string> all = args;
    all.insert(all.begin(), program);
    std::vector<char*> argv;
    for (std::string& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(program.c_str(), argv.data());
    ::_exit(122);
  }
  Interrupted out;
  if (pid < 0) return out;
  int status = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  bool ended = false;
  while (!std::filesystem::exists(mark) && std::chrono::steady_clock::now() < deadline) {
    if (::waitpid(pid, &status, WNOHANG) == pid) {
      ended = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  out.tool_started = std::filesystem::exists(mark);
  if (!ended) {
    ::kill(pid, SIGINT);
    ::waitpid(pid, &status, 0);
  }
  out.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (out.tool_started) {
    const pid_t tool = std::stoi(read_file(mark));
    out.tool_outlived = ::kill(tool, 0) == 0;
    if (out.tool_outlived) ::kill(tool, SIGKILL);
  }
  return out;
}

}  // namespace contact2d::test
