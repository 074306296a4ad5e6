// The error every layer throws for bad input (a scene file, a command-line
// value, a model MuJoCo refuses): its message is one line naming the
// source, the key and the allowed range. The CLI prints it and exits with
// status 2.
#pragma once

#include <stdexcept>

namespace contact2d {

struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// An engine failed during a run for a reason outside the physics (the
// process that runs it died, or answered outside its protocol): one line
// naming the engine and what fixes it. The CLI prints it and exits with
// status 3, as for a run that failed.
struct EngineError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace contact2d
