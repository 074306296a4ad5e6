// Numbers as text: the one formatter of the project (messages of the core,
// io, analysis, game, MuJoCo and CLI layers, tables and reports).
#pragma once

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

}  // namespace contact2d
