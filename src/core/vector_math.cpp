#include "core/vector_math.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>

namespace contact2d {

#ifdef CONTACT2D_WITH_SLEEF
namespace detail {
void sleef_tanh4(const double* in, double* out);  // core/vector_math_avx2.cpp
}
#endif

namespace {

// The saturation threshold of core/contact.hpp's smooth_sign: ±1 exactly.
constexpr double kSaturated = 22.0;

// The bounded path unless the environment asks for another: a step is one
// chain of dependent operations, and on the machine of docs/speed.md
// bounded_tanh has the shortest latency (bench: floor/bounded_tanh against
// floor/libm_tanh and floor/vector_tanh4). CONTACT2D_SCALAR_TANH=1 forces
// glibc's scalar tanh whatever CONTACT2D_TANH says; CONTACT2D_TANH=scalar
// asks for it too, CONTACT2D_TANH=vector for SLEEF (when the CPU has AVX2).
TanhPath initial_path() {
  const char* forced = std::getenv("CONTACT2D_SCALAR_TANH");
  if (forced != nullptr && *forced != '\0' && std::strcmp(forced, "0") != 0)
    return TanhPath::Scalar;
  const char* wanted = std::getenv("CONTACT2D_TANH");
  if (wanted != nullptr && std::strcmp(wanted, "scalar") == 0) return TanhPath::Scalar;
  if (wanted != nullptr && std::strcmp(wanted, "vector") == 0 && vector_tanh_available())
    return TanhPath::Vector;
  return TanhPath::Bounded;
}

std::atomic<TanhPath>& path_slot() {
  static std::atomic<TanhPath> path{initial_path()};
  return path;
}

// ScalarUlpRandom's generator (the perturbation study only, single thread).
unsigned long long random_state = 0;

double scalar_tanh(double x) {
  if (x >= kSaturated) return 1.0;
  if (x <= -kSaturated) return -1.0;
  return std::tanh(x);
}

}  // namespace

bool vector_tanh_available() {
#if defined(CONTACT2D_WITH_SLEEF) && (defined(__x86_64__) || defined(__i386__))
  static const bool avx2 = [] {
    __builtin_cpu_init();  // harmless when libgcc's constructor already ran it
    return __builtin_cpu_supports("avx2") != 0;
  }();
  return avx2;
#else
  return false;
#endif
}

TanhPath tanh_path() { return path_slot().load(std::memory_order_relaxed); }

TanhPath set_tanh_path(TanhPath path) {
  if (path == TanhPath::Vector && !vector_tanh_available()) path = TanhPath::Bounded;
  return path_slot().exchange(path);
}

const char* tanh_path_name(TanhPath path) {
  switch (path) {
    case TanhPath::Bounded: return "bounded (contact2d's own tanh, <= 1.27 ULP)";
    case TanhPath::Scalar: return "scalar (glibc tanh)";
    case TanhPath::Vector: return "vector (SLEEF Sleef_tanhd4_u10avx2)";
    case TanhPath::ScalarUlpUp: return "scalar + 1 ulp";
    case TanhPath::ScalarUlpDown: return "scalar - 1 ulp";
    case TanhPath::ScalarUlpRandom: return "scalar +/- 1 ulp at random";
  }
  return "?";
}

void set_tanh_perturbation_seed(unsigned long long seed) { random_state = seed; }

void tanh_bounded(double* x, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) x[i] = bounded_tanh(x[i]);
}

void tanh_scalar(double* x, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) x[i] = scalar_tanh(x[i]);
}

void tanh_vector(double* x, std::size_t n) {
#ifdef CONTACT2D_WITH_SLEEF
  for (std::size_t i = 0; i < n; i += 4) {
    const std::size_t m = std::min<std::size_t>(4, n - i);
    double in[4] = {0.0, 0.0, 0.0, 0.0};
    double out[4] = {0.0, 0.0, 0.0, 0.0};
    bool needed = false;  // a chain of saturated values needs no call
    for (std::size_t j = 0; j < m; ++j) {
      in[j] = x[i + j];
      needed |= !(std::fabs(in[j]) >= kSaturated);  // NaN goes to SLEEF too
    }
    if (needed) detail::sleef_tanh4(in, out);
    for (std::size_t j = 0; j < m; ++j)
      x[i + j] = std::fabs(in[j]) >= kSaturated ? std::copysign(1.0, in[j]) : out[j];
  }
#else
  tanh_scalar(x, n);
#endif
}

void tanh_batch(double* x, std::size_t n) {
  if (n == 0) return;
  switch (tanh_path()) {
    case TanhPath::Bounded: tanh_bounded(x, n); return;
    case TanhPath::Vector: tanh_vector(x, n); return;
    case TanhPath::Scalar: tanh_scalar(x, n); return;
    case TanhPath::ScalarUlpUp:
    case TanhPath::ScalarUlpDown:
    case TanhPath::ScalarUlpRandom: {
      const TanhPath path = tanh_path();
      for (std::size_t i = 0; i < n; ++i) {
        const bool saturated = std::fabs(x[i]) >= kSaturated;
        x[i] = scalar_tanh(x[i]);
        if (saturated) continue;
        bool up = path == TanhPath::ScalarUlpUp;
        if (path == TanhPath::ScalarUlpRandom) {  // SplitMix64
          unsigned long long z = (random_state += 0x9E3779B97F4A7C15ull);
          z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
          z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
          up = ((z ^ (z >> 31)) >> 63) != 0;
        }
        x[i] = std::nextafter(x[i], up ? 2.0 : -2.0);
      }
      return;
    }
  }
}

}  // namespace contact2d
