#include "io/child_process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <optional>
#include <thread>

#include "io/interrupt.hpp"

extern char** environ;  // NOLINT(readability-redundant-declaration): POSIX, not in a header

namespace contact2d {
namespace {

std::string error_text(int error) { return std::strerror(error); }

void close_fd(int& fd) {
  if (fd >= 0) ::close(fd);
  fd = -1;
}

// Waits up to `seconds` for the child to exit; true when it did.
bool wait_for(pid_t pid, int& status, double seconds) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  for (;;) {
    const pid_t r = ::waitpid(pid, &status, WNOHANG);
    if (r == pid || (r < 0 && errno != EINTR)) return true;
    if (std::chrono::steady_clock::now() >= until) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

}  // namespace

ChildProcess::ChildProcess(const std::vector<std::string>& argv, const std::string& directory,
                           bool writes_output) {
  int in[2] = {-1, -1}, out[2] = {-1, -1}, err[2] = {-1, -1};
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, in) != 0 ||
      ::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, out) != 0 ||
      ::pipe2(err, O_CLOEXEC) != 0) {
    const int e = errno;
    for (int fd : {in[0], in[1], out[0], out[1], err[0], err[1]})
      if (fd >= 0) ::close(fd);
    throw ChildProcessError("cannot create the pipes to " + argv.at(0) + " (" + error_text(e) +
                            ")");
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, in[1], STDIN_FILENO);
  posix_spawn_file_actions_adddup2(&actions, out[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, err[1], STDERR_FILENO);
  if (!directory.empty()) posix_spawn_file_actions_addchdir_np(&actions, directory.c_str());
  // A group of its own (no terminal Ctrl-C), no signal held or ignored.
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t none, defaults;
  sigemptyset(&none);
  sigemptyset(&defaults);
  for (int s : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) sigaddset(&defaults, s);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setpgroup(&attributes, 0);
  posix_spawnattr_setflags(&attributes,
                           POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  std::vector<char*> args;
  args.reserve(argv.size() + 1);
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  int spawned = 0;
  {
    // No interrupt between starting it and registering it.
    std::optional<InterruptsHeld> held;
    if (writes_output) held.emplace();
    spawned = ::posix_spawnp(&pid_, args[0], &actions, &attributes, args.data(), environ);
    if (spawned == 0 && writes_output) child_slot_ = register_child(pid_);
  }
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  ::close(in[1]);
  ::close(out[1]);
  ::close(err[1]);
  in_ = in[0];
  out_ = out[0];
  err_ = err[0];
  if (spawned != 0) {
    pid_ = -1;
    close_fd(in_);
    close_fd(out_);
    close_fd(err_);
    throw ChildProcessError("cannot start " + argv[0] + " (" + error_text(spawned) + ")", spawned);
  }
}

ChildProcess::~ChildProcess() {
  close_fd(in_);  // the child's input ends: it exits
  close_fd(out_);
  if (pid_ > 0 && !reaped_ && !wait_for(pid_, status_, 1.0)) {
    ::kill(pid_, SIGKILL);
    wait_for(pid_, status_, 5.0);
  }
  unregister_child(child_slot_);
  child_slot_ = -1;
  close_fd(err_);
}

ChildEnding ChildProcess::finish() {
  close_fd(in_);
  ChildEnding end;
  end.output = buffer_.substr(start_);
  buffer_.clear();
  start_ = 0;
  // Both streams at once: a child blocked on a full standard error pipe
  // would never close its output.
  char chunk[1 << 16];
  while (out_ >= 0 || err_ >= 0) {
    pollfd p[2] = {{out_, POLLIN, 0}, {err_, POLLIN, 0}};
    if (::poll(p, 2, -1) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    for (int i = 0; i < 2; ++i) {
      int& fd = i == 0 ? out_ : err_;
      if (fd < 0 || (p[i].revents & (POLLIN | POLLHUP | POLLERR)) == 0) continue;
      const ssize_t n = ::read(fd, chunk, sizeof chunk);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        close_fd(fd);
      } else {
        (i == 0 ? end.output : end.standard_error).append(chunk, static_cast<size_t>(n));
      }
    }
  }
  while (!reaped_) {
    if (::waitpid(pid_, &status_, 0) == pid_ || errno != EINTR) reaped_ = true;
  }
  unregister_child(child_slot_);
  child_slot_ = -1;
  end.status = WIFEXITED(status_) ? WEXITSTATUS(status_) : -1;
  end.description = ending();  // its standard error was read above: add its last line
  std::string said = end.standard_error;
  while (!said.empty() && (said.back() == '\n' || said.back() == '\r')) said.pop_back();
  if (const size_t last = said.rfind('\n'); last != std::string::npos) said.erase(0, last + 1);
  if (!said.empty()) end.description += ": " + said;
  return end;
}

void ChildProcess::write(const char* data, size_t size) {
  size_t done = 0;
  while (done < size) {
    const ssize_t n = ::send(in_, data + done, size - done, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw ChildProcessError("cannot write to process " + std::to_string(pid_) + ": " + ending());
    done += static_cast<size_t>(n);
  }
}

void ChildProcess::fill() {
  if (start_ > 0 && start_ == buffer_.size()) {
    buffer_.clear();
    start_ = 0;
  }
  char chunk[1 << 16];
  for (;;) {
    const ssize_t n = ::read(out_, chunk, sizeof chunk);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw ChildProcessError("process " + std::to_string(pid_) + " " + ending());
    buffer_.append(chunk, static_cast<size_t>(n));
    return;
  }
}

std::string ChildProcess::read_line() {
  for (;;) {
    const size_t end = buffer_.find('\n', start_);
    if (end != std::string::npos) {
      std::string line = buffer_.substr(start_, end - start_);
      start_ = end + 1;
      return line;
    }
    fill();
  }
}

void ChildProcess::read_bytes(void* out, size_t size) {
  auto* to = static_cast<char*>(out);
  while (size > 0) {
    if (start_ == buffer_.size()) fill();
    const size_t n = std::min(size, buffer_.size() - start_);
    std::memcpy(to, buffer_.data() + start_, n);
    start_ += n;
    to += n;
    size -= n;
  }
}

std::string ChildProcess::ending() {
  if (pid_ <= 0) return "was not started";
  if (!reaped_) {
    if (!wait_for(pid_, status_, 2.0)) return "stopped answering (still running)";
    reaped_ = true;
  }
  std::string text;
  if (WIFEXITED(status_)) {
    text = "exited with status " + std::to_string(WEXITSTATUS(status_));
  } else if (WIFSIGNALED(status_)) {
    text = "was killed by signal " + std::to_string(WTERMSIG(status_)) + " (" +
           strsignal(WTERMSIG(status_)) + ")";
  } else {
    text = "ended";
  }
  // The last non-empty line of its standard error, when it said anything.
  std::string said;
  pollfd p{err_, POLLIN, 0};
  char chunk[4096];
  while (err_ >= 0 && ::poll(&p, 1, 0) > 0 && (p.revents & POLLIN) != 0) {
    const ssize_t n = ::read(err_, chunk, sizeof chunk);
    if (n <= 0) break;
    said.append(chunk, static_cast<size_t>(n));
  }
  while (!said.empty() && (said.back() == '\n' || said.back() == '\r')) said.pop_back();
  const size_t last = said.rfind('\n');
  if (last != std::string::npos) said = said.substr(last + 1);
  if (!said.empty()) text += ": " + said;
  return text;
}

}  // namespace contact2d
