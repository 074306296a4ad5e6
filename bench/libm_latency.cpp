// contact2d_libm_latency: the latency of each accurate tanh and sin/cos this
// machine offers, measured the way a step pays for it — each call feeding
// the next (x ← 0.1 + 0.5·f(x), a fixed point inside the range a slowly
// slipping contact uses), so the time is the call's latency, not its
// throughput. docs/speed.md ("The targets, and why they are left") sets
// these against the 100× budget of a step: glibc's tanh and sin/cos (the
// reference's), and SLEEF's scalar and vector alternatives with their
// documented accuracy (u10: 1 ULP, u35: 3.5 ULP), and contact2d's own
// bounded_tanh (core/vector_math.hpp, ≤ 1.27 ULP). The "/exp_branch" pair
// runs the chain x ← 0.8 + 0.5·f(x), which settles at x ≈ 1.14, where
// bounded_tanh takes its exp branch (|x| ≥ 0.77); the plain chain settles
// at x ≈ 0.19, its rational branch. The FMA variants run only where the
// CPU has FMA (skipped otherwise), the AVX2 one only with AVX2.
//
//   build/bench/contact2d_libm_latency [--benchmark_min_time=0.5]
#include <benchmark/benchmark.h>

#include <cmath>
#include <string_view>

#include "core/vector_math.hpp"

#ifdef CONTACT2D_BENCH_SLEEF
#include <sleef.h>
// sleef.h declares its FMA variants only when this file is compiled with
// FMA (FP_FAST_FMA); it is not (the CPU check below decides at run time,
// and -mfma would let GCC fuse this file's own arithmetic), so they are
// declared here with the header's signatures.
extern "C" {
double Sleef_tanhd1_u10purecfma(double);
double Sleef_tanhd1_u35purecfma(double);
Sleef_double_2 Sleef_sincosd1_u10purecfma(double);
Sleef_double_2 Sleef_sincosd1_u35purecfma(double);
}
#endif

namespace {

template <typename F>
void chain(benchmark::State& state, F f) {
  double x = 0.3;
  for (auto _ : state) {
    x = 0.1 + 0.5 * f(x);
    benchmark::DoNotOptimize(x);
  }
}

bool cpu_has(const char* feature) {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_cpu_init();
  if (std::string_view(feature) == "fma") return __builtin_cpu_supports("fma") != 0;
  if (std::string_view(feature) == "avx2") return __builtin_cpu_supports("avx2") != 0;
#endif
  (void)feature;
  return false;
}

void glibc_tanh(benchmark::State& s) {
  chain(s, [](double x) { return std::tanh(x); });
}
template <typename F>
void exp_branch_chain(benchmark::State& state, F f) {
  double x = 1.0;
  for (auto _ : state) {
    x = 0.8 + 0.5 * f(x);
    benchmark::DoNotOptimize(x);
  }
}

void bounded_tanh(benchmark::State& s) {
  chain(s, [](double x) { return contact2d::bounded_tanh(x); });
}
void bounded_tanh_exp_branch(benchmark::State& s) {
  exp_branch_chain(s, [](double x) { return contact2d::bounded_tanh(x); });
}
void glibc_tanh_exp_branch(benchmark::State& s) {
  exp_branch_chain(s, [](double x) { return std::tanh(x); });
}
void glibc_exp(benchmark::State& s) {  // e^(−x): the chain settles at x ≈ 0.50
  chain(s, [](double x) { return std::exp(-x); });
}
void glibc_expm1(benchmark::State& s) {
  chain(s, [](double x) { return std::expm1(x); });
}
void glibc_sin_cos(benchmark::State& s) {  // GCC fuses the pair into one sincos
  chain(s, [](double x) { return std::sin(x) + std::cos(x); });
}

#ifdef CONTACT2D_BENCH_SLEEF
void sleef_tanh_u10_fma(benchmark::State& s) {
  if (!cpu_has("fma")) return s.SkipWithError("no FMA");
  chain(s, [](double x) { return Sleef_tanhd1_u10purecfma(x); });
}
void sleef_tanh_u35_fma(benchmark::State& s) {
  if (!cpu_has("fma")) return s.SkipWithError("no FMA");
  chain(s, [](double x) { return Sleef_tanhd1_u35purecfma(x); });
}
void sleef_tanh_u10_scalar(benchmark::State& s) {
  chain(s, [](double x) { return Sleef_tanh_u10(x); });
}
void sleef_sincos_u10_fma(benchmark::State& s) {
  if (!cpu_has("fma")) return s.SkipWithError("no FMA");
  chain(s, [](double x) {
    const auto r = Sleef_sincosd1_u10purecfma(x);
    return r.x + r.y;
  });
}
void sleef_sincos_u35_fma(benchmark::State& s) {
  if (!cpu_has("fma")) return s.SkipWithError("no FMA");
  chain(s, [](double x) {
    const auto r = Sleef_sincosd1_u35purecfma(x);
    return r.x + r.y;
  });
}
#endif

}  // namespace

BENCHMARK(glibc_tanh);
BENCHMARK(bounded_tanh);
BENCHMARK(glibc_tanh_exp_branch);
BENCHMARK(bounded_tanh_exp_branch);
BENCHMARK(glibc_exp);
BENCHMARK(glibc_expm1);
BENCHMARK(glibc_sin_cos);
#ifdef CONTACT2D_BENCH_SLEEF
BENCHMARK(sleef_tanh_u10_fma);
BENCHMARK(sleef_tanh_u35_fma);
BENCHMARK(sleef_tanh_u10_scalar);
BENCHMARK(sleef_sincos_u10_fma);
BENCHMARK(sleef_sincos_u35_fma);
#endif
BENCHMARK_MAIN();
