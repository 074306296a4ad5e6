// tanh for the force stage, many values at once (docs/speed.md).
//
// Every friction and rolling-resistance law takes tanh of one argument per
// contact (core/contact.hpp). The force stage gathers those arguments and
// calls tanh_batch once per force evaluation, which evaluates them on one of
// two paths chosen once, at the first call:
//
//   scalar  glibc's tanh, one value at a time (documented bound 2 ULP): bit
//           for bit what contact2d computed before the vector path existed.
//           The default: a step is one chain of dependent operations, and
//           on the machine measured in docs/speed.md glibc's tanh has the
//           shorter latency, so it gives the faster step.
//   vector  SLEEF's Sleef_tanhd4_u10avx2, four values per call, documented
//           error bound 1.0 ULP; taken when CONTACT2D_TANH=vector is set in
//           the environment and the CPU has AVX2 (__builtin_cpu_supports),
//           or by set_tanh_path. CONTACT2D_SCALAR_TANH=1 forces the scalar
//           path whatever else is set.
//
// On both paths |x| ≥ 22 gives exactly ±1 without a call: 1 − tanh|x| <
// 2·e⁻⁴⁴ ≈ 1.6e-19 is far below half an ulp of 1, so ±1 is the correctly
// rounded value (core/contact.hpp, smooth_sign). tests/core/test_tanh.cpp
// measures both paths against long-double tanh.
//
// Two more paths exist for the perturbation study (bench/tanh_perturbation):
// the scalar result moved by one ulp up or down (std::nextafter) wherever
// |x| < 22, to show how far one ulp of tanh moves a trajectory; and moved
// up or down at random, value by value (SplitMix64 from a seed), which is
// what two accurate libraries' differences look like.
#pragma once

#include <cstddef>

namespace contact2d {

enum class TanhPath { Scalar, Vector, ScalarUlpUp, ScalarUlpDown, ScalarUlpRandom };

// The path tanh_batch uses (chosen at the first call, unless set).
TanhPath tanh_path();
// Chooses the path for the rest of the process (tests, the perturbation
// study); Vector falls back to Scalar when the CPU has no AVX2. Returns the
// path in force before.
TanhPath set_tanh_path(TanhPath path);
// True when this build and this CPU can take the vector path.
bool vector_tanh_available();
const char* tanh_path_name(TanhPath path);
// Restarts ScalarUlpRandom's sequence of up/down choices from `seed`.
void set_tanh_perturbation_seed(unsigned long long seed);

// x[i] ← tanh(x[i]) for i < n, in place, on the current path. Allocation-free.
void tanh_batch(double* x, std::size_t n);

// The two paths directly (tests): in place, as tanh_batch would.
void tanh_scalar(double* x, std::size_t n);
void tanh_vector(double* x, std::size_t n);  // requires vector_tanh_available()

}  // namespace contact2d
