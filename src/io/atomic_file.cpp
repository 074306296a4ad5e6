// Atomic output files, output path checks and the directory lock
// (io/atomic_file.hpp).
#include "io/atomic_file.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "io/interrupt.hpp"
#include "io/scene_file.hpp"

namespace contact2d {

namespace {

namespace fs = std::filesystem;

// "out/no" for "out/no/p.png", "." for "p.png".
fs::path directory_of(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? fs::path(".") : parent;
}

// When the process `pid` started, in seconds since the epoch; NaN when
// unknown (then no file is judged by it).
double process_start_time(long pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(stat)), std::istreambuf_iterator<char>());
  const size_t paren = text.rfind(')');  // the command name may hold spaces
  if (paren == std::string::npos) return std::nan("");
  std::istringstream fields(text.substr(paren + 1));
  std::string field;
  for (int i = 3; i <= 22 && fields >> field; ++i) {  // field 22: starttime, clock ticks
    if (i < 22) continue;
    std::ifstream boot("/proc/stat");
    std::string key;
    double btime = std::nan("");
    while (boot >> key) {
      if (key == "btime") {
        boot >> btime;
        break;
      }
    }
    return btime +
           std::strtod(field.c_str(), nullptr) / static_cast<double>(::sysconf(_SC_CLK_TCK));
  }
  return std::nan("");
}

// Whether "PATH.tmp.PID.XXXXXX" was left by a process that is gone.
bool left_by_dead_process(const fs::path& file, long pid) {
  if (pid <= 0 || pid == static_cast<long>(::getpid())) return false;
  if (::kill(static_cast<pid_t>(pid), 0) != 0) return errno == ESRCH;
  // Alive (or another user's): the same process only if it started before
  // the file was last written; 1 s covers the rounding of the boot time.
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) return false;
  const double written =
      static_cast<double>(st.st_mtim.tv_sec) + 1e-9 * static_cast<double>(st.st_mtim.tv_nsec);
  return written + 1.0 < process_start_time(pid);
}

// Removes the temporaries of `path` left by dead processes.
void remove_stale_temporaries(const std::string& path) {
  const fs::path target(path);
  const std::string prefix = target.filename().string() + ".tmp.";
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(directory_of(path), ec)) {
    const std::string name = entry.path().filename().string();
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
    // PID, a dot and mkstemp's six characters.
    const std::string rest = name.substr(prefix.size());
    const size_t dot = rest.find('.');
    if (dot == 0 || dot == std::string::npos || rest.size() != dot + 7 ||
        rest.find_first_not_of("0123456789") != dot)
      continue;
    if (left_by_dead_process(entry.path(), std::strtol(rest.c_str(), nullptr, 10)))
      fs::remove(entry.path(), ec);
  }
}

// Whether `path` is in /proc or /dev/fd, or a symbolic link into /proc
// (/dev/stdout): one of this process's open files, which only writing
// through reaches (renaming onto its file would leave the program's own
// descriptor on the old one).
bool links_into_proc(const std::string& path) {
  if (path.rfind("/proc/", 0) == 0 || path.rfind("/dev/fd/", 0) == 0) return true;
  std::error_code ec;
  if (!fs::is_symlink(fs::symlink_status(path, ec))) return false;
  const std::string target = fs::read_symlink(path, ec).string();
  return target.rfind("/proc/", 0) == 0 || links_into_proc(target);
}

}  // namespace

OutputTarget output_target(const std::string& path) {
  OutputTarget t{path, false};
  std::error_code ec;
  const fs::file_status followed = fs::status(path, ec);
  const bool exists = fs::exists(followed);
  if ((exists && !fs::is_regular_file(followed) && !fs::is_directory(followed)) ||
      links_into_proc(path)) {
    t.stream = true;  // a FIFO, a device, a socket, this process's stdout
    return t;
  }
  if (fs::is_symlink(fs::symlink_status(path, ec)) && exists)
    t.path = fs::canonical(path, ec).string();  // the link stays, its file is replaced
  return t;
}

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)), target_(output_target(path_)) {
  std::string pattern;
  if (target_.stream) {
    // Written through at commit; meanwhile in the temporary directory, never
    // beside a device (/dev) or a FIFO.
    std::error_code ec;
    const fs::path tmp = fs::temp_directory_path(ec);
    pattern = ((ec ? fs::path("/tmp") : tmp) / "contact2d.stream.").string() +
              std::to_string(::getpid()) + ".XXXXXX";
  } else {
    remove_stale_temporaries(target_.path);
    pattern = target_.path + ".tmp." + std::to_string(::getpid()) + ".XXXXXX";
  }
  const InterruptsHeld held;  // no signal between creating the file and registering it
  const int fd = mkstemp(pattern.data());
  if (fd < 0) {
    throw InputError(path_ + ": cannot create output file (" + std::strerror(errno) + ")");
  }
  ::fchmod(fd, 0644);  // mkstemp creates 0600; an output file is for sharing
  temp_path_ = pattern;
  slot_ = register_temporary(temp_path_);
  file_ = fdopen(fd, "w");
  if (!file_) {
    ::close(fd);
    std::remove(temp_path_.c_str());
    unregister_temporary(slot_);
    throw InputError(path_ + ": cannot open output file");
  }
}

AtomicFile::~AtomicFile() {
  if (file_) {
    std::fclose(file_);
    std::remove(temp_path_.c_str());
  }
  unregister_temporary(slot_);
}

namespace {

// Copies the file `from` into `to`, opened for writing as it is (a FIFO, a
// device: no O_CREAT, no O_TRUNC). A reader that went away is EPIPE, not
// SIGPIPE: the signal is ignored meanwhile. Returns 0 or the errno.
int write_through(const std::string& from, const std::string& to) {
  struct sigaction ignore {
  }, saved{};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  ::sigaction(SIGPIPE, &ignore, &saved);
  int error = 0;
  // This process's own stream (/dev/stdout, /dev/fd/N): its descriptor, so
  // that the output continues where the program's other output is (opening
  // the path anew would start a redirected file over at offset 0).
  int own = -1;
  if (to == "/dev/stdout") own = STDOUT_FILENO;
  if (to == "/dev/stderr") own = STDERR_FILENO;
  for (const char* prefix : {"/dev/fd/", "/proc/self/fd/"}) {
    const std::string p(prefix);
    if (to.size() > p.size() && to.compare(0, p.size(), p) == 0 &&
        to.find_first_not_of("0123456789", p.size()) == std::string::npos)
      own = static_cast<int>(std::strtol(to.c_str() + p.size(), nullptr, 10));
  }
  if (own == STDOUT_FILENO) std::fflush(stdout);
  const int in = ::open(from.c_str(), O_RDONLY | O_CLOEXEC);
  const int out = in < 0     ? -1
                  : own >= 0 ? own
                             : ::open(to.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
  if (in < 0 || out < 0) error = errno;
  char buffer[1 << 16];
  while (error == 0) {
    const ssize_t n = ::read(in, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) error = errno;
    if (n <= 0) break;
    for (ssize_t done = 0; done < n && error == 0;) {
      const ssize_t w = ::write(out, buffer + done, static_cast<size_t>(n - done));
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) error = w < 0 ? errno : EIO;
      done += w > 0 ? w : 0;
    }
  }
  if (out >= 0 && own < 0 && ::close(out) != 0 && error == 0) error = errno;
  if (in >= 0) ::close(in);
  ::sigaction(SIGPIPE, &saved, nullptr);
  return error;
}

}  // namespace

void AtomicFile::commit() {
  const bool flushed = std::fflush(file_) == 0;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (target_.stream) {
    const int error = flushed && closed ? write_through(temp_path_, path_) : errno;
    std::remove(temp_path_.c_str());
    unregister_temporary(slot_);
    slot_ = -1;
    if (error != 0)
      throw InputError(path_ + ": cannot write output (" + std::strerror(error) + ")");
    return;
  }
  const bool renamed =
      flushed && closed && std::rename(temp_path_.c_str(), target_.path.c_str()) == 0;
  const int error = errno;
  if (!renamed) std::remove(temp_path_.c_str());
  unregister_temporary(slot_);
  slot_ = -1;
  if (!renamed) {
    throw InputError(path_ + ": cannot write output file (" + std::strerror(error) + ")");
  }
}

namespace {

// Throws unless `dir` is a directory this process may create files in.
void require_writable_directory(const std::string& what, const fs::path& dir) {
  std::error_code ec;
  if (!fs::exists(dir, ec))
    throw InputError(what + ": directory " + dir.string() + " does not exist");
  if (!fs::is_directory(dir, ec))
    throw InputError(what + ": " + dir.string() + " is not a directory");
  if (::access(dir.c_str(), W_OK | X_OK) != 0) {
    throw InputError(what + ": directory " + dir.string() + " is not writable (" +
                     std::strerror(errno) + ")");
  }
}

}  // namespace

void check_output_file(const std::string& option, const std::string& path) {
  if (path.empty()) throw InputError(option + ": the path is empty (give a file name)");
  const std::string what = option + " " + path;
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw InputError(what + ": is a directory (give a file name)");
  const OutputTarget target = output_target(path);
  if (target.stream) {
    if (::access(path.c_str(), W_OK) != 0)
      throw InputError(what + ": is not writable (" + std::strerror(errno) + ")");
    return;
  }
  if (fs::is_symlink(fs::symlink_status(path, ec)) && !fs::exists(path, ec))
    throw InputError(what +
                     ": a symbolic link to a file that does not exist (give the file "
                     "itself)");
  require_writable_directory(what, directory_of(target.path));
}

void check_output_directory(const std::string& option, const std::string& path) {
  if (path.empty()) throw InputError(option + ": the path is empty (give a directory)");
  const std::string what = option + " " + path;
  std::error_code ec;
  fs::path dir(path);
  if (fs::exists(dir, ec)) {
    require_writable_directory(what, dir);
    return;
  }
  // Created with its missing parents: the nearest existing one must take it.
  for (dir = dir.parent_path(); !dir.empty() && !fs::exists(dir, ec); dir = dir.parent_path()) {
  }
  require_writable_directory(what, dir.empty() ? fs::path(".") : dir);
}

DirectoryLock::DirectoryLock(const std::string& option, const std::string& dir)
    : path_((fs::path(dir) / ".contact2d.lock").string()) {
  // The holder removes the file when it is done, so a lock taken on a file
  // that is no longer at the path (removed and maybe created anew since it
  // was opened) is no lock: open and lock again.
  for (int attempt = 0; attempt < 100; ++attempt) {
    const InterruptsHeld held;  // no signal between locking and registering for removal
    const int fd = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) {
      throw InputError(option + " " + dir + ": cannot create its lock file (" +
                       std::strerror(errno) + ")");
    }
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      char owner[32] = {};
      const ssize_t n = ::pread(fd, owner, sizeof owner - 1, 0);
      ::close(fd);
      if (error != EWOULDBLOCK) {
        throw InputError(option + " " + dir + ": cannot lock it (" + std::strerror(error) + ")");
      }
      const std::string pid = n > 0 ? std::string(owner, static_cast<size_t>(n)) : "";
      throw InputError(option + " " + dir + ": another contact2d" +
                       (pid.empty() ? "" : " (pid " + pid + ")") +
                       " is writing into this directory; wait for it to finish or choose "
                       "another " +
                       option);
    }
    struct stat held_file {};
    struct stat at_path {};
    if (::fstat(fd, &held_file) == 0 && ::stat(path_.c_str(), &at_path) == 0 &&
        held_file.st_dev == at_path.st_dev && held_file.st_ino == at_path.st_ino) {
      const std::string pid = std::to_string(::getpid());
      if (::ftruncate(fd, 0) != 0 ||
          ::pwrite(fd, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size())) {
        // The lock holds without the PID; a second run's message only lacks it.
      }
      fd_ = fd;
      slot_ = register_temporary(path_);
      return;
    }
    ::close(fd);
  }
  throw InputError(option + " " + dir + ": cannot lock it (its lock file keeps changing)");
}

DirectoryLock::~DirectoryLock() {
  // Removed while still locked: a process waiting on this file then finds
  // it gone from the path and locks a new one.
  ::unlink(path_.c_str());
  unregister_temporary(slot_);
  ::close(fd_);
}

}  // namespace contact2d
