// Durations for people (core/format.hpp): the unit follows the size, and no
// value is ever shown in exponent form ("1e+03 ms" was the bug).
#include <gtest/gtest.h>

#include <cmath>

#include "core/format.hpp"

namespace contact2d {
namespace {

TEST(FormatDuration, PicksTheUnitBySize) {
  EXPECT_EQ(format_duration(0.0), "0 µs");
  EXPECT_EQ(format_duration(8.5e-4), "850 µs");
  EXPECT_EQ(format_duration(0.0125), "12.5 ms");
  EXPECT_EQ(format_duration(0.9996), "1 s");  // not "1e+03 ms"
  EXPECT_EQ(format_duration(4.561), "4.56 s");
  EXPECT_EQ(format_duration(59.97), "1 min 00 s");
  EXPECT_EQ(format_duration(125.0), "2 min 05 s");
  EXPECT_EQ(format_duration(1000.0), "16 min 40 s");
  EXPECT_EQ(format_duration(3725.0), "1 h 02 min");
  EXPECT_EQ(format_duration(-1.0), "-");
  EXPECT_EQ(format_duration(std::nan("")), "-");
}

}  // namespace
}  // namespace contact2d
