#include "analysis/engine.hpp"

#include <sched.h>

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace contact2d::analysis {

EngineRunner registry_runner() {
  return [](const std::string& engine, const Scene& scene) {
    return engines::run_engine(engine, scene);
  };
}

double nominal_order(Integrator integrator) { return integrator == Integrator::RK4 ? 4.0 : 1.0; }

// The cores this thread may run on (its CPU affinity, which taskset, a Slurm
// job's CPU set or a container's narrows), else the machine's: one thread per
// core the scheduler will actually give us, not per core the machine has.
unsigned default_threads() {
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof(allowed), &allowed) == 0) {
    const int n = CPU_COUNT(&allowed);
    if (n > 0) return static_cast<unsigned>(n);
  }
  const unsigned n = std::thread::hardware_concurrency();
  return n == 0 ? 1 : n;
}

void parallel_for(size_t n, unsigned threads, const std::function<void(size_t)>& task) {
  if (threads == 0) threads = default_threads();
  if (threads > n) threads = static_cast<unsigned>(n);
  std::atomic<size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto worker = [&](size_t i) {
    for (; i < n; i = next++) {
      try {
        task(i);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
      }
    }
  };
  const size_t first = next++;  // taken before any other thread starts
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back([&] { worker(next++); });
  worker(first);
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace contact2d::analysis

namespace contact2d::analysis {

std::vector<Integrator> parse_integrators(const std::vector<std::string>& names) {
  std::vector<Integrator> out;
  for (const std::string& name : names) {
    const std::optional<Integrator> integrator = parse_integrator(name);
    if (!integrator) {
      throw std::invalid_argument("--integrators: '" + name +
                                  "' is not an integrator (explicit_euler, semi_implicit_euler, "
                                  "implicit_euler, rk4)");
    }
    if (std::find(out.begin(), out.end(), *integrator) == out.end()) out.push_back(*integrator);
  }
  return out;
}

}  // namespace contact2d::analysis
