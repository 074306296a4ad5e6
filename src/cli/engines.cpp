#include "cli/engines.hpp"

#include "io/scene_file.hpp"

namespace contact2d::cli {

EngineRun run_engine(const std::string& engine, const Scene& scene) {
  if (engine == "ref") return run_reference(scene);
  throw InputError("--engine " + engine + ": not yet available (use --engine ref)");
}

}  // namespace contact2d::cli
