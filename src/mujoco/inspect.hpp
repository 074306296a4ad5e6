// `contact2d inspect`: what the contacts of a user's own MJCF model are in
// physical units, as MuJoCo 2.2.2 (or 3.14) resolves and integrates them.
//
// The model is read at one state (mujoco/model_state.hpp: its keyframe or
// qpos0, settled by mj_step for `settle` seconds, then mj_forward) by either
// version; everything below is computed from those plain numbers.
// For every contact d->contact[i] (and, with `pairs`, every geom pair that
// can collide: explicit <pair>s, and default collisions filtered as
// mj_collision filters them: contype/conaffinity, the same weld body, the
// parent filter, <exclude>) the report gives:
//
//   solref, solimp, condim, friction as MuJoCo resolved them: d->contact[i]
//   for a contact; for a pair the explicit <pair>'s values, or the geoms'
//   mixed as mj_collideGeoms mixes them (the geom of higher priority wins;
//   at equal priority friction is the max, solimp and a standard-form
//   solref are mixed by solmix, a direct-form solref takes the min);
//   refsafe (standard form: timeconst raised to 2Δt) as getsolparam applies it;
//   K = 1/(d_max²·tc²·dr²), B = 2/(d_max·tc) (standard) or
//   K = −solref[0]/d_max², B = −solref[1]/d_max (direct), mj_makeImpedance;
//   A: the contact's true inverse mass, n·J·M⁻¹·Jᵀ·n (mj_jac, mj_solveM);
//   for a pair not in contact, at its closest points (MuJoCo's own collision
//   function run on a copy of the model with the pair's margin raised to
//   reach it);
//   Â: what MuJoCo's regulariser uses (efc_diagApprox: body_invweight0 of
//   both bodies; with a pyramidal cone and friction the normal sees
//   Â·μ²(1 + μ²)/((condim − 1)·impratio), mujoco/solref_tool.hpp);
//   the linear regime at impedance d (f = d·(−B·v − K·d·p)/(d·A + (1 − d)·Â)):
//     k = d²·K/(d·A + (1 − d)·Â) N/m,  c = d·B/(d·A + (1 − d)·Â) N·s/m,
//     ω = √(A·k),  ζ = A·c/(2ω);
//   ω·Δt at d_max (the stiffest the contact gets) against the limit of the
//   model's integrator (Euler and implicit: semi-implicit Euler's, RK4: RK4's;
//   core stability_limit);
//   the load f: MuJoCo's own normal force (mj_contactForce) at that state,
//   or with estimate_loads the least-squares (minimum-norm) solution of
//   Jₙᵀ·f = qfrc_bias over every contact, and the rest depth p solving
//   p·K·d(p)² = f·Â·(1 − d(p)) (mujoco/solref_tool.hpp), with a note where
//   MuJoCo is not at it (a row out of the quadratic zone, or (B·v + J·qacc)/R
//   over 1 % of the force);
//   each body's bounce: its contacts hitting together, stepped as MuJoCo
//   steps them (mujoco/bounce.hpp), and each contact's alone;
//   the restitution of the Kelvin–Voigt oscillator at (ω, ζ) with its force
//   clamped at zero (the contact lets go when k·x + c·ẋ = 0, before x = 0;
//   benchmarks/impact.hpp);
//   the creep speed on a slope of θ: inside the friction cone MuJoCo's
//   tangential rows have no spring, aref = −B·v (B of solreffriction where an
//   elliptic contact's <pair> sets it, MuJoCo ≥ 2.3.6), and R_t = R/impratio, so at
//   steady creep (qacc = 0) a contact carries impratio·B·d·v/((1 − d)·Â)
//   (elliptic; the pyramidal cone's edge rows give the same divided by 1 + μ²);
//   with the tangential load f·sinθ: v = f·sinθ·(1 − d)·Â·(1 + μ²)/(impratio·B·d)
//   (no (1 + μ²) for the elliptic cone), d at the depth under f·cosθ. The
//   solver stays in its quadratic zone (where this holds) while tanθ < μ
//   for the elliptic cone, and while no edge row unloads for the pyramidal
//   one, each carrying f/(2(condim − 1)) ± f·sinθ/(2μ): tanθ < μ/(condim − 1).
//   With noslip_iterations > 0 MuJoCo re-solves the friction forces after its
//   main solver without their regulariser (mj_solNoSlip): the creep is not
//   estimated then, and the advice that follows from the main solver's
//   friction rows (the impratio cap, impratio < 1) says it does not include it.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "mujoco/model_state.hpp"

namespace contact2d::mujoco {

struct InspectOptions {
  std::string path;
  std::string key;              // keyframe name; empty: qpos0
  double settle = 0.0;          // s of mj_step before reading the state (model_state.hpp)
  bool estimate_loads = false;  // loads from the least-squares split, not MuJoCo's forces
  std::string body;             // only the contacts and pairs of this body; empty: all
  // Called every 1024 pairs with (done, total) while --pairs works.
  std::function<void(size_t, size_t)> progress;
  bool pairs = false;           // also every geom pair that can collide
  std::optional<double> slope;  // degrees, [0, 90)
};

struct InspectRow {
  bool active = false;  // a contact at this state (else a pair that may collide)
  int contact = -1;     // index in d->contact, or -1
  int geom1 = -1, geom2 = -1, body1 = -1, body2 = -1;
  std::string geom1_name, geom2_name, body1_name, body2_name;
  std::string source;    // "explicit <pair>" or "default collision"
  int contacts_now = 0;  // pairs: how many contacts the pair has now
  double dist = 0.0;     // contact distance (negative: penetrating)
  std::array<double, 3> pos{}, normal{};
  int condim = 1;
  std::array<double, 5> friction{};
  std::array<double, 2> solref{};
  std::array<double, 5> solimp{};
  double timeconst_used = 0.0;  // standard form: after refsafe; 0 for the direct form
  bool refsafe_changes = false;
  double K = 0.0, B = 0.0;
  // MuJoCo ≥ 2.3.6's <pair solreffriction> (0 0: none): an elliptic
  // contact's friction rows take their B from it (mj_makeImpedance: K = 0,
  // B = 2/(d_max·tc) or −solreffriction[1]/d_max, refsafe on its
  // timeconst); B_friction is the friction rows' B either way.
  std::array<double, 2> solreffriction{};
  bool friction_ref = false;  // the friction rows use solreffriction
  double B_friction = 0.0;
  double dmax = 0.0;  // solimp[1] after MuJoCo's clamps
  // The stiffest impedance: k = d²K/(d·A + (1 − d)·Â) rises with d, and d
  // runs from solimp[0] at first touch to solimp[1] at full width, so
  // max(d0, d_max) (d0 > d_max: the impedance falls with depth).
  double d_stiff = 0.0;
  double d_now = 0.0;          // impedance at dist
  double d_rest = 0.0;         // impedance at the static penetration
  double A = 0.0;              // true inverse mass at the contact, 1/kg
  bool A_measured = false;     // false: no contact point found, A = Â assumed
  bool closest = false;        // a pair not in contact: A at its closest points (dist > 0)
  double inv_weight = 0.0;     // Â: body_invweight0 of both bodies
  double motion_scale = 0.0;   // the larger of Â and the moving bodies' 1/m (kNoMotion)
  double normal_weight = 0.0;  // Â the normal row sees (pyramidal: ·φ)
  double phi = 1.0;            // normal_weight / inv_weight
  double force = 0.0;          // MuJoCo's normal force at this state (mj_contactForce), N
  double estimate = NAN;       // the least-squares load (estimate_loads), N
  double load = 0.0;         // the load the rest depth is for: force, or estimate (NaN: not known)
  double penetration = 0.0;  // static penetration, m (NaN: not known)
  int rows = 0, quadratic = 0;     // constraint rows, and those in the solver's quadratic zone
  double normal_speed = 0.0;       // n·(v₂ − v₁) at the contact now (J·qvel), m/s
  double normal_accel = 0.0;       // J·qacc, m/s²
  double unsettled = 0.0;          // the part of its force that is not rest: (B·v + J·qacc)/R
  std::string depth_note;          // why there is no rest depth, or why MuJoCo is not at it now
  double k = 0.0, c = 0.0;         // N/m, N·s/m at d_rest
  double omega = 0.0, zeta = 0.0;  // at d_rest
  double omega_max = 0.0, zeta_max = 0.0;  // at d_stiff
  double omega_dt = 0.0, limit = 0.0;      // ω·Δt at d_stiff and the integrator's limit
  double restitution = 0.0;     // continuous time (Kelvin–Voigt, force clamped at zero)
  double restitution_dt = 0.0;  // as MuJoCo steps it at the model's Δt (bounce.hpp), at 1 m/s
  // Friction (condim ≥ 3): A_t, the larger tangent direction's inverse mass;
  // the friction rows' viscous slope c_t = impratio·B·d/((1 − d)·Â) per
  // contact (÷ (1 + μ²) for the pyramidal cone), explicit in MuJoCo's step:
  // it reverses a slip within one step above impratio_cap = impratio/(Δt·A_t·c_t);
  // sliding, MuJoCo pushes the normal force up by μ·c·|v_t| (push, N per m/s)
  // and the contact leaves the surface at lift_off = f·(1 + μ²/impratio)/(μ·c)
  // (elliptic cone; NaN for the pyramidal one and without friction).
  double A_t = 0.0, impratio_cap = NAN, push = NAN, lift_off = NAN;
  double creep = 0.0;      // m/s at --slope (NaN: not computed)
  std::string creep_note;  // why there is no creep number, or what it assumes
};

// A contact moves along its normal when A > kNoMotion·scale, the scale
// (motion_scale) the larger of Â and 1/m of each moving body of the pair
// (Â alone is 0 for a body that only turns: a sphere on a hinge through its
// centre). n·J·M⁻¹·Jᵀ·n of a contact its joints cannot move (a wheel on an
// axle through its centre, a geom pair on one hinge chain) sums terms of
// that size that cancel, to round-off: on Debian's samples 5e-33 to
// 1.1e-16 1/kg against Â of 0.14–7 1/kg, 3.3e-17·Â at most, about ε/7
// (ε = 2.2e-16). The smallest A of a contact that moves there is
// 1.1e-10·Â (active_adhesion's winch). 1e-12 sits between: an effective
// mass 1e12 times the bodies' is no contact dynamics at any timestep.
inline constexpr double kNoMotion = 1e-12;
inline bool moves_along_normal(const InspectRow& r) { return r.A > kNoMotion * r.motion_scale; }

// One body's contacts at a glance (the text's first table).
struct BodySummary {
  std::string name;
  int contacts = 0;
  double load = 0.0;                      // the sum of its contacts' loads, N
  double deepest = 0.0;                   // the largest rest depth, m (NaN: none known)
  double mass_min = 0.0, mass_max = 0.0;  // effective masses 1/A over its contacts, kg
  double stability = 0.0;  // the largest ω·Δt / limit over its contacts (≥ 1: unstable)
  // Its contacts hitting together at 1 m/s, stepped as MuJoCo steps them
  // (bounce.hpp): the body's bounce, and how much it varies with where in
  // a step the contacts begin (NaN: no contact its joints can move).
  double bounce = 0.0, bounce_spread = 0.0;
};

// One kinematic tree (a child of the world and every body below it): its
// weight Σ m·|g| against what the contacts with other trees and the world
// push it up by, Σ f·(n·up) (up = −g/|g|; a contact pushes geom2 along its
// normal n, geom1 against it). At rest a free tree's contacts carry its
// weight; a tree jointed to the world shares it with its joints.
struct TreeLoad {
  std::string root;  // the tree's top body
  int bodies = 0;
  double mass = 0.0;     // kg
  double weight = 0.0;   // Σ m·|g|, N
  double support = 0.0;  // Σ f·(n·up) over its contacts with the rest, N
  int contacts = 0;      // its contacts with the rest (the world, other trees)
  bool free = false;     // its top body has a free joint (nothing but contacts holds it)
};

struct InspectReport {
  std::string path, key;
  std::string version;   // MuJoCo's
  double settled = 0.0;  // s of settling
  double speed = 0.0;    // largest |qvel| at the state
  double accel = 0.0;    // largest |qacc| at the state
  bool at_rest = true;   // model_state.hpp's at_rest()
  bool loads_estimated = false;
  std::string load_warning;
  std::string integrator;  // Euler, RK4, implicit
  double dt = 0.0;
  std::string cone;  // pyramidal, elliptic
  double impratio = 1.0;
  int noslip_iterations = 0;  // > 0: MuJoCo's noslip pass, which the creep does not model
  std::array<double, 3> gravity{};
  bool refsafe_enabled = true;
  std::optional<double> slope;
  // The least-squares split (estimate_loads): whether normal forces alone can
  // hold the model against gravity at this configuration (qvel = 0), within
  // a relative residual of 1e-6 and with no force pulling; computed whether
  // or not --estimate-loads is asked.
  bool balanced = true;
  double residual = 0.0;        // |Jₙᵀ·f − qfrc_bias| / |qfrc_bias|
  std::vector<TreeLoad> trees;  // every moving tree, in body order (all contacts, not --body's)
  // When the state is not at rest: the settle time after which MuJoCo is
  // (rest_search: how far it was looked for; rest_after NaN: not looked
  // for, +∞: not at rest within rest_search s either). Filled by
  // settle_time() (mujoco3/inspect_versions.hpp), which re-reads the model.
  double rest_after = std::numeric_limits<double>::quiet_NaN();
  double rest_search = 0.0;
  std::vector<InspectRow> contacts;
  std::vector<BodySummary> bodies;  // every moving body with a contact, in body order
  std::string body;                 // --body: the one body listed
  std::vector<InspectRow> pairs;    // with --pairs
  bool pairs_listed = false;
  std::vector<std::string> warnings;
};

// MuJoCo 2.2.2's. Throws InputError: the file cannot be read or MuJoCo
// cannot load it (MuJoCo's message on one line), an unknown --key, --slope
// or --settle out of range.
InspectReport inspect(const InspectOptions& options);

// The same from a state either version read (mujoco3/model_state.hpp for
// 3.14); options.pairs is refused (it probes MuJoCo 2.2.2's model).
InspectReport inspect_state(const ModelState& state, const InspectOptions& options);

std::string format_inspect_text(const InspectReport& report);
std::string format_inspect_json(const InspectReport& report);

}  // namespace contact2d::mujoco
