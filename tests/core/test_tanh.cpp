// The force stage's tanh (core/vector_math.hpp) on both paths against
// long-double tanh (x87 extended precision, 64-bit significand), on a dense
// grid of the arguments the friction and rolling laws use: α·v_t and
// α·R·ω, |x| from the smallest subnormal to 40 (beyond 22 every path
// returns ±1 exactly). tanhl is not correctly rounded itself: its error is
// a few ulps of long double, each 2⁻¹¹ ≈ 0.0005 of a double's ulp, so every
// measured figure below carries ±0.002 ULP (kReference).
//
// Error in ULP = |f(x) − tanhl(x)| / ulp(tanhl(x)), ulp(y) = 2^(e−52) for
// |y| in [2^e, 2^(e+1)) (the double spacing at the true value). Measured
// (build/tests/core/core_tests --gtest_filter='Tanh.*' prints them;
// docs/speed.md):
//   SLEEF Sleef_tanhd4_u10avx2  1.000 ULP (x = 1.19e-16: it returns the
//                               double above x, where tanh x rounds to x)
//   glibc tanh                  2.021 ULP (x = 0.25365; 2.02108 with 60-digit
//                               decimal arithmetic, so not tanhl's error)
// Asserted: SLEEF's documented bound, 1.0 ULP (+ kReference). glibc
// documents 2 ULP for tanh, but that figure (its libm-test-ulps) is the
// largest error its own test inputs showed, not a proof, and this grid finds
// 2.021: the scalar path is held to the measured 2.021 + kReference, which
// still fails on any change of libm that makes it worse.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "core/contact.hpp"
#include "core/vector_math.hpp"

namespace contact2d {
namespace {

// The grid: 0, ± a log-spaced sweep from 1e-320 to 40 (200 points per
// decade), and ± a uniform sweep of [0, 25] at spacing 2.5e-5 (1e6 points,
// every region of tanh: linear, the bend, the approach to ±1, saturation).
std::vector<double> grid() {
  std::vector<double> x{0.0};
  for (double e = -320.0; e <= std::log10(40.0); e += 1.0 / 200.0) {
    x.push_back(std::pow(10.0, e));
    x.push_back(-std::pow(10.0, e));
  }
  for (int i = 1; i <= 1000000; ++i) {
    x.push_back(2.5e-5 * i);
    x.push_back(-2.5e-5 * i);
  }
  return x;
}

double ulp_error(double got, double x) {
  const long double exact = tanhl(static_cast<long double>(x));
  if (exact == 0.0L) return got == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
  const double rounded = static_cast<double>(exact);
  const int e = std::max(std::ilogb(rounded), std::numeric_limits<double>::min_exponent - 1);
  const long double ulp = std::ldexp(1.0L, e - 52);
  return static_cast<double>(std::fabs(static_cast<long double>(got) - exact) / ulp);
}

constexpr double kReference = 0.002;  // tanhl's own error, in double ulps

struct Worst {
  double ulp = 0.0;
  double at = 0.0;
};

template <typename Path>
Worst worst_error(Path path) {
  const std::vector<double> x = grid();
  std::vector<double> y = x;
  path(y.data(), y.size());
  Worst w;
  for (size_t i = 0; i < x.size(); ++i) {
    const double err = ulp_error(y[i], x[i]);
    if (!(err <= w.ulp)) w = {err, x[i]};
  }
  return w;
}

TEST(Tanh, ScalarPathWithinGlibcsMeasuredBound) {
  const Worst w = worst_error(tanh_scalar);
  std::printf("glibc tanh: max error %.4f ULP at x = %.17g\n", w.ulp, w.at);
  EXPECT_LE(w.ulp, 2.021 + kReference) << "at x = " << w.at;
}

TEST(Tanh, VectorPathWithinSleefsDocumentedOneUlp) {
  if (!vector_tanh_available()) GTEST_SKIP() << "no AVX2 or no SLEEF in this build";
  const Worst w = worst_error(tanh_vector);
  std::printf("SLEEF Sleef_tanhd4_u10avx2: max error %.4f ULP at x = %.17g\n", w.ulp, w.at);
  EXPECT_LE(w.ulp, 1.0 + kReference) << "at x = " << w.at;
}

// The scalar path is the law's smooth_sign value for value (bit for bit
// what the force stage computed before the batch existed).
TEST(Tanh, ScalarPathIsSmoothSign) {
  for (double x : grid()) {
    double y = x;
    tanh_scalar(&y, 1);
    ASSERT_EQ(y, smooth_sign(x)) << x;
  }
}

// Saturation: ±1 exactly from |x| = 22 on both paths; NaN stays NaN; any
// count of values, including a partial last group of four.
TEST(Tanh, SaturationNanAndPartialGroups) {
  const TanhPath before = set_tanh_path(TanhPath::Vector);
  for (size_t n = 1; n <= 9; ++n) {
    std::vector<double> x(n);
    for (size_t i = 0; i < n; ++i) x[i] = (i % 2 ? -1.0 : 1.0) * (22.0 + static_cast<double>(i));
    tanh_batch(x.data(), n);
    for (size_t i = 0; i < n; ++i) EXPECT_EQ(x[i], i % 2 ? -1.0 : 1.0) << n << " " << i;
    std::vector<double> y(n, 0.5);
    y[n - 1] = std::numeric_limits<double>::quiet_NaN();
    tanh_batch(y.data(), n);
    EXPECT_TRUE(std::isnan(y[n - 1]));
    for (size_t i = 0; i + 1 < n; ++i) EXPECT_NEAR(y[i], std::tanh(0.5), 2.3e-16);
  }
  set_tanh_path(before);
}

// The perturbed paths move every unsaturated value by exactly one ulp.
TEST(Tanh, PerturbedPathsMoveOneUlp) {
  const TanhPath before = set_tanh_path(TanhPath::ScalarUlpUp);
  double x[3] = {0.3, -2.0, 30.0};
  tanh_batch(x, 3);
  EXPECT_EQ(x[0], std::nextafter(std::tanh(0.3), 2.0));
  EXPECT_EQ(x[1], std::nextafter(std::tanh(-2.0), 2.0));
  EXPECT_EQ(x[2], 1.0);
  set_tanh_path(TanhPath::ScalarUlpDown);
  double y[1] = {0.3};
  tanh_batch(y, 1);
  EXPECT_EQ(y[0], std::nextafter(std::tanh(0.3), -2.0));
  set_tanh_path(before);
}

}  // namespace
}  // namespace contact2d
