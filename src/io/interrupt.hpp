// Output that survives an interrupt: SIGINT, SIGTERM and SIGHUP end the
// program without leaving a temporary file behind.
//
// Every writer of the project writes to a temporary file and renames it into
// place when it is done (AtomicFile, the video's "<path>.tmp"). Those files
// are registered here while they exist. The handler installed by
// install_interrupt_cleanup() kills a registered child writer, removes every
// registered file (kill, waitpid and unlink are async-signal-safe), writes one line to stderr
// ("contact2d: interrupted (SIGINT): no output written") and exits with 128 + the signal number
// (130, 143, 129), as a shell reports a process killed by that signal.
#pragma once

#include <signal.h>

#include <string>

namespace contact2d {

// Installs the handler for SIGINT, SIGTERM and SIGHUP (the CLI's main does),
// except for a signal that is ignored when the program starts (nohup).
void install_interrupt_cleanup();

// While alive, SIGINT, SIGTERM and SIGHUP wait (on this thread), and the
// handler, running on another thread, waits for it to end before it cleans
// up: wrap the creation of a temporary file (or a child) and its
// registration in one, so that no interrupt can come between them on any
// thread. Keep it short: an interrupt waits for it.
class InterruptsHeld {
 public:
  InterruptsHeld();
  ~InterruptsHeld();
  InterruptsHeld(const InterruptsHeld&) = delete;
  InterruptsHeld& operator=(const InterruptsHeld&) = delete;

 private:
  sigset_t saved_;  // the mask before
};

// Registers a temporary file for removal on an interrupt; returns its slot
// (-1 when all 64 slots are in use: the file is then not cleaned up).
int register_temporary(const std::string& path);

// The file was renamed or removed: forget it (slot -1 is ignored).
void unregister_temporary(int slot);

// A child process writing one of those files (gnuplot, ffmpeg, the bench),
// or one that must not outlive the program (MuJoCo 3's Node processes): on
// an interrupt it is killed and reaped before the files are removed, so it
// cannot create one after. Several at a time (the report runs its sections
// on several threads, each with its own Node); returns its slot (-1 when
// all 512 are in use: it is then not killed here, and still dies with the
// program, io/child_process.hpp).
int register_child(int pid);

// The child was reaped: forget it (slot -1 is ignored).
void unregister_child(int slot);

}  // namespace contact2d
