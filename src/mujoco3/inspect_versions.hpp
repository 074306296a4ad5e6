// `inspect` beyond one read of the model: how long MuJoCo takes to bring a
// model to rest (settle_time), and the model on both versions side by side
// (inspect_versions, mujoco/version_compare.hpp). Both re-read the model
// through the readers of mujoco3/own_model.hpp, so they live above both.
#pragma once

#include <string>

#include "mujoco/inspect.hpp"
#include "mujoco/version_compare.hpp"

namespace contact2d::mujoco3 {

// The settle time after which `engine` has the model at rest, when `report`
// is not: the model re-read after settling twice as long, then twice that,
// up to `longest` s of settling, and no read started once the reads so far
// took `budget` s (a read costs about twice the one before). Sets
// report.rest_after (+∞: not at rest within report.rest_search s).
void settle_time(mujoco::InspectReport& report, const mujoco::InspectOptions& options,
                 const std::string& engine, double longest = 120.0, double budget = 20.0);

// The model on MuJoCo 2.2.2 and 3.14 at the same settle time, compared
// (--pairs is refused: it needs 2.2.2 alone). Throws InputError as inspect does.
mujoco::VersionComparison inspect_versions(const mujoco::InspectOptions& options);

}  // namespace contact2d::mujoco3
