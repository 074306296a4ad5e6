// contact2d --version: the project version (CMake's project(VERSION)) and
// the git revision it was built from, written at every build by
// cmake/version.cmake.
#pragma once

#include <string>

namespace contact2d::cli {

extern const char* const kVersion;      // "0.1.0"
extern const char* const kGitRevision;  // "c215530f4a1b", "+dirty" appended; "" when unknown

// "contact2d 0.1.0 (git c215530f4a1b)", or "contact2d 0.1.0" without git.
inline std::string version_text() {
  std::string text = std::string("contact2d ") + kVersion;
  if (kGitRevision[0] != '\0') text += std::string(" (git ") + kGitRevision + ")";
  return text;
}

}  // namespace contact2d::cli
