// One number as text through a printf format, e.g. format_number("%g", 1e-4).
// Shared by the messages of the core, io, analysis and game layers.
#pragma once

#include <cstdio>
#include <string>

namespace contact2d {

inline std::string format_number(const char* fmt, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, fmt, value);
  return buffer;
}

}  // namespace contact2d
