// A child process spoken to over its standard input and output (one
// connected socket pair each way, so that writing to a child that died is
// an error, EPIPE, and never the SIGPIPE that would end this program). Its
// standard error goes to a pipe that is read only when it fails, for the
// last thing it said.
//
// The child runs in a process group of its own: a Ctrl-C at the terminal
// reaches this program (io/interrupt.hpp), which exits; the child then sees
// its input close and ends. The destructor closes the input, waits up to a
// second for the child to exit and kills it otherwise.
#pragma once

#include <sys/types.h>

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace contact2d {

// A child that could not be started, or that died or broke the protocol:
// the message is one line.
struct ChildProcessError : std::runtime_error {
  ChildProcessError(const std::string& what, int error = 0)
      : std::runtime_error(what), spawn_error(error) {}
  int spawn_error;  // errno of a child that could not be started, else 0
};

// How it ended (finish()): its exit status, or -1 when a signal ended it,
// the ending() line, and what it wrote to its standard output (the part not
// read before) and to its standard error.
struct ChildEnding {
  int status = -1;
  std::string description;
  std::string output;
  std::string standard_error;
};

class ChildProcess {
 public:
  // Starts argv[0] (looked up in PATH) with the arguments in `directory`
  // (empty: this one). Throws ChildProcessError when it cannot be started
  // (`spawn_error()` then holds the errno, ENOENT for a program not found).
  // A child that writes one of the program's output files (gnuplot,
  // ffmpeg) is started with `writes_output`: it is registered with the
  // interrupt handler (io/interrupt.hpp, register_child) from the moment it
  // exists, so an interrupt kills it before removing the files, and it
  // cannot create one after.
  ChildProcess(const std::vector<std::string>& argv, const std::string& directory = {},
               bool writes_output = false);
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  // Writes all of `text` to its input; throws ChildProcessError when it
  // cannot (the child is gone).
  void write(const std::string& text) { write(text.data(), text.size()); }
  void write(const char* data, size_t size);
  // The next line of its output without the '\n'; throws at end of output.
  std::string read_line();
  // Exactly `size` bytes of its output; throws at end of output.
  void read_bytes(void* out, size_t size);

  // Closes its input, reads its output and its standard error to the end,
  // and waits for it to exit.
  ChildEnding finish();

  pid_t pid() const { return pid_; }
  // Why it ended, once its output ended: "exited with status 1", "killed
  // by signal 9 (Killed)", with the last line it wrote to standard error.
  std::string ending();

 private:
  void fill();  // reads more output into buffer_; false at end
  pid_t pid_ = -1;
  int in_ = -1;   // its standard input (our end)
  int out_ = -1;  // its standard output (our end)
  int err_ = -1;  // its standard error (our end, read on failure only)
  std::string buffer_;
  size_t start_ = 0;  // the unread part of buffer_ begins here
  bool reaped_ = false;
  int status_ = 0;
  int child_slot_ = -1;  // with the interrupt handler (writes_output), else -1
};

}  // namespace contact2d
