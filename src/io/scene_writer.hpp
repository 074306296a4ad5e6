// A scene as a scene file (TOML) that reads back as the same scene: every
// number in its shortest round-trip form, only the keys of its shape. Used
// by the report to save the random scenes it draws, so that each row of its
// tables can be re-run with `contact2d compare FILE`.
#pragma once

#include <string>

#include "core/scene.hpp"

namespace contact2d {

// `comment` (may be empty) is written as the first lines, each behind "# ".
// Box obstacles are written as centre and size, which reproduces their
// corners to rounding (the other values read back bit for bit).
std::string scene_to_toml(const Scene& scene, const std::string& comment = "");

}  // namespace contact2d
