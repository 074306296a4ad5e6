#include "io/toml_table.hpp"

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

toml::table parse_toml(const std::string& text, const std::string& origin) {
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
