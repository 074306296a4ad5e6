// tanh for the force stage, many values at once (docs/speed.md).
//
// Every friction and rolling-resistance law takes tanh of one argument per
// contact (core/contact.hpp). The force stage gathers those arguments and
// calls tanh_batch once per force evaluation, which evaluates them on one of
// three paths chosen once, at the first call:
//
//   bounded contact2d's own tanh, bounded_tanh below (proven bound 1.27 ULP,
//           measured in tests/core/test_tanh.cpp). The default, and the
//           law's own function (smooth_sign, core/contact.hpp): a step is
//           one chain of dependent operations, and bounded_tanh has about
//           half glibc's latency on that chain (docs/speed.md).
//   scalar  glibc's tanh, one value at a time (documented 2 ULP, measured
//           2.021): what contact2d computed before the bounded path existed.
//           Taken when CONTACT2D_SCALAR_TANH=1 (which wins over everything
//           else) or CONTACT2D_TANH=scalar is set in the environment.
//   vector  SLEEF's Sleef_tanhd4_u10avx2, four values per call, documented
//           error bound 1.0 ULP; taken when CONTACT2D_TANH=vector is set
//           and the CPU has AVX2 (__builtin_cpu_supports), or by
//           set_tanh_path.
//
// On every path |x| ≥ 22 gives exactly ±1 without a call: 1 − tanh|x| <
// 2·e⁻⁴⁴ ≈ 1.6e-19 is far below half an ulp of 1, so ±1 is the correctly
// rounded value. tests/core/test_tanh.cpp measures every path against
// long-double tanh.
//
// Two more paths exist for the perturbation study (bench/tanh_perturbation):
// glibc's result moved by one ulp up or down (std::nextafter) wherever
// |x| < 22, to show how far one ulp of tanh moves a trajectory; and moved
// up or down at random, value by value (SplitMix64 from a seed), which is
// what two accurate libraries' differences look like.
#pragma once

#include <cmath>
#include <cstddef>

namespace contact2d {

// tanh(x) with |error| ≤ 1.27 ULP for every double x (ULP: the spacing of
// doubles at the true value), exact odd symmetry, ±1 exactly at |x| ≥ 22,
// NaN → NaN, ±0 → ±0. It works on a = |x| and gives the result x's sign.
//
//   a < 0.77:  tanh a = a + a·z·P(z)/Q(z),  z = a²,
//     P(z) = p0 + p1·z + p2·z² + p3·z³,  Q(z) = 1 + q1·z + q2·z² + q3·z³:
//     the (3, 3) minimax rational approximation of (tanh(√z)/√z − 1)/z in
//     relative error on z ∈ [0, 0.85²] (Remez, 90-digit arithmetic): its
//     error is 2.9e-19 relative, with the coefficients rounded to the
//     doubles below at most 0.055 ULP of tanh on a < 0.77 (the rounding of
//     p0 = −1/3 is most of it). P and Q are evaluated by Estrin's scheme,
//     (c0 + c1·z) + z²·(c2 + c3·z), which puts 3 operations instead of 6
//     on the chain.
//   a ≥ 0.77:  tanh a = 1 − 2/(e^(2a) + 1), with glibc's exp (documented
//     0.511 ULP without FMA, 0.509 with it: sysdeps/ieee754/dbl-64/
//     e_exp_data.c, "ulp error: 0.509 (0.511 without fma)"; 2a is exact).
//     From a = 19.1 on, 2/(e^(2a) + 1) < 2⁻⁵⁴ and the result rounds to 1.
//
// The bound, to first order in u = 2⁻⁵³ (second-order terms are ~u² of the
// result, 1e-16 ULP), in units of ulp(tanh a):
//   - rational branch: the computed correction y = a·z·P/Q carries each
//     operation's rounding, ≤ ulp(v)/2 for an intermediate v, times
//     |∂y/∂v| (13 operations: z, z², the 4 + 4 of P and Q, a·z, the
//     product, the quotient), at most 0.710 ULP of tanh a in total; the
//     rational approximation with double coefficients adds ≤ 0.055, and
//     the final a + y rounds by ≤ 0.5: ≤ 1.265 at a = 0.770. The
//     correction is at most (a − tanh a)/tanh a ≤ 19 % of the result, which
//     is what keeps the 13 roundings small.
//   - exp branch, E = e^(2a), s = E + 1, q = 2/s: exp's 0.511·ulp(E) moves
//     q by 2·0.511·ulp(E)/s²; rounding s by ulp(s)/2 moves q by
//     ulp(s)/s²; the quotient rounds by ulp(q)/2; 1 − q by ulp/2:
//     ≤ 1.254 at a = 0.77, falling to 0.5 as a grows.
//   Both maxima were taken over 6000 points of each branch (90-digit
//   arithmetic, mpmath), the ends and
//   the crossing of tanh a = 1/2 (where ulp(tanh a) halves) included; the
//   cut 0.77 is where the two branches' bounds meet. Total: 1.27 ULP.
//   For |x| < 2⁻²⁷ the result is x itself, without arithmetic: tanh x =
//   x·(1 − x²/3 + …) with x²/3 < 2⁻⁵⁴/3, less than half the spacing of the
//   doubles next to x (≥ 2⁻⁵⁴·|x|), so x is the correctly rounded value
//   (±0 and subnormals included). The first-order sum above is for the
//   rational branch from there on, where no intermediate underflows.
//
// The arithmetic must be evaluated as written (no -ffast-math: it would
// reassociate; FMA contraction would only remove roundings from the sum
// above). 4 comparisons, no call on |x| < 0.77, one exp call beyond.
inline double bounded_tanh(double x) {
  const double a = std::fabs(x);
  if (a >= 22.0) return std::copysign(1.0, x);
  if (a < 0x1p-27) return x;  // a contact at rest (v_t = 0) pays no arithmetic
  double t;
  if (a < 0.77) {
    const double z = a * a;
    const double z2 = z * z;
    const double p = (-0x1.5555555555555p-2 + -0x1.5ed88403e05cap-6 * z) +
                     z2 * (-0x1.fea3333b76333p-13 + -0x1.29ea01f3b3aa6p-26 * z);
    const double q =
        (1.0 + 0x1.db62325a53aaep-2 * z) + z2 * (0x1.91c67e4c09ce4p-6 + 0x1.0ae56587bc992p-12 * z);
    t = a + (a * z) * p / q;
  } else {
    t = 1.0 - 2.0 / (std::exp(2.0 * a) + 1.0);  // NaN goes here and stays NaN
  }
  return std::copysign(t, x);
}

enum class TanhPath { Bounded, Scalar, Vector, ScalarUlpUp, ScalarUlpDown, ScalarUlpRandom };

// The path tanh_batch uses (chosen at the first call, unless set).
TanhPath tanh_path();
// Chooses the path for the rest of the process (tests, the perturbation
// study); Vector falls back to Bounded when the CPU has no AVX2. Returns
// the path in force before.
TanhPath set_tanh_path(TanhPath path);
// True when this build and this CPU can take the vector path.
bool vector_tanh_available();
const char* tanh_path_name(TanhPath path);
// Restarts ScalarUlpRandom's sequence of up/down choices from `seed`.
void set_tanh_perturbation_seed(unsigned long long seed);

// x[i] ← tanh(x[i]) for i < n, in place, on the current path. Allocation-free.
void tanh_batch(double* x, std::size_t n);

// The three paths directly (tests): in place, as tanh_batch would.
void tanh_bounded(double* x, std::size_t n);
void tanh_scalar(double* x, std::size_t n);
void tanh_vector(double* x, std::size_t n);  // requires vector_tanh_available()

}  // namespace contact2d
