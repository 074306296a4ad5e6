// Ctrl-C in Python while the program's code runs.
//
// Python handles a signal only on its main thread and only between
// bytecodes: a run of many seconds inside the extension would take Ctrl-C
// only when it ends. So interruptible(work) releases the GIL, hands `work`
// to a worker thread and, while it waits, asks Python every 20 ms whether a
// signal came (PyErr_CheckSignals). When one raised (KeyboardInterrupt for
// Ctrl-C, or what the user's own handler raises), it requests the work's end
// (core/cancel.hpp: the run loop looks every 1024 steps, the converged
// solution every step, MuJoCo's settling every 1024 steps), waits for it and
// raises that exception; what the work had produced is dropped.
//
// The worker is one thread per calling thread, kept while that thread lives:
// MuJoCo 3 keeps one Node process per thread (mujoco3/node_mujoco.hpp), and a
// thread per call would start a new one every call.
#pragma once

#include <pybind11/pybind11.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>

#include "core/cancel.hpp"

namespace contact2d::python {

class Worker {
 public:
  Worker() : thread_([this] { loop(); }) {}
  ~Worker() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
  }
  Worker(const Worker&) = delete;
  Worker& operator=(const Worker&) = delete;

  // Runs `task` (which must not throw) on the worker thread.
  void start(std::function<void()> task) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      task_ = std::move(task);
      done_ = false;
    }
    wake_.notify_all();
  }
  // Whether the task ended within `timeout`.
  bool wait_for(std::chrono::milliseconds timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    return finished_.wait_for(lock, timeout, [this] { return done_; });
  }

 private:
  void loop() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      wake_.wait(lock, [this] { return stop_ || task_; });
      if (stop_) return;
      std::function<void()> task = std::move(task_);
      task_ = nullptr;
      lock.unlock();
      task();
      lock.lock();
      done_ = true;
      finished_.notify_all();
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_, finished_;
  std::function<void()> task_;
  bool done_ = true;
  bool stop_ = false;
  std::thread thread_;  // last: started once the members above exist
};

// The calls of interruptible() in progress, in every thread. A Ctrl-C's
// cancel request ends them all (core/cancel.hpp's one flag), so it is
// cleared when the last of them ends, not by the thread that took the
// signal: cleared as soon as that thread's own work stopped, another
// thread's run could miss it between two of its checks and go on (measured:
// a worker still running 60 s after the main thread's KeyboardInterrupt).
inline std::atomic<int>& calls_in_progress() {
  static std::atomic<int> calls{0};
  return calls;
}

// The calling thread's worker: one for every call of interruptible() on
// this thread, whatever the work (a thread_local inside the template would
// be one per instantiation, each with its own Node process).
inline Worker& this_threads_worker() {
  thread_local Worker worker;
  return worker;
}

// work() on the calling thread's worker, with Python's signals polled while
// it runs; returns its result or rethrows its exception. Call with the GIL
// held.
template <typename F>
auto interruptible(F&& work) -> decltype(work()) {
  namespace py = pybind11;
  Worker& worker = this_threads_worker();
  std::optional<decltype(work())> result;
  std::exception_ptr error;
  bool interrupted = false;
  calls_in_progress().fetch_add(1);
  {
    py::gil_scoped_release release;
    worker.start([&] {
      try {
        result.emplace(work());
      } catch (...) {
        error = std::current_exception();
      }
    });
    while (!worker.wait_for(std::chrono::milliseconds(20))) {
      if (interrupted) continue;
      py::gil_scoped_acquire acquire;
      if (PyErr_CheckSignals() != 0) {  // the handler's exception stays set
        interrupted = true;
        request_cancel();
      }
    }
  }
  // The last call to end takes the cancel request away (see above).
  if (calls_in_progress().fetch_sub(1) == 1 && cancel_requested()) clear_cancel();
  if (interrupted) throw py::error_already_set();
  if (error) std::rethrow_exception(error);
  return std::move(*result);
}

}  // namespace contact2d::python
