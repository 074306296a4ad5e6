#include "cli/engines.hpp"

#include "io/scene_file.hpp"
#ifdef CONTACT2D_WITH_MUJOCO
#include "cli/mujoco_engine.hpp"
#endif

namespace contact2d::cli {

EngineRun run_engine(const std::string& engine, const Scene& scene) {
  if (engine == "ref") return run_reference(scene);
#ifdef CONTACT2D_WITH_MUJOCO
  if (engine == "mujoco") {
    return run_mujoco_engine(scene, {});  // default mapping and geometry
  }
  throw InputError("--engine " + engine + ": unknown engine (use ref or mujoco)");
#else
  throw InputError("--engine " + engine +
                   ": not available (contact2d was built without MuJoCo; use --engine ref)");
#endif
}

}  // namespace contact2d::cli
