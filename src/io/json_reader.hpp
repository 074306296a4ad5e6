// Reading JSON: a small hand parser (the project has no JSON library; its
// one writer is io/json.hpp). A value is parsed in full and checked;
// anything that is not JSON throws std::runtime_error naming `what` and the
// offset. Objects keep their members in order, arrays their items, scalars
// their text (strings unescaped; a \u escape, which no reader here needs,
// becomes '?').
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace contact2d::json {

struct Value {
  enum class Kind { Null, Bool, Number, String, Array, Object } kind = Kind::Null;
  std::string text;
  double number = 0.0;
  std::vector<Value> items;
  std::vector<std::pair<std::string, Value>> members;

  const Value* get(const std::string& key) const {
    for (const auto& [name, value] : members) {
      if (name == key) return &value;
    }
    return nullptr;
  }
};

// The JSON document `text`; `what` names it in errors ("benchmark JSON").
Value parse(const std::string& text, const std::string& what);

}  // namespace contact2d::json
