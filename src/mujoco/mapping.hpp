// From the reference contact law (k, c, μ, α) to MuJoCo 2.2 solver settings.
//
// MuJoCo's soft contact (engine_core_constraint.c) sets, per constraint row,
// a reference acceleration aref = −B·v − K·d·pos and a regulariser
// R = (1−d)/d·Â, with d the impedance (solimp) and Â the approximate inverse
// mass of the contact (body_invweight0). The standard solref form
// (timeconst, dampratio) gives K = 1/(d_max²·tc²·ζ²), B = 2/(d_max·tc); the
// direct form (−stiffness, −damping) gives K = stiffness/d_max²,
// B = damping/d_max. Three named mappings:
//
//   seed        timeconst = √(m/k), dampratio ζ = c/(2√(m·k))   (the common rule of thumb):
//               K·d_max² = 1/(tc²ζ²) = (k/m)/ζ², B·d_max = 2/tc = (c/m)/ζ,
//               so it reproduces k/m and c/m only when ζ = 1.
//   exact       timeconst = 2m/c, dampratio = c/(2√(m·k)):
//               K·d_max² = 1/(tc²ζ²) = (c²/4m²)·(4mk/c²) = k/m,
//               B·d_max  = 2/tc = c/m,
//               i.e. the same as the direct form solref = (−k/m, −c/m).
//   calibrated  direct form solref = (−k·Â/n, −c·Â/n), flat minimal impedance
//               d = 1e-4, elliptic cone, impratio = 1/(c·Δt·A_t) (below).
//
// Why calibrated reproduces F = k·p − c·v: for one contact the solver's
// unconstrained (quadratic-zone) force is f = (aref − a0)/(A + R) with A the
// true inverse mass. With d ≪ 1, A + R ≈ Â/d and d·aref = (k·Â·p − c·Â·v)/n,
// so f = (k·p − c·v)/n − d·a0/Â + O(d): the Kelvin–Voigt law (the solver
// clamps f ≥ 0), independent of the true A, to a relative O(d) = 1e-4. n is
// the number of MuJoCo contacts one 2D contact point becomes (1 for a corner
// sphere, 2 for an edge of a box geom). seed and exact keep MuJoCo's default
// impedance (0.9–0.95), under which gravity inside a contact is scaled by
// (1 − d): the static penetration is only 5–10 % of m·g/k.
//
// Friction (calibrated): in the elliptic cone the tangential rows get
// R_t = R/impratio and no spring, so inside the cone MuJoCo's friction is
// viscous, f_t = −impratio·c·v_t, capped at μ·f_n. On the cone surface
// (sliding) the normal force becomes
//   f_n = (k·p − c·v_n + μ·c·|v_t|)/(1 + μ²/impratio):
// the damper's slip term pushes the body up (it hops), and the divisor
// weakens the contact. No setting removes the push (B is shared by all rows
// of a contact); a large impratio removes the divisor, but the friction
// force is explicit in v_t, so a slope above 1/(Δt·A_t) reverses the slip
// within one step and the contact chatters at rest. impratio = 1/(c·Δt·A_t),
// with A_t = 1/m + r_max²/I the largest tangential inverse mass of a contact
// point, is the largest chatter-free value (rolling rows, whose slope is
// impratio·c·(μ_roll/μ)², bound it too). It depends on Δt: 5, 50, 500
// for validation/scenes/box.toml (c = 50, A_t = 4/kg) at Δt = 1e-3, 1e-4,
// 1e-5 (the generated header says so). No Δt-independent value measured as
// well (bench/impratio_dt.cpp, Kelvin–Voigt built-in scenes at Δt = 1e-4:
// the rule's value at Δt = 1e-3 kept fixed halves the box's max position
// error, 17 → 8 mm, but multiplies the T's by 14, 18 → 256 mm; μ·m·g·α/c
// gives 15 mm and 136 mm). The reference's tanh slope μ·Fn·α
// only shapes speeds below 1/α and is not matched.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "core/scene.hpp"

namespace contact2d::mujoco {

enum class Mapping { Seed, Exact, Calibrated };
constexpr Mapping kAllMappings[] = {Mapping::Seed, Mapping::Exact, Mapping::Calibrated};
constexpr Mapping kDefaultMapping = Mapping::Calibrated;

std::string_view mapping_name(Mapping mapping);  // "seed", "exact", "calibrated"
std::optional<Mapping> parse_mapping(std::string_view name);

// Which MuJoCo geoms carry the 2D contact points of a box or T. The point
// mass and the circle always use one sphere.
enum class Geometry { CornerSpheres, BoxGeoms };
constexpr Geometry kDefaultGeometry = Geometry::CornerSpheres;
std::string_view geometry_name(Geometry geometry);  // "corners", "boxes"
std::optional<Geometry> parse_geometry(std::string_view name);

// MuJoCo contacts that one 2D contact point becomes: a corner sphere gives
// one, a box geom gives two (a 2D corner is a 3D edge, both of its end
// vertices touch the plane).
int contacts_per_point(Shape shape, Geometry geometry);

// MuJoCo 2.2's defaults, used by seed and exact for everything but solref.
constexpr std::array<double, 5> kMujocoDefaultSolimp = {0.9, 0.95, 0.001, 0.5, 2.0};
// Flat impedance at MuJoCo's minimum (mjMINIMP = 1e-4): solimp[0] == solimp[1].
constexpr std::array<double, 5> kMinimalSolimp = {0.0001, 0.0001, 0.001, 0.5, 2.0};

struct SolverSettings {
  Mapping mapping = kDefaultMapping;
  std::array<double, 2> solref = {0.02, 1.0};  // standard: (timeconst, dampratio); direct: both < 0
  std::array<double, 5> solimp = kMujocoDefaultSolimp;
  bool elliptic = false;  // cone="elliptic" (else MuJoCo's default pyramidal)
  double impratio = 1.0;
  double inv_mass = 0.0;  // Â used by calibrated (body_invweight0), 0 otherwise
  int split = 1;          // contacts per 2D point (calibrated divides k and c by it)
  // Standard form only: MuJoCo's refsafe raises timeconst to 2·timestep
  // (silently softening the contact); true when that happens here.
  bool refsafe_clamped = false;
};

// Solver settings of a mapping. `inv_mass` is MuJoCo's body_invweight0 of
// the body (read from the compiled model; only calibrated uses it). Throws
// InputError when the scene's k, c cannot be expressed by the mapping
// (seed and exact need k > 0 and c > 0, and a timeconst and dampratio that
// are positive normal floating-point numbers: not 0, subnormal or inf).
SolverSettings solver_settings(const Scene& scene, Mapping mapping, double inv_mass, int split);
// The same from the contact law, the body (its mass; for impratio its
// inertia, contact points and roll radius) and the Δt: the scene version
// calls this one with make_body(scene) and largest_damping(scene) (`contact2d
// solref` calls it with a body it describes by its mass, inertia and lever).
// largest_c: the largest damper of every contact law of the model, which
// bounds calibrated's one impratio (0: contact.c).
SolverSettings solver_settings(const ContactParams& contact, const RigidBody& body, double dt,
                               Mapping mapping, double inv_mass, int split, double largest_c = 0.0);

// The largest c of the scene's [contact] and its obstacles' own laws: the
// damper that bounds calibrated's impratio (one value for every contact).
double largest_damping(const Scene& scene);

// MuJoCo's contact spring and damper per unit of approximate inverse mass
// as its solver computes them from solref/solimp (K·d_max², B·d_max): the
// quantity each mapping is meant to set equal to (k·Â, c·Â) or (k/m, c/m).
struct AccelerationGains {
  double stiffness = 0.0;  // 1/s²
  double damping = 0.0;    // 1/s
};
AccelerationGains acceleration_gains(const std::array<double, 2>& solref);

// MuJoCo's integrator name for a scene integrator; throws InputError naming
// sim.integrator for explicit_euler, which MuJoCo 2.2 does not have.
std::string mujoco_integrator(Integrator integrator);

}  // namespace contact2d::mujoco
