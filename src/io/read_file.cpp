#include "io/read_file.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>

#include "core/format.hpp"
#include "core/input_error.hpp"

namespace contact2d {

namespace {

// Closes the descriptor on every way out of the read.
struct Descriptor {
  int fd = -1;
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

// The one form of every refusal here: "PATH: cannot read WHAT (BECAUSE)".
[[noreturn]] void cannot_read(const std::string& path, const std::string& what,
                              const std::string& because) {
  throw InputError(path + ": cannot read " + what + " (" + because + ")");
}

constexpr const char* kDirectory = "a directory, not a file";

}  // namespace

std::string read_input_file(const std::string& path, const std::string& what) {
  return read_input_file(path, what, kMaxInputBytes,
                         "larger than 4 MiB, where one is a few kB: is it the right file?");
}

std::string read_input_file(const std::string& path, const std::string& what, std::size_t limit,
                            const std::string& why) {
  return read_input_file(path, what, limit, why, kInputWaitSeconds);
}

std::string read_input_file(const std::string& path, const std::string& what, std::size_t limit,
                            const std::string& why, double wait_seconds) {
  const auto refuse = [&](const std::string& because) { cannot_read(path, what, because); };
  // Opened without blocking: a FIFO nobody has opened for writing would
  // otherwise block open() itself until a writer came, without end.
  Descriptor file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
  if (file.fd < 0) refuse(errno == ENOENT ? "missing" : std::strerror(errno));
  struct stat info {};
  if (::fstat(file.fd, &info) != 0) refuse(std::strerror(errno));
  if (S_ISDIR(info.st_mode)) refuse(kDirectory);
  // A regular file's size is known before it is read: one past the cap is
  // refused at once (a sparse file of terabytes reads as zeros).
  if (S_ISREG(info.st_mode) && static_cast<unsigned long long>(info.st_size) > limit) refuse(why);
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(wait_seconds));
  std::string text;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t got = ::read(file.fd, buffer, sizeof buffer);
    if (got > 0) {
      text.append(buffer, static_cast<std::size_t>(got));
      if (text.size() > limit) refuse(why);
      continue;
    }
    if (got == 0) break;  // the end (a pipe: every writer closed it, or none had opened it)
    if (errno == EINTR) continue;
    if (errno != EAGAIN && errno != EWOULDBLOCK)
      refuse("read error: " + std::string(std::strerror(errno)));
    // A pipe or device with nothing to read yet: wait for it, up to the
    // deadline of the whole read (a writer that never writes, a terminal).
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0)
      refuse(std::string(text.empty() ? "nothing came" : "nothing more came") + " within " +
             format_number("%g", wait_seconds) + " s: a pipe or device nobody writes to the end");
    pollfd wait{file.fd, POLLIN, 0};
    if (::poll(&wait, 1, static_cast<int>(std::min<long long>(left.count() + 1, 1000))) < 0 &&
        errno != EINTR)
      refuse("read error: " + std::string(std::strerror(errno)));
  }
  // A FIFO no process had opened for writing reads as empty at once: say so
  // rather than let the caller call the file empty.
  if (S_ISFIFO(info.st_mode) && text.empty()) refuse("a pipe nobody was writing to");
  return text;
}

void check_input_file(const std::string& path, const std::string& what, std::size_t limit) {
  check_input_file(path, what, limit,
                   "larger than " + std::to_string(limit >> 20) +
                       " MiB, where one is a few kB: is it the right file?");
}

void check_input_file(const std::string& path, const std::string& what, std::size_t limit,
                      const std::string& why) {
  const auto refuse = [&](const std::string& because) { cannot_read(path, what, because); };
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) refuse(std::strerror(errno));
  if (S_ISDIR(info.st_mode)) refuse(kDirectory);
  if (S_ISCHR(info.st_mode) || S_ISBLK(info.st_mode))
    refuse("a device, not a regular file: it could be read without end");
  if (S_ISFIFO(info.st_mode) || S_ISSOCK(info.st_mode))
    refuse("a pipe or socket, not a regular file: it could be read without end");
  if (!S_ISREG(info.st_mode)) refuse("not a regular file");
  if (static_cast<unsigned long long>(info.st_size) > limit) refuse(why);
  if (::access(path.c_str(), R_OK) != 0) refuse(std::strerror(errno));
}

}  // namespace contact2d
