// Scene files (TOML, docs/scenes.md) and command-line overrides.
#pragma once

#include <string>
#include <vector>

#include "core/input_error.hpp"
#include "core/scene.hpp"

namespace contact2d {

// "key=value" assignments applied on top of the file, e.g. "contact.k=1e6" or
// "sim.integrator=rk4". The value is read as a TOML value (a bare word is a
// string), so overrides pass the same type and range checks as the file.
// `option` names the command-line option it came from ("--dt"; empty:
// "--set key=value"), so an error in the value names the option, not the file.
struct Override {
  std::string key;
  std::string value;
  // {}: aggregates that leave it out stay clear of GCC's
  // -Wmissing-field-initializers.
  std::string option = {};  // NOLINT(readability-redundant-member-init)
};
Override parse_override(const std::string& assignment);  // throws InputError

// Reads, applies the overrides, checks keys, types and ranges. Throws InputError.
Scene load_scene(const std::string& path, const std::vector<Override>& overrides = {});

// Same, from TOML text; `origin` names the source in messages.
Scene parse_scene(const std::string& toml_text, const std::string& origin,
                  const std::vector<Override>& overrides = {});

}  // namespace contact2d
