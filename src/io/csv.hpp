// Trajectory CSV (docs/cli.md), written atomically: rows go to a temporary file
// beside the target, which is renamed into place only by commit(). A run that
// fails or diverges leaves no file behind.
#pragma once

#include <cstdio>
#include <string>

#include "core/run.hpp"

namespace contact2d {

class AtomicFile {
 public:
  // Opens a temporary file in the target's directory; throws InputError
  // (from io/scene_file.hpp) when the directory does not exist or is not writable.
  explicit AtomicFile(std::string path);
  ~AtomicFile();  // removes the temporary file unless committed
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::FILE* get() const { return file_; }
  // The temporary file's path, for a writer that opens it by name (gnuplot);
  // flush get() first if it was written through too.
  const std::string& temp_path() const { return temp_path_; }
  void commit();  // flush, close, rename; throws InputError on failure

 private:
  std::string path_;
  std::string temp_path_;
  std::FILE* file_ = nullptr;
  int slot_ = -1;  // io/interrupt.hpp: removed if a signal ends the program first
};

constexpr const char* kTrajectoryHeader = "t,x,y,theta,vx,vy,omega";

void write_trajectory_row(std::FILE* out, const Sample& sample);

}  // namespace contact2d
