#include "io/csv.hpp"

#include <sys/stat.h>
#include <unistd.h>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "io/interrupt.hpp"
#include "io/scene_file.hpp"

namespace contact2d {

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  std::string pattern = path_ + ".tmp.XXXXXX";
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

namespace fs = std::filesystem;

// "out/no" for "out/no/p.png", "." for "p.png".
fs::path directory_of(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? fs::path(".") : parent;
}

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

void write_trajectory_row(std::FILE* out, const Sample& s) {
  std::fprintf(out, "%.10g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g\n", s.t, s.state.q.x(),
               s.state.q.y(), s.state.q.z(), s.state.v.x(), s.state.v.y(), s.state.v.z());
}

}  // namespace contact2d
