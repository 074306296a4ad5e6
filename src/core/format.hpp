// Numbers as text: the one formatter of the project (messages of the core,
// io, analysis, game, MuJoCo and CLI layers, tables and reports).
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace contact2d {

// printf-style formatting into a string (at most 255 characters kept).
template <typename... Args>
std::string format_text(const char* fmt, Args... args) {
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, fmt, args...);
  return buffer;
}

// One number through a printf format, e.g. format_number("%g", 1e-4).
inline std::string format_number(const char* fmt, double value) { return format_text(fmt, value); }

// "%.<digits>g": 6 significant digits by default. Also a valid TOML number
// (inf and nan included).
inline std::string format_number(double value, int digits = 6) {
  return format_text("%.*g", digits, value);
}

// The shortest "%.<n>g" with n ≥ min_digits that reads back as the same double.
inline std::string format_shortest(double value, int min_digits = 1) {
  std::string text;
  for (int digits = min_digits; digits <= 17; ++digits) {
    text = format_number(value, digits);
    if (std::strtod(text.c_str(), nullptr) == value) break;
  }
  return text;
}

// A duration for people: "850 µs", "12.3 ms", "4.56 s", "2 min 05 s",
// "1 h 03 min" (never "1e+03 ms"); "-" when negative or not finite.
inline std::string format_duration(double seconds) {
  if (!(seconds >= 0.0) || seconds > 1e15) return "-";
  if (seconds < 0.9995e-3) return format_text("%.3g µs", seconds * 1e6);
  if (seconds < 0.9995) return format_text("%.3g ms", seconds * 1e3);
  if (seconds < 59.95) return format_text("%.3g s", seconds);
  const long long whole = std::llround(seconds);
  if (whole < 3600) return format_text("%lld min %02lld s", whole / 60, whole % 60);
  const long long minutes = (whole + 30) / 60;
  return format_text("%lld h %02lld min", minutes / 60, minutes % 60);
}

}  // namespace contact2d
