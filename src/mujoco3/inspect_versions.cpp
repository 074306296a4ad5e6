// inspect's settle time and its two-version comparison (mujoco3/inspect_versions.hpp).
#include "mujoco3/inspect_versions.hpp"

#include <chrono>
#include <cmath>
#include <limits>

#include "core/input_error.hpp"
#include "mujoco/model_state.hpp"
#include "mujoco3/node_mujoco.hpp"
#include "mujoco3/own_model.hpp"

namespace contact2d::mujoco3 {

void settle_time(mujoco::InspectReport& report, const mujoco::InspectOptions& options,
                 const std::string& engine, double longest, double budget) {
  if (report.at_rest || report.contacts.empty()) return;
  const mujoco::StateReader read = state_reader(engine);
  mujoco::StateRequest request;
  request.path = options.path;
  request.key = options.key;
  const auto start = std::chrono::steady_clock::now();
  double last = 0.0;  // s the last read took
  double settle = std::max(1.0, 2.0 * report.settled);
  report.rest_search = report.settled;
  while (settle <= longest) {
    const double spent =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (spent + 2.0 * last > budget) break;
    request.settle = settle;
    const auto begin = std::chrono::steady_clock::now();
    const mujoco::ModelState state = read(request);
    last = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    report.rest_search = state.settled;
    if (mujoco::at_rest(state)) {
      report.rest_after = state.settled;
      return;
    }
    settle *= 2.0;
  }
  report.rest_after = std::numeric_limits<double>::infinity();
}

mujoco::VersionComparison inspect_versions(const mujoco::InspectOptions& options) {
  if (options.pairs)
    throw InputError("--pairs: lists pairs with MuJoCo 2.2.2 alone; run it without --engines");
  mujoco::StateRequest request;
  request.path = options.path;
  request.key = options.key;
  request.settle = options.settle;
  mujoco::LoadedState v2 = mujoco::load_model_state(request);
  const std::vector<mujoco::MeshGeom> meshes = mujoco::mesh_geoms(v2.model.get());
  const mujoco::ModelState v3 = mujoco3::read_model_state(request);
  mujoco::InspectReport r2 = mujoco::inspect_state(v2.state, options);
  mujoco::InspectReport r3 = mujoco::inspect_state(v3, options);
  return mujoco::compare_versions(v2.state, std::move(r2), v3, std::move(r3), meshes);
}

}  // namespace contact2d::mujoco3
