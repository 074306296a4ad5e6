#include "io/toml_table.hpp"

#include <algorithm>
#include <cctype>
#include <sstream>

#include "io/scene_file.hpp"

namespace contact2d {
namespace {

std::string type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a number";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::array: return "an array";
    case toml::node_type::table: return "a table";
    default: return "a date or time";
  }
}

}  // namespace

void check_toml_shape(const std::string& text, const std::string& origin) {
  // Outside strings and comments: the dots of one run of key characters
  // (bare-key characters, dots, blanks and quoted parts: a.b, "a" . 'b'),
  // and how deep brackets and braces nest. A float has one dot, a date one.
  int line = 1, dots = 0, depth = 0;
  auto refuse = [&](const std::string& what) {
    throw InputError(origin + ":" + std::to_string(line) + ": " + what);
  };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char ch = text[i];
    if (ch == '"' || ch == '\'') {  // a string: skipped whole, the run goes on
      const bool multi = text.compare(i, 3, std::string(3, ch)) == 0;
      const std::string close = multi ? std::string(3, ch) : std::string(1, ch);
      std::size_t j = i + close.size();
      for (; j < text.size(); ++j) {
        if (text[j] == '\n') {
          if (!multi) break;  // malformed: toml++ says where
          ++line;
        }
        if (ch == '"' && text[j] == '\\') {
          ++j;
          continue;
        }
        if (text.compare(j, close.size(), close) == 0) break;
      }
      i = std::min(text.size(), j + close.size()) - 1;
      continue;
    }
    if (ch == '#') {  // a comment, to the end of the line
      while (i + 1 < text.size() && text[i + 1] != '\n') ++i;
      continue;
    }
    const bool key_char = std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-' ||
                          ch == '+' || ch == ' ' || ch == '\t' || ch == '.';
    if (ch == '.' && ++dots > kMaxTomlDepth)
      refuse("a key of more than " + std::to_string(kMaxTomlDepth) + " dotted parts");
    if (!key_char) dots = 0;
    if (ch == '[' || ch == '{') {
      if (++depth > kMaxTomlDepth)
        refuse("arrays or tables nested more than " + std::to_string(kMaxTomlDepth) + " deep");
    } else if (ch == ']' || ch == '}') {
      depth = std::max(0, depth - 1);
    }
    if (ch == '\n') ++line;
  }
}

toml::table parse_toml(const std::string& text, const std::string& origin) {
  check_toml_shape(text, origin);
  try {
    return toml::parse(text, origin);
  } catch (const toml::parse_error& e) {
    std::ostringstream where;
    where << origin << ":" << e.source().begin.line << ":" << e.source().begin.column
          << ": malformed TOML: " << e.description();
    throw InputError(where.str());
  }
}

void TableReader::number(const char* key, double& out) {
  const toml::node* node = find(key);
  if (!node) return;
  if (const auto* f = node->as_floating_point()) {
    out = f->get();
  } else if (const auto* i = node->as_integer()) {
    out = static_cast<double>(i->get());
  } else {
    fail(key, "must be a number, got " + type_name(*node));
  }
}

void TableReader::integer(const char* key, long long& out) {
  const toml::node* node = find(key);
  if (!node) return;
  const auto* i = node->as_integer();
  if (!i) fail(key, "must be an integer, got " + type_name(*node));
  out = i->get();
}

void TableReader::string(const char* key, std::string& out) {
  const toml::node* node = find(key);
  if (!node) return;
  if (const auto* s = node->as_string()) {
    out = s->get();
  } else {
    fail(key, "must be a string, got " + type_name(*node));
  }
}

const toml::array* TableReader::array(const char* key) {
  const toml::node* node = find(key);
  if (!node) return nullptr;
  if (!node->is_array()) fail(key, "must be an array, got " + type_name(*node));
  return node->as_array();
}

void TableReader::reject_unknown(const std::string& allowed) const {
  if (!table_) return;
  for (const auto& [key, node] : *table_) {
    if (!used_.count(std::string(key.str()))) {
      throw InputError(origin_ + ": unknown key '" + prefix_ + std::string(key.str()) +
                       "' (allowed here: " + allowed + ")");
    }
  }
}

void TableReader::reject_unknown() const {
  std::string allowed;
  for (const std::string& key : used_) allowed += (allowed.empty() ? "" : ", ") + key;
  reject_unknown(allowed);
}

void TableReader::fail(const std::string& key, const std::string& why) const {
  throw InputError(origin_ + ": " + prefix_ + key + " " + why);
}

const toml::node* TableReader::find(const char* key) {
  if (!table_) return nullptr;
  used_.insert(key);
  return table_->get(key);
}

}  // namespace contact2d
