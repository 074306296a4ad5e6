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

}  // namespace

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  remove_stale_temporaries(path_);
  std::string pattern = path_ + ".tmp." + std::to_string(::getpid()) + ".XXXXXX";
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

void AtomicFile::commit() {
  const bool flushed = std::fflush(file_) == 0;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  const bool renamed = flushed && closed && std::rename(temp_path_.c_str(), path_.c_str()) == 0;
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
  require_writable_directory(what, directory_of(path));
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
