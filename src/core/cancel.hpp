// A request to stop long work early, made from another thread: the Python
// module's Ctrl-C (src/python/module.cpp runs the work on a thread of its own
// and polls Python's signals while it waits). The loops that can run for
// long — the run loop (core/run.hpp), the converged solution's steps, MuJoCo
// settling a model — call throw_if_cancelled() and end with Cancelled.
//
// The command line never requests it: an interrupt there ends the program
// (io/interrupt.hpp). One flag for the process: a Ctrl-C stops every run in
// progress, as it would at a terminal.
#pragma once

#include <atomic>
#include <stdexcept>

namespace contact2d {

struct Cancelled : std::runtime_error {
  Cancelled() : std::runtime_error("cancelled") {}
};

namespace detail {
inline std::atomic<bool> cancel_flag{false};
}  // namespace detail

inline void request_cancel() { detail::cancel_flag.store(true, std::memory_order_relaxed); }
inline void clear_cancel() { detail::cancel_flag.store(false, std::memory_order_relaxed); }
inline bool cancel_requested() { return detail::cancel_flag.load(std::memory_order_relaxed); }
inline void throw_if_cancelled() {
  if (cancel_requested()) throw Cancelled();
}

}  // namespace contact2d
