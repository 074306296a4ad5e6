// The bounce MuJoCo produces: a set of contacts hitting at once, stepped as
// MuJoCo steps them at the model's timestep (discrete time), not the
// continuous-time Kelvin–Voigt restitution.
//
// The rows are the contacts' normal rows (a pyramidal cone's edges seen as
// one normal row with Â·φ, as inspect.hpp does). Each row i has MuJoCo's
// K_i, B_i (from its solref after refsafe), its solimp and the regulariser's
// weight W_i = Â·φ; the rows are coupled through the model's inverse
// inertia, A_ij = J_i·M⁻¹·J_jᵀ. With x the rows' distances (negative:
// penetrating) and v their normal speeds, a step of MuJoCo's constraint
// solver in its quadratic zone, without gravity (a restitution is a ratio
// of speeds, gravity only shifts it by g·contact time / v0):
//
//   d_i = impedance(solimp_i, x_i),  R_i = (1 − d_i)/d_i · W_i,
//   aref_i = −B_i·v_i − K_i·d_i·x_i,
//   f = (A_act + R_act)⁻¹ · aref_act over the rows in contact (x_i ≤ 0),
//   dropping rows whose force would be negative (a contact only pushes:
//   MuJoCo's constraint is unilateral) until none is,
//   a = A·f;
//
// then MuJoCo's Euler (and implicit: contacts explicit) step: v += Δt·a,
// x += Δt·v (semi-implicit), or RK4's four stages on (x, v), each stage
// with the contacts at its own positions (mj_RungeKutta runs collision
// again per stage). The contacts approach together at v0 from φ·v0·Δt
// above (φ in (0, 1): where in a step the first contact falls); the bounce
// is the mean of their normal speeds once every row has left (x > 0) over
// v0, averaged over 8 phases φ, and its spread over them. Speeds scale out
// of it except through the solimp width: v0 is a parameter.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <vector>

#include "core/integrators.hpp"

namespace contact2d::mujoco {

struct BounceRow {
  double K = 0.0, B = 0.0;  // MuJoCo's KBIP[0], KBIP[1]
  std::array<double, 5> solimp{};
  double weight = 0.0;  // Â·φ, 1/kg
};

// A bounce lasts a few ω⁻¹ (ms for MuJoCo's default contact); rows that
// push against each other (a body between two walls, all its contacts
// closing at once) never leave: the stepping gives up after this many steps.
inline constexpr long kMaxBounceSteps = 20000;

// `left` false: some row had not left after kMaxBounceSteps steps (rows
// pushing against each other, or a contact so soft that it lasts longer).
struct Bounce {
  double restitution = 0.0;   // mean outgoing / approach normal speed
  double spread = 0.0;        // largest minus smallest over the phases
  double contact_time = 0.0;  // s, mean over the phases
  bool left = true;           // every phase left within the step budget
};

// `coupling`: A (n×n). `rk4`: MuJoCo's RK4, else its Euler/implicit.
Bounce mujoco_bounce(const std::vector<BounceRow>& rows, const Eigen::MatrixXd& coupling, double dt,
                     bool rk4, double v0);

}  // namespace contact2d::mujoco
