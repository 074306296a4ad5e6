// The files of one atlas run's directory (analysis/atlas.hpp): which points
// a shard owns, and the writer that puts their rows into points.csv and
// times.csv in index order and marks the directory finished with shard.txt.
// Shared by the run (analysis/atlas_run.cpp) and the merge
// (analysis/atlas_merge.cpp), which writes the merged directory the same way.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "analysis/atlas.hpp"
#include "io/atomic_file.hpp"

namespace contact2d::analysis {

// The indices of the points `shard` holds of `total`, in increasing order.
std::vector<long long> shard_points(const Shard& shard, long long total);

std::string shard_text(const Shard& s);  // "I/N"

// `text` on one line (line breaks as spaces, no trailing blank): an
// engine's message as a CSV field.
std::string atlas_one_line(std::string text);

// Creates OUT (or says it cannot) and removes an older run's shard.txt first:
// shard.txt marks a finished run, so a run that stops halfway leaves no
// directory that looks complete.
void prepare_atlas_dir(const std::string& out_dir);

// Writes `text` to `path` atomically (io/atomic_file.hpp).
void write_atlas_file(const std::string& path, const std::string& text);

// The text of shard.txt: the spec, its digest, the number of points, the
// shard and how many rows its points.csv holds.
std::string atlas_manifest(const std::string& spec, const std::string& digest, long long points,
                           const Shard& shard, long long rows);

// points.csv and times.csv of one run being written. The constructor creates
// OUT, locks it (two shards run into one --out would overwrite each other's
// files: the second one stops here, before it touches any, docs/atlas.md),
// removes an older shard.txt and opens both files with their headers. Rows
// are written in index order as soon as every earlier row is done; only the
// rows waiting for an earlier one are held (the pool hands out points in
// order, so about one per thread). Not thread safe: the caller serialises.
class AtlasShardWriter {
 public:
  explicit AtlasShardWriter(const std::string& out_dir);

  // The rows of the shard's point number `position` (0, 1, … in the order
  // of shard_points).
  void add(size_t position, std::string points_row, std::string times_row);

  // Renames both files into place, then writes shard.txt (`manifest`).
  void finish(const std::string& manifest);

 private:
  std::string out_dir_;
  std::optional<DirectoryLock> lock_;
  std::optional<AtomicFile> points_csv_, times_csv_;
  std::map<size_t, std::pair<std::string, std::string>> pending_;
  size_t next_to_write_ = 0;
};

}  // namespace contact2d::analysis
