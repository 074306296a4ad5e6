#include "io/child_process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <thread>

#include "core/cancel.hpp"
#include "core/format.hpp"
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

// An absolute path to run: a name with a '/' as given (a relative one
// against the working folder), else the first executable file of that name
// in PATH, whose relative entries ("", ".", "bin") are the working folder's
// too (the child may start in another). "" when there is none.
std::string resolve_program(const std::string& name) {
  std::string cwd;
  if (char* here = ::getcwd(nullptr, 0)) {
    cwd = here;
    std::free(here);  // NOLINT(cppcoreguidelines-no-malloc): getcwd's buffer
  }
  const auto absolute = [&](const std::string& path) {
    return path.empty() || path[0] != '/' ? cwd + "/" + path : path;
  };
  const auto runnable = [](const std::string& path) {
    struct stat info {};
    return ::stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode) &&
           ::access(path.c_str(), X_OK) == 0;
  };
  if (name.find('/') != std::string::npos) return absolute(name);  // exec says why it fails
  const char* path = std::getenv("PATH");
  const std::string dirs = path != nullptr ? path : "/usr/local/bin:/usr/bin:/bin";
  size_t start = 0;
  for (;;) {
    const size_t end = dirs.find(':', start);
    const std::string dir = dirs.substr(start, end == std::string::npos ? end : end - start);
    std::string candidate = absolute((dir.empty() ? "." : dir) + "/" + name);
    if (runnable(candidate)) return candidate;
    if (end == std::string::npos) return {};
    start = end + 1;
  }
}

// The line of a child's standard error that says why it ended: the last
// "...Error: ..." line (Node prints the error, its stack, then its own
// version), else the last line that is not a stack frame or a version.
std::string last_said(const std::string& text) {
  std::vector<std::string> lines;
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    // V8's fatal errors come framed in '#' lines: "# Fatal process OOM in ...".
    if (line.rfind("# ", 0) == 0) line.erase(0, 2);
    if (line == "#") line.clear();
    lines.push_back(line);
    start = end + 1;
  }
  const auto is_error = [](const std::string& line) {
    const size_t colon = line.find(": ");
    if (colon == std::string::npos || colon < 5) return false;
    const std::string head = line.substr(0, colon);
    return head.compare(head.size() - 5, 5, "Error") == 0 &&
           head.find_first_of(" \t") == std::string::npos;
  };
  for (auto i = lines.rbegin(); i != lines.rend(); ++i)
    if (is_error(*i)) return *i;
  for (auto i = lines.rbegin(); i != lines.rend(); ++i) {
    const std::string& line = *i;
    const size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line.rfind("Node.js v", 0) == 0 ||
        line.compare(first, 3, "at ") == 0)
      continue;
    return line;
  }
  return {};
}

}  // namespace

ChildProcess::ChildProcess(const std::vector<std::string>& argv, const std::string& directory,
                           bool writes_output, bool dies_on_interrupt) {
  const std::string program = resolve_program(argv.at(0));
  if (program.empty())
    throw ChildProcessError("cannot start " + argv[0] + " (" + error_text(ENOENT) + ")", ENOENT);
  int in[2] = {-1, -1}, out[2] = {-1, -1}, err[2] = {-1, -1}, report[2] = {-1, -1};
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, in) != 0 ||
      ::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, out) != 0 ||
      ::pipe2(err, O_CLOEXEC) != 0 || ::pipe2(report, O_CLOEXEC) != 0) {
    const int e = errno;
    for (int fd : {in[0], in[1], out[0], out[1], err[0], err[1], report[0], report[1]})
      if (fd >= 0) ::close(fd);
    throw ChildProcessError("cannot create the pipes to " + argv.at(0) + " (" + error_text(e) +
                            ")");
  }
  std::vector<char*> args;
  args.reserve(argv.size() + 1);
  args.push_back(const_cast<char*>(program.c_str()));
  for (size_t i = 1; i < argv.size(); ++i) args.push_back(const_cast<char*>(argv[i].c_str()));
  args.push_back(nullptr);
  const char* dir = directory.empty() ? nullptr : directory.c_str();
  int spawned = 0;
  {
    // No interrupt between starting it and registering it, and none in the
    // child before it has put back the default handlers (it is a copy of
    // this program until exec).
    const InterruptsHeld held;
    const pid_t parent = ::getpid();
    pid_ = ::fork();
    if (pid_ == 0) {
      // The child: async-signal-safe calls only (another thread may have
      // held a lock at the fork). SIGKILL when the starting thread ends.
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (::getppid() != parent) ::_exit(127);  // it ended before the line above
      ::setpgid(0, 0);                          // a group of its own: no terminal Ctrl-C
      ::dup2(in[1], STDIN_FILENO);
      ::dup2(out[1], STDOUT_FILENO);
      ::dup2(err[1], STDERR_FILENO);
      int failure = 0;
      if (dir != nullptr && ::chdir(dir) != 0) failure = errno;
      if (failure == 0) {
        struct sigaction plain {};
        plain.sa_handler = SIG_DFL;
        for (int s : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) ::sigaction(s, &plain, nullptr);
        sigset_t none;
        sigemptyset(&none);
        ::sigprocmask(SIG_SETMASK, &none, nullptr);
        ::execve(args[0], args.data(), environ);
        failure = errno;
      }
      // Told through the report pipe, which exec would have closed.
      while (::write(report[1], &failure, sizeof failure) < 0 && errno == EINTR) {
      }
      ::_exit(127);
    }
    if (pid_ < 0) {
      spawned = errno;
    } else if (writes_output || dies_on_interrupt) {
      child_slot_ = register_child(pid_);
    }
  }
  ::close(report[1]);
  if (pid_ > 0) {
    int failure = 0;
    ssize_t n = 0;
    while ((n = ::read(report[0], &failure, sizeof failure)) < 0 && errno == EINTR) {
    }
    if (n == static_cast<ssize_t>(sizeof failure)) {
      spawned = failure;
      int status = 0;
      while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
      }
      unregister_child(child_slot_);
      child_slot_ = -1;
    }
  }
  ::close(report[0]);
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
  end.standard_error = std::move(error_tail_);
  error_tail_.clear();
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

void ChildProcess::set_deadline(double seconds) {
  deadline_seconds_ = seconds;
  const auto now = std::chrono::steady_clock::now();
  const double room =
      std::chrono::duration<double>(std::chrono::steady_clock::time_point::max() - now).count();
  deadline_ = !(seconds < room)
                  ? std::chrono::steady_clock::time_point::max()
                  : now + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                              std::chrono::duration<double>(std::max(seconds, 0.0)));
}

void ChildProcess::drain_error() {
  char chunk[1 << 16];
  pollfd p{err_, POLLIN, 0};
  while (err_ >= 0 && ::poll(&p, 1, 0) > 0 && (p.revents & (POLLIN | POLLHUP | POLLERR)) != 0) {
    const ssize_t n = ::read(err_, chunk, sizeof chunk);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      close_fd(err_);  // it closed its standard error: nothing more to drain
      break;
    }
    error_tail_.append(chunk, static_cast<size_t>(n));
    constexpr size_t kKept = 1 << 16;
    if (error_tail_.size() > 2 * kKept) error_tail_.erase(0, error_tail_.size() - kKept);
  }
}

void ChildProcess::give_up(const std::string& why) {
  // Whether it was stopped (SIGSTOP, a debugger): /proc/PID/stat's state.
  std::string state;
  {
    std::ifstream stat("/proc/" + std::to_string(pid_) + "/stat");
    std::string line;
    std::getline(stat, line);
    const size_t close = line.rfind(')');
    if (close != std::string::npos && close + 2 < line.size()) state = line.substr(close + 2, 1);
  }
  ::kill(pid_, SIGKILL);
  if (!reaped_ && wait_for(pid_, status_, 5.0)) set_reaped();
  throw ChildProcessError("process " + std::to_string(pid_) + " " + why +
                          (state == "T" || state == "t" ? " (it was stopped)" : "") + ": killed");
}

void ChildProcess::wait_ready(int fd, short events) {
  for (;;) {
    if (cancel_requested()) {  // a Python Ctrl-C: the child's work is dropped with it
      ::kill(pid_, SIGKILL);
      if (!reaped_ && wait_for(pid_, status_, 5.0)) set_reaped();
      throw Cancelled();
    }
    const auto now = std::chrono::steady_clock::now();
    if (now >= deadline_)
      give_up("did not answer within " + format_number(deadline_seconds_, 3) + " s");
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline_ - now);
    const int timeout = static_cast<int>(std::clamp<long long>(left.count() + 1, 0, 20));
    pollfd p[2] = {{fd, events, 0}, {err_, POLLIN, 0}};
    const int n = ::poll(p, err_ >= 0 ? 2 : 1, timeout);
    if (n < 0 && errno != EINTR) return;  // the read or write says what is wrong
    if (n <= 0) continue;
    if (err_ >= 0 && p[1].revents != 0) drain_error();
    if (p[0].revents != 0) return;
  }
}

void ChildProcess::write(const char* data, size_t size) {
  size_t done = 0;
  while (done < size) {
    const ssize_t n = ::send(in_, data + done, size - done, MSG_NOSIGNAL | MSG_DONTWAIT);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
      wait_ready(in_, POLLOUT);
      continue;
    }
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
    wait_ready(out_, POLLIN);
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

void ChildProcess::set_reaped() {
  reaped_ = true;
  // Its pid may be another process's from now on: the interrupt handler
  // must not kill it.
  unregister_child(child_slot_);
  child_slot_ = -1;
}

bool ChildProcess::running() {
  if (pid_ <= 0 || reaped_) return false;
  const pid_t r = ::waitpid(pid_, &status_, WNOHANG);
  if (r == pid_ || (r < 0 && errno == ECHILD)) set_reaped();
  return !reaped_;
}

std::string ChildProcess::ending() {
  if (pid_ <= 0) return "was not started";
  if (!reaped_) {
    if (!wait_for(pid_, status_, 2.0)) return "stopped answering (still running)";
    set_reaped();
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
  // What it said last on its standard error, when it said anything.
  drain_error();
  const std::string said = last_said(error_tail_);
  if (!said.empty()) text += ": " + said;
  return text;
}

}  // namespace contact2d
