// Reading a file whole, for the suites that check what a program wrote
// (no dependency on the libraries: the window test includes it too).
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace contact2d::test {

// A file's whole content ("" when it cannot be opened: the caller's
// assertion on the content then says what was missing).
inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The size of an output's temporary "PATH.tmp.PID.XXXXXX" (io/atomic_file.hpp),
// -1 while there is none.
inline long long temporary_size(const std::filesystem::path& output) {
  const std::string prefix = output.filename().string() + ".tmp.";
  for (const auto& e : std::filesystem::directory_iterator(output.parent_path()))
    if (e.path().filename().string().rfind(prefix, 0) == 0)
      return static_cast<long long>(std::filesystem::file_size(e.path()));
  return -1;
}

}  // namespace contact2d::test
