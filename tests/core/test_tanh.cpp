// The force stage's tanh (core/vector_math.hpp) on every path against
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

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
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

// The law's smooth_sign is the bounded path value for value (one
// implementation: core/contact.hpp calls bounded_tanh).
TEST(Tanh, BoundedPathIsSmoothSign) {
  for (double x : grid()) {
    double y = x;
    tanh_bounded(&y, 1);
    ASSERT_EQ(y, smooth_sign(x)) << x;
  }
}

// The default path is the bounded one (unless the environment asks for
// another: CONTACT2D_SCALAR_TANH, CONTACT2D_TANH).
TEST(Tanh, DefaultPathIsBounded) {
  if (std::getenv("CONTACT2D_SCALAR_TANH") != nullptr || std::getenv("CONTACT2D_TANH") != nullptr)
    GTEST_SKIP() << "the environment chooses the path";
  EXPECT_EQ(tanh_path(), TanhPath::Bounded);
}

// Saturation: ±1 exactly from |x| = 22 on every path; NaN stays NaN; any
// count of values, including a partial last group of four.
TEST(Tanh, SaturationNanAndPartialGroups) {
  const TanhPath before = tanh_path();
  for (TanhPath path : {TanhPath::Bounded, TanhPath::Scalar, TanhPath::Vector}) {
    set_tanh_path(path);
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

// contact2d's own tanh (bounded_tanh, core/vector_math.hpp) over the whole
// double range against tanhl. Its error bound is derived at the code: at
// most 1.27 ULP (1.265 on the rational branch |x| < 0.77, 1.254 on the exp
// branch, first order in 2⁻⁵³, glibc's exp taken at its documented 0.511
// ULP). The assertion is that bound plus tanhl's own error (kReference);
// nothing is widened to fit a measurement.
constexpr double kBoundedBound = 1.27;

// Positive arguments: a log-spaced sweep of [1e-300, 22] (2000 points per
// decade), 2000 uniform samples in every binade [2^e, 2^(e+1)) from the
// smallest subnormal's to [16, 32) (cut at 22; a fixed seed) and 10⁶ more
// in [0.5, 0.77], the neighbours of the branch cut 0.77, of tanh x = 1/2,
// of 22 and of the smallest normal; each is used with both signs.
std::vector<double> bounded_grid() {
  std::vector<double> x;
  for (double e = -300.0; e <= std::log10(22.0); e += 1.0 / 2000.0) x.push_back(std::pow(10.0, e));
  std::mt19937_64 rng(40);
  for (int e = -1074; e <= 4; ++e) {
    std::uniform_real_distribution<double> in_binade(std::ldexp(1.0, e), std::ldexp(1.0, e + 1));
    for (int i = 0; i < 2000; ++i) {
      const double v = in_binade(rng);
      if (v < 22.0) x.push_back(v);
    }
  }
  // … and 10⁶ uniform samples of [0.5, 0.77], where the rational branch's
  // rounding is largest (its bound's maximum is at the cut).
  std::uniform_real_distribution<double> peak(0.5, 0.77);
  for (int i = 0; i < 1000000; ++i) x.push_back(peak(rng));
  for (double centre : {0.77, 0.54930614433405489, 22.0, std::numeric_limits<double>::min()}) {
    double v = centre;
    for (int i = 0; i < 5000; ++i) v = std::nextafter(v, 0.0);
    for (int i = 0; i < 10000; ++i, v = std::nextafter(v, 30.0)) x.push_back(v);
  }
  x.push_back(std::numeric_limits<double>::denorm_min());
  x.push_back(22.0);
  return x;
}

std::uint64_t bits(double v) {
  std::uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

TEST(BoundedTanh, WithinItsDerivedBoundOverTheWholeRange) {
  const std::vector<double> x = bounded_grid();
  Worst w;
  for (double v : x) {
    for (double s : {v, -v}) {
      const double err = ulp_error(bounded_tanh(s), s);
      if (!(err <= w.ulp)) w = {err, s};
    }
  }
  std::printf("bounded_tanh: max error %.4f ULP at x = %.17g over %zu arguments\n", w.ulp, w.at,
              2 * x.size());
  EXPECT_LE(w.ulp, kBoundedBound + kReference) << "at x = " << w.at;
  // The test's own coarse grid (the one every path is measured on) too.
  const Worst g = worst_error(tanh_bounded);
  std::printf("bounded_tanh on the common grid: max error %.4f ULP at x = %.17g\n", g.ulp, g.at);
  EXPECT_LE(g.ulp, kBoundedBound + kReference) << "at x = " << g.at;
}

TEST(BoundedTanh, SpecialValues) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(bits(bounded_tanh(0.0)), bits(0.0));
  EXPECT_EQ(bits(bounded_tanh(-0.0)), bits(-0.0));
  EXPECT_EQ(bounded_tanh(inf), 1.0);
  EXPECT_EQ(bounded_tanh(-inf), -1.0);
  EXPECT_TRUE(std::isnan(bounded_tanh(std::numeric_limits<double>::quiet_NaN())));
  EXPECT_TRUE(std::isnan(bounded_tanh(-std::numeric_limits<double>::quiet_NaN())));
  EXPECT_EQ(bounded_tanh(22.0), 1.0);
  EXPECT_EQ(bounded_tanh(-22.0), -1.0);
  EXPECT_EQ(bounded_tanh(1e300), 1.0);
  // Just below 22 tanh rounds to 1 as well (1 − tanh x < 1.6e-19).
  EXPECT_EQ(bounded_tanh(std::nextafter(22.0, 0.0)), 1.0);
  // Subnormals and the tiny: tanh x rounds to x itself.
  for (double v : {std::numeric_limits<double>::denorm_min(), 1e-310, 2.2e-308, 1e-200, 1e-9}) {
    EXPECT_EQ(bounded_tanh(v), v) << v;
    EXPECT_EQ(bounded_tanh(-v), -v) << v;
  }
}

// Exact odd symmetry and |tanh| ≤ 1 on the whole grid; monotone
// non-decreasing over the dense sweeps (the log sweep and the common grid's
// uniform sweep of [−25, 25], sorted). Between neighbouring doubles a ≤ 1.27
// ULP approximation need not be monotone where tanh rises by less than an
// ulp per ulp of x: among the 4e6 neighbours of the cut 0.77 it steps down
// twice, by one ulp each (measured), which the last check bounds.
TEST(BoundedTanh, OddBoundedAndMonotone) {
  std::vector<double> x = bounded_grid();
  for (double v : grid()) x.push_back(v);
  for (double v : x) {
    const double y = bounded_tanh(v);
    ASSERT_EQ(bits(bounded_tanh(-v)), bits(-y)) << v;
    ASSERT_LE(std::fabs(y), 1.0) << v;
  }
  std::vector<double> sweep;
  for (double e = -300.0; e <= std::log10(40.0); e += 1.0 / 2000.0) {
    sweep.push_back(std::pow(10.0, e));
    sweep.push_back(-std::pow(10.0, e));
  }
  for (double v : grid()) sweep.push_back(v);
  std::sort(sweep.begin(), sweep.end());
  for (size_t i = 1; i < sweep.size(); ++i)
    ASSERT_LE(bounded_tanh(sweep[i - 1]), bounded_tanh(sweep[i]))
        << sweep[i - 1] << " " << sweep[i];
  double v = 0.77;
  for (int i = 0; i < 2000000; ++i) v = std::nextafter(v, 0.0);
  double previous = bounded_tanh(v);
  int down = 0;
  for (int i = 0; i < 4000000; ++i) {
    v = std::nextafter(v, 1.0);
    const double y = bounded_tanh(v);
    if (y < previous) {
      ++down;
      EXPECT_EQ(std::nextafter(previous, 0.0), y) << "a step down of more than one ulp at " << v;
    }
    previous = y;
  }
  EXPECT_LE(down, 8);
}

}  // namespace
}  // namespace contact2d
