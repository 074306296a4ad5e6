// `contact2d solref --model F --body B --apply OUT.xml`: the user's model
// with the recommended mapping written into it, then read back.
//
// The mapping goes into <pair>s, one per geom pair the body rests on
// (solref_tool.hpp's RestPair: the mapping's solref and solimp, every other
// field as MuJoCo resolved it for those geoms, --mu's condim and friction),
// and into <option> (cone, impratio), by editing the MJCF with tinyxml2:
// comments, classes and every other element stay as they were. Not on the
// body's geoms with priority: that copies the geom's condim and friction
// over the mixing MuJoCo does, and reaches every other contact of the geom.
// An unnamed geom a pair needs is named contact2d_geomID; a pair the model
// has is edited in place. OUT.xml may sit in any folder: elsewhere than the
// model's, its relative file references are made absolute (an <include>d
// file's cannot be, and is refused). It must not be the model itself.
//
// Then MuJoCo (the version the report is for) settles OUT.xml as it settled
// the model, and each of the body's contacts is listed with MuJoCo's load
// and depth beside the depth the mapping gives that load
// (static_penetration with the mapping's K, solimp and Â·φ: the body's
// Â, plus the other body's when it moves).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "mujoco/model_state.hpp"
#include "mujoco/solref_tool.hpp"

namespace contact2d::mujoco {

// The class each geom has in the model's own file (`model`): its class
// attribute, else the childclass of the nearest element above it that sets
// one (MuJoCo's rule): {name, ""} or {name, "the childclass of body 'B'"};
// {"", ""} when it has none, or is not written in that file (an <include>)
// or the file is not MJCF. What class="contact2d" would replace.
std::vector<std::pair<std::string, std::string>> geom_classes_in_file(
    const std::string& model, const std::vector<GeomRef>& geoms);

// Throws InputError naming --apply (OUT is the model itself, the body rests
// on nothing, an unnamed geom or a pair not in the model's own file, an
// <include> with relative references when OUT is elsewhere) or --model
// (MuJoCo refuses OUT.xml); no file is left when it throws.
Applied apply_solref(const SolrefReport& report, const MappingOutcome& outcome,
                     const std::string& model, const std::string& body, const std::string& out,
                     const StateRequest& settle, const StateReader& read);

}  // namespace contact2d::mujoco
