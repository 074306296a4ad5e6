// `contact2d solref --model F --body B --apply OUT.xml`: the user's model
// with the recommended mapping written into it, then read back.
//
// The snippet goes onto the body's own <geom> elements (each gets the
// mapping's solref, solimp, priority 1 so its values win over what it
// touches, and, with --mu, condim and friction) and into <option> (cone,
// impratio), by editing the MJCF with tinyxml2: comments, classes and every
// other element stay as they were. OUT.xml must sit in the model's folder,
// where the model's includes, meshes and textures resolve, and must not be
// the model itself.
//
// Then MuJoCo (the version the report is for) settles OUT.xml as it settled
// the model, and each of the body's contacts is listed with MuJoCo's load
// and depth beside the depth the mapping gives that load
// (static_penetration with the mapping's K, solimp and Â·φ: the body's
// Â, plus the other body's when it moves).
#pragma once

#include <string>
#include <vector>

#include "mujoco/model_state.hpp"
#include "mujoco/solref_tool.hpp"

namespace contact2d::mujoco {

// Throws InputError naming --apply (OUT elsewhere than the model's folder,
// the model itself, the body not in the model's own file) or --model (MuJoCo
// refuses OUT.xml); no file is left when it throws before writing.
Applied apply_solref(const SolrefReport& report, const MappingOutcome& outcome,
                     const std::string& model, const std::string& body, const std::string& out,
                     const StateRequest& settle, const StateReader& read);

}  // namespace contact2d::mujoco
