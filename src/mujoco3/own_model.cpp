// A user's own model on either MuJoCo version (mujoco3/own_model.hpp).
#include "mujoco3/own_model.hpp"

#include "core/input_error.hpp"
#include "mujoco3/node_mujoco.hpp"

namespace contact2d::mujoco3 {

mujoco::StateReader state_reader(const std::string& engine) {
  if (engine == "mujoco") return mujoco::read_model_state;
  if (engine == "mujoco3") return read_model_state;
  throw InputError("--engine " + engine + ": reads a model in mujoco (2.2.2) or mujoco3 (3.14)");
}

mujoco::InspectReport inspect(const mujoco::InspectOptions& options, const std::string& engine) {
  const mujoco::StateReader read = state_reader(engine);
  if (engine == "mujoco") return mujoco::inspect(options);
  mujoco::StateRequest request;
  request.path = options.path;
  request.key = options.key;
  request.settle = options.settle;
  return mujoco::inspect_state(read(request), options);
}

mujoco::SolrefReport solref(const mujoco::SolrefRequest& request,
                            const std::function<void(const std::string&)>& note) {
  return mujoco::solref_request(request, note, state_reader(request.engine));
}

}  // namespace contact2d::mujoco3
