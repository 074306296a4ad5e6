// A user's own model read by the MuJoCo version asked for: the one place
// that maps an engine name to the reader of mujoco/model_state.hpp, for
// `inspect` and `solref` in the program and the Python module.
#pragma once

#include <string>

#include "mujoco/inspect.hpp"
#include "mujoco/model_state.hpp"
#include "mujoco/solref_request.hpp"

namespace contact2d::mujoco3 {

// "mujoco": MuJoCo 2.2.2 in this process; "mujoco3": 3.14 in Node. Throws
// InputError "--engine NAME: ..." for any other name.
mujoco::StateReader state_reader(const std::string& engine);

// inspect on `engine` (--pairs needs 2.2.2's collision functions).
mujoco::InspectReport inspect(const mujoco::InspectOptions& options, const std::string& engine);

// solref_request with the reader request.engine names.
mujoco::SolrefReport solref(const mujoco::SolrefRequest& request,
                            const std::function<void(const std::string&)>& note);

}  // namespace contact2d::mujoco3
