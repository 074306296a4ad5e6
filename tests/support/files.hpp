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

}  // namespace contact2d::test
