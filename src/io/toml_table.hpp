// Typed reads from one TOML table with one-line messages that name the
// source, the key and what was wrong; shared by the scene reader and the
// game's [game] table. Internal to the project (needs toml++).
#pragma once

#include <toml++/toml.h>
#include <set>
#include <string>

namespace contact2d {

// Reads keys out of one TOML table, remembering which were read so that the
// rest can be reported as unknown. A missing key leaves `out` unchanged (the
// caller's default); a key of the wrong type throws InputError. `prefix` is
// prepended to keys in messages ("body.", "game."), `origin` names the file.
class TableReader {
 public:
  TableReader(const toml::table* table, std::string prefix, std::string origin)
      : table_(table), prefix_(std::move(prefix)), origin_(std::move(origin)) {}

  // A number (integer or floating point). Non-finite values pass through:
  // the caller's range check names them.
  void number(const char* key, double& out);
  void integer(const char* key, long long& out);
  void string(const char* key, std::string& out);
  const toml::array* array(const char* key);  // nullptr when missing

  void mark_used(const char* key) { used_.insert(key); }

  // Every key not read so far is unknown; `allowed` lists the valid ones.
  void reject_unknown(const std::string& allowed) const;
  // Same, listing the keys read so far as the allowed ones.
  void reject_unknown() const;

  [[noreturn]] void fail(const std::string& key, const std::string& why) const;

 private:
  const toml::node* find(const char* key);

  const toml::table* table_;
  std::string prefix_;
  std::string origin_;
  std::set<std::string> used_;
};

// The TOML document `text` read from `origin`; InputError
// "ORIGIN:LINE:COLUMN: malformed TOML: …" when it is not TOML, and
// check_toml_shape's before it is parsed.
toml::table parse_toml(const std::string& text, const std::string& origin);

// toml++ parses a dotted key and nested arrays by recursion, one frame per
// part: a 100 kB file with a key of 40,000 parts (a.a.a…) overflowed the
// stack (exit 139). InputError "ORIGIN:LINE: …" for a key of more than
// kMaxTomlDepth dotted parts, or arrays and tables nested deeper, before
// toml++ sees the text.
inline constexpr int kMaxTomlDepth = 64;
void check_toml_shape(const std::string& text, const std::string& origin);

// The [body] keys of a scene file for scene.shape (io/scene_file.cpp): a
// recording's manifest (io/recording.hpp) describes its body the same way.
struct Scene;
void read_body(const toml::table* table, Scene& scene, const std::string& origin);

}  // namespace contact2d
