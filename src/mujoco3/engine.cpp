// MuJoCo 3's descriptor for the engine registry (mujoco3/engine.hpp).
#include "mujoco3/engine.hpp"

#include "core/input_error.hpp"
#include "mujoco/engine.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco3/node_mujoco.hpp"
#include "mujoco3/stepper.hpp"

namespace contact2d::mujoco3 {
namespace {

std::unique_ptr<Stepper> make_mujoco3(const engines::EngineSpec& spec, const Scene& scene) {
  mujoco::MjcfOptions options =
      mujoco::mjcf_options(spec.option("mapping"), spec.option("geometry"), spec.source);
  options.model_dt = spec.model_dt;
  options.friction_damper = spec.option("friction") == "damper";
  return std::make_unique<Mujoco3Stepper>(scene, options);
}

// MuJoCo 2.2.2's check (its integrators: 3.14 has the same three and
// implicitfast, which contact2d does not use), then whether MuJoCo 3 can
// run here at all: both before any work.
void check(const Scene& scene) {
  mujoco::engine_info().check(scene);
  const std::string why = missing();
  if (!why.empty()) throw InputError(why);
}

}  // namespace

const engines::EngineInfo& engine_info() {
  // MuJoCo 2.2.2's descriptor with its own kind, title and stepper: the same
  // options, integrators and contact law.
  static const engines::EngineInfo info = [] {
    engines::EngineInfo i = mujoco::engine_info();
    i.kind = "mujoco3";
    i.title = "MuJoCo 3";
    i.make = make_mujoco3;
    i.check = check;
    i.compared_by_default = false;
    i.options.push_back(
        {"friction",
         "MuJoCo 3's friction rows (shared: the contact's damper, as 2.2.2, which pushes a sliding "
         "body up by mu c |v_t|; damper: a damper of their own, matched to the tanh law's stop, "
         "compensated mapping only)",
         {"shared", "damper"},
         "shared"});
    return i;
  }();
  return info;
}

}  // namespace contact2d::mujoco3
