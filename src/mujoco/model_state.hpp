// A user's MuJoCo model at one state, as plain numbers: what `inspect` and
// `solref --model` read from MuJoCo, filled by either version — 2.2.2
// natively here (read_model_state), 3.14 through Node
// (mujoco3/node_mujoco.hpp) — and read from MuJoCo's arrays by one reader
// for both (state_arrays.hpp), so the contact math that follows
// (inspect.hpp, solref_tool.hpp) is one implementation fed by both.
//
// The state: the model's keyframe (or qpos0), then, with a settle time,
// mj_step for that long (at most 1e6 steps) so MuJoCo itself brings the
// model to rest; then mj_forward. The settled criterion is stated, not assumed: `speed` and `accel`
// are the largest |qvel| and |qacc| at the end, and the state counts as at rest when they are at
// most kRestSpeed and kRestAccel.
//
// Per contact (d->contact[i] that is in the constraint problem):
//   dist      con.dist − con.includemargin (negative: penetrating), m;
//   A         n·J·M⁻¹·Jᵀ·n at the contact point (mj_jac of both bodies,
//             mj_solveM on the factor mj_forward left), 1/kg;
//   force     MuJoCo's own normal force (mj_contactForce, the contact
//             frame's first component), N;
//   jacobian  the normal row n·(J₂ − J₁) (nv, sparse), for the least-squares
//             loads, and M⁻¹ times it (the coupling of two contacts);
//   rows      how many of its constraint rows are in the solver's quadratic
//             zone (from their forces: a pushing pyramidal row, an elliptic
//             force strictly inside its cone): a contact rests at the depth
//             its load gives only when all are (an unloaded pyramid edge or
//             an elliptic contact on its cone's surface slips).
// Per body: body_invweight0 (Â, what the regulariser uses), the weld id
// (0: welded to the world) and the mass.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "mujoco/model.hpp"

namespace contact2d::mujoco {

// At rest: the forces balance (every |qacc| at most 1 % of Earth's
// gravity; a state at qvel = 0 that is not in equilibrium, as qpos0 usually
// is, accelerates at about g) and nothing moves faster than 1 cm/s (or
// 0.01 rad/s). A creeping body is not at rest: a contact that slips has an
// edge of the pyramidal cone unloaded, and its normal force no longer sets
// its depth as at rest (measured on Debian's humanoid sample: the rest
// depths of its slipping foot contacts are 9–55 % off MuJoCo's at 3 s of
// settling, |qvel| 0.10; every contact within 0.05 % at 60 s, |qvel| 0.004).
// It labels the state; it does not stop the settling early: stopped at the
// first step that meets it, a box on MuJoCo's default contact was still
// closing, 7 % short of its rest depth.
inline constexpr double kRestSpeed = 0.01;  // m/s, rad/s
inline constexpr double kRestAccel = 0.1;   // m/s², rad/s²
// The most steps a settle takes (a model with a tiny timestep settles less).
inline constexpr long kMaxSettleSteps = 1000000;

struct StateRequest {
  std::string path;    // the MJCF file
  std::string key;     // keyframe name; empty: qpos0
  double settle = 0;   // s of mj_step before the state is read; 0: none
  std::string option;  // the option naming the file in messages ("--model" or "")
};

// A row over the model's dofs that is mostly zeros (a contact touches the
// dofs of two kinematic chains): its non-zero columns, ascending.
struct SparseRow {
  std::vector<int> index;
  std::vector<double> value;
  static SparseRow of(const std::vector<double>& dense) {
    SparseRow row;
    for (size_t i = 0; i < dense.size(); ++i) {
      if (dense[i] == 0.0) continue;
      row.index.push_back(static_cast<int>(i));
      row.value.push_back(dense[i]);
    }
    return row;
  }
  double dot(const std::vector<double>& dense) const {
    double sum = 0.0;
    for (size_t k = 0; k < index.size(); ++k)
      sum += value[k] * dense[static_cast<size_t>(index[k])];
    return sum;
  }
  double dot(const SparseRow& other) const {
    double sum = 0.0;
    for (size_t a = 0, b = 0; a < index.size() && b < other.index.size();) {
      if (index[a] < other.index[b]) {
        ++a;
      } else if (other.index[b] < index[a]) {
        ++b;
      } else {
        sum += value[a++] * other.value[b++];
      }
    }
    return sum;
  }
};

struct StateContact {
  int geom1 = -1, geom2 = -1, body1 = -1, body2 = -1;
  bool explicit_pair = false;  // the geoms are an explicit <pair>
  double dist = 0.0;
  std::array<double, 3> pos{}, normal{};
  int condim = 1;
  std::array<double, 5> friction{};
  std::array<double, 2> solref{};
  std::array<double, 2> solreffriction{};  // 0 0: none (always so in 2.2.2)
  std::array<double, 5> solimp{};
  // The margin and gap MuJoCo gave the geom pair (an explicit pair: its own;
  // else 2.2.2 takes the larger geom's, 3.x adds the two geoms'), m. 2.2.2
  // detects a contact within the margin and keeps margin − gap as
  // con.includemargin; 3.x detects within margin + gap and keeps the margin.
  double margin = 0.0, gap = 0.0;
  double A = 0.0;
  double A_t = 0.0;  // the larger of the two tangent directions' (condim ≥ 3; else 0), 1/kg
  // condim ≥ 3: the two tangent rows of the contact frame and M⁻¹ times
  // them (the coupling of friction rows across contacts).
  std::array<SparseRow, 2> tangent, tangent_solved;
  double force = 0.0;
  int rows = 0;        // its constraint rows (pyramidal: 2(condim − 1), or 1; elliptic: condim)
  int quadratic = 0;   // of them, in the solver's quadratic zone (efc_state)
  SparseRow jacobian;  // the normal row n·(J₁ − J₂)
  SparseRow solved;    // M⁻¹·jacobianᵀ: A = jacobian·solved, A_ij = jacobian_i·solved_j
};

struct ModelState {
  std::string version;                // MuJoCo's, "2.2.2" or "3.14.0"
  std::string load_warning;           // MuJoCo's warning while loading, one line
  std::vector<std::string> messages;  // MuJoCo's warnings while stepping
  // <option>
  double timestep = 0.0;
  std::string integrator;  // Euler, RK4, implicit, implicitfast
  bool elliptic = false;
  double impratio = 1.0;
  // MuJoCo's noslip post-pass over the friction rows (0: none); inspect does
  // not model it.
  int noslip_iterations = 0;
  std::array<double, 3> gravity{};
  bool refsafe = true;
  std::string disabled;  // "contacts" or "constraints" when <flag> turns them off, else empty
  // bodies (index = MuJoCo's body id)
  std::vector<std::string> body_names, geom_names;  // "#id" when unnamed
  std::vector<int> body_weld;                       // body_weldid
  std::vector<double> body_mass;
  std::vector<double> body_inertia;      // 3 per body: body_inertia (principal, about the COM)
  std::vector<double> body_invweight0;   // 2 per body: translational, rotational
  std::vector<int> body_parent;          // body_parentid
  std::vector<std::string> body_joints;  // the body's own joints' types, "slide, slide, hinge"
  std::vector<int> geom_body;
  std::vector<double> geom_mu;  // sliding friction (geom_friction[0])
  std::vector<int> geom_condim;
  // How MuJoCo mixes a geom pair without a <pair> (inspect.hpp): the geom of
  // higher priority wins; at equal priority solref and solimp mix by solmix,
  // a direct-form solref takes the element-wise min.
  std::vector<int> geom_priority;
  std::vector<double> geom_solmix;
  std::vector<double> geom_solref;  // 2 per geom
  std::vector<bool> geom_collides;  // contype or conaffinity non-zero
  // the state
  int nv = 0;
  double settled = 0.0;            // s stepped
  double speed = 0.0;              // largest |qvel| at the end
  double accel = 0.0;              // largest |qacc| at the end
  std::vector<double> qvel, qacc;  // at this state
  std::vector<double> bias;        // qfrc_bias at this configuration with qvel = 0
  std::vector<StateContact> contacts;
};

inline bool at_rest(const ModelState& s) { return s.speed <= kRestSpeed && s.accel <= kRestAccel; }

// MuJoCo 2.2.2's. Throws InputError: the file cannot be read or MuJoCo
// cannot load it (its message, one line), an unknown keyframe, a settle
// time that is negative or not finite.
ModelState read_model_state(const StateRequest& request);

// The same, keeping MuJoCo's model and data at that state (inspect --pairs
// probes the model further).
struct LoadedState {
  ModelPtr model;
  DataPtr data;
  ModelState state;
};
LoadedState load_model_state(const StateRequest& request);

// A version's reader: read_model_state here, mujoco3::read_model_state.
using StateReader = std::function<ModelState(const StateRequest&)>;

// The largest eigenvalue of the friction rows' J·M⁻¹·Jᵀ over these
// contacts (indices into state.contacts; two tangent rows each, condim ≥ 3):
// the tangential inverse mass of the stiffest way they slip together. A
// box's four corners yawing together see more than any corner alone.
double coupled_tangential_inverse_mass(const ModelState& state, const std::vector<int>& contacts);

// The request's checks shared by both versions (InputError naming the option).
void check_state_request(const StateRequest& request);

// "--settle S s is more than the N steps a settle takes: settled T s" when
// the settle asks for more than kMaxSettleSteps at this timestep, else "":
// both versions add it to the state's messages.
std::string settle_cap_note(double settle, double timestep);

}  // namespace contact2d::mujoco
