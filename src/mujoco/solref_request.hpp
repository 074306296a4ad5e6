// `contact2d solref` from its options to its report, as a library call
// shared by the program and the Python module (src/python): the checks of
// which options go together, the body read from a user's model
// (read_model_body: mass, joints, Â, friction, the contacts at rest), the
// targets solved for k or c (solve_targets), then solref_report — the
// numbers mujoco/solref_tool.hpp derives.
//
// Every field mirrors one option of the command (docs/cli.md); an option
// not given is an empty optional, and the defaults are the command's.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "mujoco/solref_tool.hpp"

namespace contact2d::mujoco {

struct SolrefRequest {
  std::optional<double> k, c;  // --k, --c
  std::optional<double> dt;    // --dt; absent: --model's own timestep (required without --model)
  SolrefTargets targets;       // --restitution, --contact-time, --penetration
  std::optional<double> mass;  // --mass
  std::optional<double> mu;    // --mu; absent: the snippets keep the user's friction
  double inertia = 0.0, lever = 0.0, pivot = 0.0, mu_roll = 0.0;
  std::string model, body;           // --model FILE --body NAME
  std::optional<std::string> joint;  // --joint
  std::string mapping = "all";       // --mapping: calibrated | exact | seed | all
  std::optional<int> contacts;       // --contacts
  std::string engine = "mujoco";     // --engine: mujoco (2.2.2) | mujoco3 (3.14)
  double settle = kSettleSeconds;    // --settle: s of mj_step before reading --model's contacts
  std::string key;                   // --key: the keyframe the settling starts from
  std::string apply;                 // --apply OUT.xml: the model with the recommendation
  std::optional<double> slope;       // --slope DEG: each mapping's creep
};

// The mappings --mapping names, in the order the report gives them. Throws
// InputError for an unknown name and for compensated (not offered, with why).
std::vector<Mapping> chosen_mappings(const std::string& name);

// The report of the request `options`. Notes that are not failures (MuJoCo's
// warning while loading the model, a body on none of the four joint sets) go to
// `note` as one line each, without a prefix, as they arise. Throws
// InputError naming the option for a value out of range, a combination of
// options that does not go together, a model MuJoCo cannot load, or a
// mapping asked for by name that cannot express k and c.
// `read` reads --model in options.engine's MuJoCo (mujoco/model_state.hpp;
// empty: 2.2.2's read_model_state, which only --engine mujoco may use).
SolrefReport solref_request(const SolrefRequest& options,
                            const std::function<void(const std::string&)>& note = {},
                            const StateReader& read = {});

}  // namespace contact2d::mujoco
