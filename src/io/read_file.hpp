// Reading an input file whole, bounded: a scene or an atlas spec is a few
// kB, so a path that names something endless (/dev/zero, a FIFO nobody
// closes, a huge file given by mistake) is refused at kMaxInputBytes with
// one line instead of reading until memory runs out. A pipe is read (a
// shell's `<(command)` is one), but never waited on without end: one no
// process opened for writing is refused at once, and one whose writer
// stops writing is refused after kInputWaitSeconds.
#pragma once

#include <cstddef>
#include <string>

namespace contact2d {

constexpr std::size_t kMaxInputBytes = 4u << 20;  // 4 MiB

// How long a read waits, in all, on a pipe or device that gives nothing.
constexpr double kInputWaitSeconds = 10.0;

// The file's text. Throws InputError "PATH: cannot read WHAT (…)" when
// it cannot be opened or read, is a folder, is larger than
// kMaxInputBytes, or is a pipe or device that gives no end in time.
std::string read_input_file(const std::string& path, const std::string& what);

// That `path` names a regular file (after symlinks) of at most `limit`
// bytes, without reading it: for a file another process reads (MuJoCo 3's
// Node). Throws InputError "PATH: cannot read WHAT (…)" saying which:
// missing, a device, a FIFO, a folder, larger than the cap.
void check_input_file(const std::string& path, const std::string& what,
                      std::size_t limit = kMaxInputBytes);
// The same with the reason a file past `limit` is refused (named in the message).
void check_input_file(const std::string& path, const std::string& what, std::size_t limit,
                      const std::string& why);

// A recording's data (io/recording.hpp): thousands of rows, so a larger cap.
constexpr std::size_t kMaxRecordingBytes = 64u << 20;  // 64 MiB
// The same read with its own cap (`limit` bytes, named in the message).
std::string read_input_file(const std::string& path, const std::string& what, std::size_t limit,
                            const std::string& why);
// The same with the wait on a pipe or device given (seconds; for tests).
std::string read_input_file(const std::string& path, const std::string& what, std::size_t limit,
                            const std::string& why, double wait_seconds);

}  // namespace contact2d
