#include "io/read_file.hpp"

#include <fstream>

#include "core/input_error.hpp"

namespace contact2d {

std::string read_input_file(const std::string& path, const std::string& what) {
  return read_input_file(path, what, kMaxInputBytes,
                         "larger than 4 MiB, where one is a few kB: is it the right file?");
}

std::string read_input_file(const std::string& path, const std::string& what, std::size_t limit,
                            const std::string& why) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot read " + what + " (missing or unreadable)");
  std::string text;
  char buffer[1 << 16];
  while (in) {
    in.read(buffer, sizeof buffer);
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (text.size() > limit) throw InputError(path + ": cannot read " + what + " (" + why + ")");
  }
  if (in.bad()) throw InputError(path + ": cannot read " + what + " (read error)");
  return text;
}

}  // namespace contact2d
