// libFuzzer target: scene-file parsing and validation. Any input must either
// give a Scene that passes validate() or throw InputError; anything else (a
// crash, a sanitizer report, another exception) is a bug. A valid scene is
// also run for a few steps: the library must not produce NaN without the
// divergence rule noticing.
#include <cmath>
#include <cstdint>
#include <string>

#include "core/run.hpp"
#include "io/scene_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  contact2d::Scene scene;
  try {
    scene = contact2d::parse_scene(text, "fuzz.toml");
  } catch (const contact2d::InputError&) {
    return 0;
  }
  if (contact2d::validate(scene)) __builtin_trap();  // parse_scene must have rejected it
  // Keep each input cheap: at most 200 steps.
  scene.sim.duration = std::min(scene.sim.duration, 200.0 * scene.sim.dt);
  const contact2d::Trajectory t = contact2d::simulate(scene);
  for (const contact2d::Sample& s : t.samples) {
    if (!s.state.q.allFinite() || !s.state.v.allFinite()) __builtin_trap();
  }
  return 0;
}
