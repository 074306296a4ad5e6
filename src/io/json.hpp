// JSON text for the program's --json outputs: one escaper and one number
// writer, so that every subcommand prints the same JSON for the same value.
//
// Strings are escaped as RFC 8259 asks: the quotation mark and the reverse
// solidus with a backslash, the control characters below U+0020 as \b, \f,
// \n, \r, \t or \u00XX; every other byte (UTF-8 included) as it is.
// Numbers that are not finite have no JSON form and are written as null.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "core/format.hpp"

namespace contact2d::json {

inline std::string string(const std::string& text) {
  std::string out = "\"";
  for (const char ch : text) {
    switch (ch) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\b': out += "\\b"; break;
      case '\f': out += "\\f"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(ch) < 0x20) {
          char code[8];
          std::snprintf(code, sizeof code, "\\u%04x", static_cast<unsigned>(ch));
          out += code;
        } else {
          out += ch;
        }
    }
  }
  return out + "\"";
}

// The shortest text that reads back as the same double (an integer below
// 1e15 without exponent: 10000, not 1e+04); null when not finite.
inline std::string number(double v) {
  if (!std::isfinite(v)) return "null";
  if (v == std::trunc(v) && std::abs(v) < 1e15) return format_number("%.0f", v);
  return format_shortest(v);
}

// "%.<digits>g"; null when not finite.
inline std::string number(double v, int digits) {
  return std::isfinite(v) ? format_number(v, digits) : "null";
}

// {"name": value, …}: named numbers in the order given.
inline std::string object(const std::vector<std::pair<std::string, double>>& members) {
  std::string out = "{";
  for (size_t i = 0; i < members.size(); ++i)
    out += (i ? ", " : "") + string(members[i].first) + ": " + number(members[i].second);
  return out + "}";
}

}  // namespace contact2d::json
