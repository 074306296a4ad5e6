// The one JSON writer (io/json.hpp): every control character escaped (a raw
// tab or newline inside a string is not JSON), numbers that read back, and
// null for what JSON cannot hold.
#include <gtest/gtest.h>

#include <cstdlib>
#include <limits>
#include <string>

#include "io/json.hpp"

namespace contact2d {
namespace {

TEST(Json, EscapesQuotesBackslashesAndEveryControlCharacter) {
  EXPECT_EQ(json::string("a\"b\\c"), "\"a\\\"b\\\\c\"");
  EXPECT_EQ(json::string("tab\there\nnew\rline"), "\"tab\\there\\nnew\\rline\"");
  EXPECT_EQ(json::string(std::string("\b\f\x01\x1f", 4)), "\"\\b\\f\\u0001\\u001f\"");
  EXPECT_EQ(json::string("µ·Δt ≤ 1"), "\"µ·Δt ≤ 1\"");  // UTF-8 passes through
  for (int c = 0; c < 0x20; ++c) {
    const std::string out = json::string(std::string(1, static_cast<char>(c)));
    for (char ch : out) EXPECT_GE(static_cast<unsigned char>(ch), 0x20) << "control " << c;
  }
}

TEST(Json, NumbersReadBackAndNonFiniteIsNull) {
  for (double v : {0.1, 1.0 / 3.0, 6.02214076e23, -2.5e-300, 10000.0}) {
    EXPECT_EQ(std::strtod(json::number(v).c_str(), nullptr), v) << json::number(v);
  }
  EXPECT_EQ(json::number(10000.0), "10000");  // integers without an exponent
  EXPECT_EQ(json::number(0.1), "0.1");
  EXPECT_EQ(json::number(1.0 / 3.0, 10), "0.3333333333");
  EXPECT_EQ(json::number(std::numeric_limits<double>::quiet_NaN()), "null");
  EXPECT_EQ(json::number(std::numeric_limits<double>::infinity(), 10), "null");
}

}  // namespace
}  // namespace contact2d
