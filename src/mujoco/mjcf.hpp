// MJCF for a scene (docs/mujoco.md), written with tinyxml2: same scene and options,
// same bytes.
//
// The plane of motion is MuJoCo's x–z plane (2D y = MuJoCo z). One body with
// slide joints along x and z and, for bodies that rotate, a hinge about
// (0, −1, 0) so that θ is counter-clockwise in the x–z plane (R_y(−θ) maps
// (x, z) to (x·cosθ − z·sinθ, x·sinθ + z·cosθ), the 2D R(θ)). The body frame
// is the COM and is written in the initial pose, so that qpos0 (what a
// viewer shows on opening the file) is the scene's start: pos (x0, 0, y0),
// axisangle (0, −1, 0, θ0), hinge ref = θ0 (MuJoCo turns the body by
// qpos − ref), and slide axes (cosθ0, 0, −sinθ0), (sinθ0, 0, cosθ0), which
// are MuJoCo x and z in that rotated frame. qpos = (x − x0, y − y0, θ),
// qvel = (vx, vy, ω); keyframe "initial" is qpos0 with the initial
// velocities. Contact parameters live in <default> so that the ground plane
// carries the same values and MuJoCo's per-pair mixing (friction and condim:
// max, direct solref: min, solimp: average) changes nothing.
//
// condim is what the scene needs (contact_condim): 1 without friction, 3
// with sliding friction only, 6 with rolling or torsional friction;
// friction "μ μ_torsion μ_roll". nconmax = 2·P + 40 (P: contacts the body
// can make with the ground; room for 10 added geoms of up to 4 contacts),
// njmax = rows of a condim-6 contact (6 elliptic, 10 pyramidal) × nconmax.
//
// Contact geoms, named for what they are:
//   point mass  "contact_point": a sphere of radius ε = kCornerRadius centred
//               at (0, ε − h): its lowest point is the 2D contact point
//               (0, −h), on flat ground, a slope or an obstacle's edge alike;
//               "visual_point", a sphere of radius h at the COM, draws it
//   circle      "disc": a sphere of radius R at the COM: the single contact
//               point below the centre of Algorithm 4
//   box, T      corners: "corner<i>", a sphere of radius ε = kCornerRadius at
//               every 2D contact point (one MuJoCo contact per 2D point; the
//               contact sits ε lower than the 2D point, shifting rest
//               heights by ε); the parts are drawn by "visual_part<j>_box"
//               boxes:   "part<j>_box", one box geom per part (a 2D corner
//               becomes a 3D edge whose two end vertices both touch: 2
//               contacts per point)
// Visual-only geoms (contype = conaffinity = 0, group 1) draw the shape.
// Under the compensated mapping (mapping.hpp) the contact geoms sit instead
// on a massless child body "contacts" (explicit <inertial> of mass 0 at its
// origin) placed at (L, 0, 0) in the body frame, each geom at its own
// point less (L, 0, 0); corner spheres (and their obstacle pairs) get
// gap = kCornerRadius, so that MuJoCo's contact starts and its spring is
// measured at the 2D point; the point mass gets a hinge "spin" about
// MuJoCo z that turns "contacts" (no contact force has a moment about it);
// a disc with rolling resistance gets the cone coefficient μ_roll'
// (docs/mujoco.md).
//
// Static obstacles (core/obstacles.hpp) are world-body geoms "obstacle<i>":
// a box obstacle a box geom (centre (x, 0, y), half-size (w/2, D, h/2), D
// deep enough to hold every body geom), a segment a capsule from (x1, 0, y1)
// to (x2, 0, y2) of its radius, whose cut by the plane y = 0 is the 2D
// capsule (a sphere when a = b). They have contype = conaffinity = 0 and
// touch the body only through an explicit <contact><pair> per (contact
// geom, obstacle), which carries the obstacle's own law (its keys over the
// scene's [contact]) mapped like the ground's: solref from its k, c (same Â
// and n), friction (μ, μ, μ_torsion, μ_roll, μ_roll), its condim, the
// scene's solimp. A pair's values are used as given, where geom values
// would be mixed (friction: max, direct solref: min, solimp: average).
// calibrated's impratio, one value for all contacts, uses the largest c.
// A moving obstacle (Obstacle::moves, a box: the game's keeper) is the same
// geom at the origin of its own mocap body "obstacle<i>_body" (after the
// planar body, which stays body 1), placed by Stepper::move_obstacle.
//
// The header comment states every derived value with the formula that
// computes it (tests/mujoco/test_mjcf_header.cpp recomputes them) and marks
// the ones that depend on Δt: calibrated's impratio, and the timeconst
// MuJoCo uses under seed/exact (refsafe: max(timeconst, 2Δt)).
//
// Inertia (explicit <inertial>, inertiafromgeom="false"): the 2D value on the
// hinge axis (MuJoCo y). The other two axes carry no joint; they are the
// values of a prism of depth D (box, T: D = smallest side of any part) or,
// for the circle, of a cylinder of length 2R: Ix = Iz = m·R²/4 + m·(2R)²/12,
// raised where MuJoCo's checks need it (each ≥ mjMINVAL, A + B ≥ C).
#pragma once

#include <string>

#include "core/scene.hpp"
#include "mujoco/mapping.hpp"

namespace contact2d::mujoco {

// Radius of a corner sphere: small against any penetration the tolerance
// tests resolve (the rest height shifts by exactly this much), large against
// MuJoCo's mjMINVAL = 1e-15.
constexpr double kCornerRadius = 1e-9;

// The MuJoCo the model is written for. The contact law is the same on both;
// V3 (MuJoCo 3.14, the engine mujoco3) differs where MuJoCo 3 changed what
// the same MJCF does: a point mass gets the hinge "spin" under every mapping
// (3.0 gives a body with only slide joints body_invweight0 = 1/m), the
// compensated corners start at margin = −ε instead of gap = ε (3.9's
// margin/gap), and the solver's tolerance is kV3Tolerance (3.11's early
// exits). docs/mujoco3.md measures each.
enum class Version { V2, V3 };

// MuJoCo 3's solver tolerance: small enough that its early exits (3.11) stop
// where 2.2.2's Newton solver does (docs/mujoco3.md).
constexpr double kV3Tolerance = 1e-12;

struct MjcfOptions {
  Mapping mapping = kDefaultMapping;
  Geometry geometry = kDefaultGeometry;
  std::string source;  // the scene file named in the header comment, as given
  int condim = 0;      // 0: contact_condim(); 1, 3 or 6 forces it (for measurements)
  // The Δt the mapping's Δt-dependent values (calibrated's impratio) are
  // computed for; 0: the scene's sim.dt (the timestep). Set, it holds the
  // model fixed while the timestep changes (`--model-dt`).
  double model_dt = 0.0;
  Version version = Version::V2;
  // MuJoCo 3 only: the friction rows get a damper of their own
  // (set_friction_damper in mapping.hpp: solreffriction on one <pair> per
  // contact geom and the ground, and per obstacle). The engine mujoco3's
  // option friction=damper.
  bool friction_damper = false;
};

// condim of every contact geom (and the plane): only what the scene needs,
// 1 without friction (μ = μ_roll = μ_torsion = 0), 3 with sliding friction
// only, 6 with rolling or torsional friction.
int contact_condim(const ContactParams& contact);

// Options from their names (empty: the default); throws InputError naming
// an unknown mapping or geometry.
MjcfOptions mjcf_options(const std::string& mapping, const std::string& geometry,
                         const std::string& source);

struct GeneratedModel {
  std::string xml;
  SolverSettings settings;
};

// The MJCF of a scene. For the calibrated mapping it compiles a first pass
// to read body_invweight0 (the effective-mass factor Â) from MuJoCo, then
// writes the final model. Throws InputError when the scene cannot be mapped
// (explicit Euler; seed/exact with k or c = 0 or a timeconst or dampratio
// that overflows or underflows, the ground's or an obstacle's)
// or MuJoCo rejects the final model or warns while loading it (it is loaded
// once to check).
GeneratedModel generate_mjcf(const Scene& scene, const MjcfOptions& options);

// The rolling coefficient the model writes for the scene under `s`:
// compensated's μ_roll' = μ_roll/√(1 − q²) for a rolling disc (MuJoCo's
// elliptic cone shares one budget between sliding and rolling,
// docs/mujoco.md), otherwise the scene's μ_roll. The second form for one
// law of the scene (an obstacle's own): its pairs write that law's.
double cone_mu_roll(const Scene& scene, const SolverSettings& s);
double cone_mu_roll(const Scene& scene, const ContactParams& p, const SolverSettings& s);

// The MJCF with given solver settings (no MuJoCo involved).
std::string write_mjcf(const Scene& scene, const MjcfOptions& options,
                       const SolverSettings& settings);

// How messages name the MJCF generated from a scene file: "<source> (its
// generated MJCF)".
std::string generated_origin(const std::string& source);

// Shortest decimal text that reads back as the same double ("0.1", not
// "0.10000000000000001").
std::string format_exact(double value);

}  // namespace contact2d::mujoco
