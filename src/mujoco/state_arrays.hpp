// MuJoCo's own arrays at one state, as either version hands them over, and
// the one function that reads a ModelState's bodies, geoms and contacts
// from them (model_state.hpp): 2.2.2 fills StateArrays from mjModel/mjData
// in this process (model_state.cpp), 3.14 from the Node driver's "read"
// answer (mujoco3/node_mujoco.cpp, src/mujoco3/driver.mjs). Which contacts
// are listed, their margin and gap, depths, inverse masses and rows in the
// quadratic zone are decided here once, for both.
//
// The only work a version does for the reader beyond copying arrays is
// MuJoCo's own: mj_jac of both bodies at each contact point, mj_contactForce,
// and mj_solveM on the rows the reader builds (SolveM).
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "mujoco/model_state.hpp"

namespace contact2d::mujoco {

// How a version gives a geom pair without a <pair> its margin and gap:
// 2.2.2's mj_collideGeoms takes the larger geom's, 3.x adds the two.
enum class MarginRule { Larger, Summed };

// One d->contact[i], as MuJoCo has it, with what MuJoCo computes for it.
struct ArrayContact {
  int geom1 = -1, geom2 = -1;
  int dim = 1;
  int exclude = 0;       // 1: within its gap, 2: … (not in the constraint problem)
  int efc_address = -1;  // its first constraint row, or −1
  double dist = 0.0, includemargin = 0.0;
  std::array<double, 3> pos{};
  std::array<double, 9> frame{};  // normal, then the two tangents
  std::array<double, 5> friction{};
  std::array<double, 2> solref{};
  // MuJoCo ≥ 2.3.6's own reference for an elliptic contact's friction rows
  // (a <pair>'s solreffriction; 0 0: they use solref); 2.2.2 has none.
  std::array<double, 2> solreffriction{};
  std::array<double, 5> solimp{};
  double normal_force = 0.0;  // mj_contactForce's first component, N
  // mj_jac's translational Jacobian of geom1's and geom2's bodies at pos:
  // three rows (x, y, z) over the dofs each.
  std::array<SparseRow, 3> jac1, jac2;
};

struct StateArrays {
  MarginRule margin_rule = MarginRule::Larger;
  int nv = 0;
  // model (names as stored: "" when unnamed)
  std::vector<std::string> body_names, geom_names;
  std::vector<int> body_weldid, body_parentid, jnt_bodyid, jnt_type;
  std::vector<double> body_mass, body_inertia, body_invweight0;  // 1, 3, 2 per body
  std::vector<int> geom_bodyid, geom_condim, geom_contype, geom_conaffinity;
  std::vector<double> geom_friction, geom_margin, geom_gap;  // 3, 1, 1 per geom
  std::vector<int> geom_priority;
  std::vector<double> geom_solmix, geom_solref;  // 1, 2 per geom
  std::vector<int> pair_geom1, pair_geom2;
  std::vector<double> pair_margin, pair_gap;
  bool elliptic = false;  // opt.cone
  // data at the state
  std::vector<double> qvel, qacc, efc_force;
  std::vector<ArrayContact> contacts;
};

// M⁻¹ times each row at the state (that version's mj_solveM).
using SolveM = std::function<std::vector<SparseRow>(const std::vector<SparseRow>&)>;

// Every index the reader follows is in range and every array has its
// model's size: "" when so, else what does not fit (the Node driver is
// this program's own, but its answer is still checked).
std::string arrays_misfit(const StateArrays& a);

// Fills the state's bodies, geoms, nv, qvel, qacc, speed, accel and
// contacts from the arrays; the option, version, messages, settled time and
// bias (qfrc_bias at qvel = 0, which needs another mj_forward) stay the
// caller's. Only the contacts in the constraint problem are
// listed (exclude 0 and constraint rows): one within its gap has none.
void read_state_arrays(const StateArrays& a, const SolveM& solve, ModelState& s);

}  // namespace contact2d::mujoco
