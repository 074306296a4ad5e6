// Reading an input file whole, bounded: a scene or an atlas spec is a few
// kB, so a path that names something endless (/dev/zero, a FIFO nobody
// closes, a huge file given by mistake) is refused at kMaxInputBytes with
// one line instead of reading until memory runs out.
#pragma once

#include <cstddef>
#include <string>

namespace contact2d {

constexpr std::size_t kMaxInputBytes = 4u << 20;  // 4 MiB

// The file's text. Throws InputError "PATH: cannot read WHAT (…)" when
// it cannot be opened or read, or is larger than kMaxInputBytes.
std::string read_input_file(const std::string& path, const std::string& what);

// That `path` names a regular file (after symlinks) of at most `limit`
// bytes, without reading it: for a file another process reads (MuJoCo 3's
// Node). Throws InputError "PATH: cannot read WHAT (…)" saying which:
// missing, a device, a FIFO, a folder, larger than the cap.
void check_input_file(const std::string& path, const std::string& what,
                      std::size_t limit = kMaxInputBytes);

// A recording's data (io/recording.hpp): thousands of rows, so a larger cap.
constexpr std::size_t kMaxRecordingBytes = 64u << 20;  // 64 MiB
// The same read with its own cap (`limit` bytes, named in the message).
std::string read_input_file(const std::string& path, const std::string& what, std::size_t limit,
                            const std::string& why);

}  // namespace contact2d
