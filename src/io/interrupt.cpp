#include "io/interrupt.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <pthread.h>
#include <atomic>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <mutex>

namespace contact2d {
namespace {

constexpr int kSlots = 64;
constexpr size_t kPathMax = 4096;

// A slot is written only while it is free (in_use == false) and published by
// setting in_use; the handler reads only published slots.
struct Slot {
  std::atomic<bool> in_use{false};
  char path[kPathMax] = {};
};
Slot g_slots[kSlots];
std::mutex g_register;  // between threads that register; never taken by the handler
// Gnuplot, ffmpeg and the bench, and MuJoCo 3's Node processes: one per
// thread that runs it, up to --threads' 256, beside the writers.
constexpr int kChildren = 512;
std::atomic<int> g_children[kChildren];  // a pid, or 0: free
// Held sections in progress, on every thread, and whether the handler has
// begun. The handler runs on a thread that holds none (its signals wait
// there), but the others go on: it sets g_stopping, waits until no
// section is in progress (each is a few system calls: a file created and
// registered, a child spawned and registered, a set of renames), then
// cleans up and exits, so no thread can create a file or a child between
// its cleanup and the exit. A section that starts after g_stopping never
// runs: its thread waits for the exit.
std::atomic<int> g_held{0};
std::atomic<bool> g_stopping{false};

void write_all(const char* text) {
  size_t left = std::strlen(text);
  while (left > 0) {
    const ssize_t n = ::write(STDERR_FILENO, text, left);
    if (n <= 0) return;
    text += n;
    left -= static_cast<size_t>(n);
  }
}

extern "C" void on_interrupt(int signal) {
  g_stopping.store(true);
  while (g_held.load() > 0) {
    const timespec pause_ms{0, 1000000};
    ::nanosleep(&pause_ms, nullptr);  // async-signal-safe
  }
  for (const std::atomic<int>& slot : g_children) {
    if (const int child = slot.load(); child > 0) ::kill(child, SIGKILL);
  }
  for (const std::atomic<int>& slot : g_children) {
    if (const int child = slot.load(); child > 0) ::waitpid(child, nullptr, 0);
  }
  for (Slot& slot : g_slots) {
    if (slot.in_use.load()) ::unlink(slot.path);
  }
  const char* name = signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "SIGHUP";
  write_all("contact2d: interrupted (");
  write_all(name);
  write_all("): unfinished output files removed\n");
  ::_exit(128 + signal);
}

// At the program's normal end: the children still registered are the
// MuJoCo 3 Nodes kept for reuse (mujoco3/node_mujoco.cpp). The kernel would
// kill them as the program ends (PR_SET_PDEATHSIG), but nobody here would
// reap them then: they stayed zombies for init to collect (0.5–2 s; for
// ever under a PID 1 that reaps nothing). Killed and reaped here instead,
// each within a deadline (SIGKILL cannot be caught; a process in an
// uninterruptible wait is left to the kernel after 2 s).
extern "C" void end_children_at_exit() {
  for (const std::atomic<int>& slot : g_children) {
    if (const int child = slot.load(); child > 0) ::kill(child, SIGKILL);
  }
  const timespec pause_ms{0, 1000000};
  for (std::atomic<int>& slot : g_children) {
    const int child = slot.load();
    if (child <= 0) continue;
    for (int waited = 0; waited < 2000; ++waited) {
      const pid_t r = ::waitpid(child, nullptr, WNOHANG);
      if (r == child || (r < 0 && errno != EINTR)) break;  // reaped, or not ours any more
      ::nanosleep(&pause_ms, nullptr);
    }
    slot.store(0);
  }
}

}  // namespace

void install_interrupt_cleanup() {
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&action.sa_mask, s);  // one at a time
  for (int s : {SIGINT, SIGTERM, SIGHUP}) {
    // A signal the caller ignores stays ignored (nohup, a background job of
    // a non-interactive shell): the program then runs on, uninterrupted.
    struct sigaction current {};
    if (::sigaction(s, nullptr, &current) == 0 && current.sa_handler == SIG_IGN) continue;
    ::sigaction(s, &action, nullptr);
  }
}

InterruptsHeld::InterruptsHeld() {
  sigset_t held;
  sigemptyset(&held);
  for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&held, s);
  ::pthread_sigmask(SIG_BLOCK, &held, &saved_);
  g_held.fetch_add(1);
  if (g_stopping.load()) {  // the handler is cleaning up: this thread waits for the exit
    g_held.fetch_sub(1);
    for (;;) ::pause();
  }
}

InterruptsHeld::~InterruptsHeld() {
  g_held.fetch_sub(1);
  ::pthread_sigmask(SIG_SETMASK, &saved_, nullptr);
}

int register_temporary(const std::string& path) {
  if (path.size() >= kPathMax) return -1;
  const std::lock_guard<std::mutex> lock(g_register);
  for (int i = 0; i < kSlots; ++i) {
    if (g_slots[i].in_use.load()) continue;
    std::memcpy(g_slots[i].path, path.c_str(), path.size() + 1);
    g_slots[i].in_use.store(true);
    return i;
  }
  return -1;
}

void unregister_temporary(int slot) {
  if (slot >= 0 && slot < kSlots) g_slots[slot].in_use.store(false);
}

int register_child(int pid) {
  static const bool at_exit = std::atexit(end_children_at_exit) == 0;
  (void)at_exit;
  for (int i = 0; i < kChildren; ++i) {
    int free = 0;
    if (g_children[i].compare_exchange_strong(free, pid)) return i;
  }
  return -1;
}

void unregister_child(int slot) {
  if (slot >= 0 && slot < kChildren) g_children[slot].store(0);
}

}  // namespace contact2d
