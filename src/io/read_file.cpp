#include "io/read_file.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>

#include "core/input_error.hpp"

namespace contact2d {

std::string read_input_file(const std::string& path, const std::string& what) {
  return read_input_file(path, what, kMaxInputBytes,
                         "larger than 4 MiB, where one is a few kB: is it the right file?");
}

std::string read_input_file(const std::string& path, const std::string& what, std::size_t limit,
                            const std::string& why) {
  // A regular file's size is known before it is read: one past the cap is
  // refused at once (a sparse file of terabytes reads as zeros).
  struct stat info {};
  if (::stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode) &&
      static_cast<unsigned long long>(info.st_size) > limit)
    throw InputError(path + ": cannot read " + what + " (" + why + ")");
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

void check_input_file(const std::string& path, const std::string& what, std::size_t limit) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0)
    throw InputError(path + ": cannot read " + what + " (" + std::strerror(errno) + ")");
  const auto refuse = [&](const std::string& why) {
    throw InputError(path + ": cannot read " + what + " (" + why + ")");
  };
  if (S_ISDIR(info.st_mode)) refuse("a folder, not a file");
  if (S_ISCHR(info.st_mode) || S_ISBLK(info.st_mode))
    refuse("a device, not a regular file: it could be read without end");
  if (S_ISFIFO(info.st_mode) || S_ISSOCK(info.st_mode))
    refuse("a pipe or socket, not a regular file: it could be read without end");
  if (!S_ISREG(info.st_mode)) refuse("not a regular file");
  if (static_cast<unsigned long long>(info.st_size) > limit)
    refuse("larger than " + std::to_string(limit >> 20) +
           " MiB, where one is a few kB: is it the right file?");
  if (::access(path.c_str(), R_OK) != 0) refuse(std::strerror(errno));
}

}  // namespace contact2d
