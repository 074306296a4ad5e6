#include "io/csv.hpp"

#include <sys/stat.h>
#include <unistd.h>
#include <cerrno>
#include <cstdlib>
#include <cstring>

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

void write_trajectory_row(std::FILE* out, const Sample& s) {
  std::fprintf(out, "%.10g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g\n", s.t, s.state.q.x(),
               s.state.q.y(), s.state.q.z(), s.state.v.x(), s.state.v.y(), s.state.v.z());
}

}  // namespace contact2d
