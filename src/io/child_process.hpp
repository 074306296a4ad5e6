// A child process spoken to over its standard input and output (one
// connected socket pair each way, so that writing to a child that died is
// an error, EPIPE, and never the SIGPIPE that would end this program). Its
// standard error goes to a pipe that is drained whenever this side waits
// (a chatty child never blocks on it); the last 64 kB are kept for the
// message when it fails.
//
// The child runs in a process group of its own: a Ctrl-C at the terminal
// reaches this program (io/interrupt.hpp), which exits; the child then sees
// its input close and ends. It dies with this program in every case: the
// kernel sends it SIGKILL when the thread that started it ends
// (PR_SET_PDEATHSIG; so the whole program's end, however it comes), and one
// started with `dies_on_interrupt` is killed by the interrupt handler. The
// destructor closes the input, waits up to a second for the child to exit
// and kills it otherwise.
//
// Every wait has a deadline (set_deadline; none by default) and looks at
// core/cancel.hpp's request every 20 ms: a child that does not answer in
// time, or a wait cancelled, kills the child.
#pragma once

#include <sys/types.h>

#include <chrono>
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
  // `dies_on_interrupt`: registered the same way, for a child that writes
  // no file but must not outlive an interrupt (MuJoCo 3's Node).
  // A relative argv[0] with a '/', and relative PATH entries, are this
  // program's working folder's, not `directory`'s.
  ChildProcess(const std::vector<std::string>& argv, const std::string& directory = {},
               bool writes_output = false, bool dies_on_interrupt = false);
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  // The time by which every write and read below must be done: past it the
  // child is killed and the call throws ChildProcessError "process N did
  // not answer within S s" (and says whether it was stopped). `seconds`
  // from now; infinity (the default) waits without end.
  void set_deadline(double seconds);
  // A cancel requested (core/cancel.hpp) while waiting kills the child and
  // throws Cancelled.

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
  // Whether it has not ended (reaps it when it has).
  bool running();
  // Why it ended, once its output ended: "exited with status 1", "killed
  // by signal 9 (Killed)", with the last line it wrote to standard error.
  std::string ending();

 private:
  void fill();  // reads more output into buffer_; throws at end
  // Waits until `fd` is ready for `events` (draining standard error
  // meanwhile), until the deadline (throws) or a cancel (throws).
  void wait_ready(int fd, short events);
  void drain_error();  // what standard error holds now, into error_tail_
  [[noreturn]] void give_up(const std::string& why);
  void set_reaped();               // waitpid returned it: forgotten by the interrupt handler too
  double deadline_seconds_ = 0.0;  // as set, for the message
  std::chrono::steady_clock::time_point deadline_ = std::chrono::steady_clock::time_point::max();
  std::string error_tail_;  // the last 64 kB of its standard error
  pid_t pid_ = -1;
  int in_ = -1;   // its standard input (our end)
  int out_ = -1;  // its standard output (our end)
  int err_ = -1;  // its standard error (our end)
  std::string buffer_;
  size_t start_ = 0;  // the unread part of buffer_ begins here
  bool reaped_ = false;
  int status_ = 0;
  int child_slot_ = -1;  // with the interrupt handler (writes_output), else -1
};

}  // namespace contact2d
