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
//   compensated calibrated's settings with MuJoCo's O(d) error removed
//               (below): solref = (−k·D/n, −c·D/n), D = d/m + (1 − d)·Â,
//               and the contact geoms on a massless body at a lever L that
//               raises their Â to G·A_max (G = kCompensatingGain).
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
// Why compensated reproduces it to 1e-10: with solref (−S, −D_) the exact
// single-contact force is f = (S·p − D_·v + d·g)/(d·A + (1 − d)·Â) (docs/
// mujoco.md, checked against MuJoCo by test_mujoco_contact_force.cpp).
// S = k·D, D_ = c·D with D = d·A_c + (1 − d)·Â gives
//   f = (k·p − c·v)·(1 + d·(A_c − A)/(d·A + (1 − d)·Â)) + d·g/(d·A + (1 − d)·Â):
// exact where A = A_c (= 1/m: the point mass, the disc, a contact in line
// with the COM) but for the offset d·g/(…), and elsewhere off by the
// relative d·(A − A_c)/Â. mjMINIMP = 1e-4 bounds d, not Â: Â is
// body_invweight0 of the geom's body (mj_diagApprox uses geom_bodyid, not
// the weld root), the mean of the three translational diagonal entries of
// J·M⁻¹·Jᵀ at that body's COM (engine_setconst.c). A massless body without
// joints, fixed to the moving one at a lever L in the plane and turned by
// its hinge of inertia I, has Â = (2/m + L²/I)/3; the contact geoms moved
// onto it (each placed back at its own point) touch exactly where they did on the moving body, and
// with Â = G·A_max both error terms fall by G: relative ≤ d/G = 1e-10, the
// offset ≤ 1e-10·m·g. The coupling of several contacts (off-diagonal
// A_ij) is of the same relative order d·A_ij/Â. The point mass has no
// hinge; it gets one about MuJoCo z ("spin"), about which no contact force
// has a moment (its contact lies on the vertical through the COM), so it
// never turns. A corner sphere's surface is ε = kCornerRadius below its
// 2D point: compensated gives it gap = ε, so MuJoCo includes the contact
// from dist < −ε and measures the spring from there (includemargin =
// margin − gap): from the 2D point itself. Measured frictionless (bench/
// compensation_table.cpp): 2.1e-14 to 3.9e-8 m against calibrated's 1.3e-7
// to 1.3e-3 m on the drops at ζ = 0.1…5; the one random scene above 1e-5 m
// is one the reference itself moves 1.8e-5 m when its start is nudged by
// 1e-15 m (rounding, amplified).
//
// Friction (calibrated and compensated alike): in the elliptic cone the tangential rows get
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
//
// With rolling rows (condim 6) the same projection pushes by
// c·√((μ·v_t)² + (μ_roll·ω)²): a disc rolling at ω is lifted by
// μ_roll·c·|ω| even without slip. The cone also shares one budget,
// (f_t/μ)² + (τ/μ_roll)² ≤ f_n²: a disc rolling steadily needs
// f_t = κ·τ/R (κ = m·R²/(I + m·R²)), so compensated writes
// μ_roll' = μ_roll/√(1 − q²), q = κ·μ_roll/(μ·R), which gives back the
// reference's torque μ_roll·F_n (mjcf.cpp, cone_mu_roll; docs/mujoco.md
// has the friction table and what remains).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "core/scene.hpp"

namespace contact2d::mujoco {

enum class Mapping { Seed, Exact, Calibrated, Compensated };
constexpr Mapping kAllMappings[] = {Mapping::Seed, Mapping::Exact, Mapping::Calibrated,
                                    Mapping::Compensated};
constexpr Mapping kDefaultMapping = Mapping::Calibrated;

// "seed", "exact", "calibrated", "compensated"
std::string_view mapping_name(Mapping mapping);
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
  double inv_mass = 0.0;  // Â used by calibrated/compensated (body_invweight0), 0 otherwise
  // compensated only: the lever (m) of the massless body that carries the
  // contact geoms, and the inverse mass A_c its solref assumes (1/m).
  double lever = 0.0;
  double assumed_inv_mass = 0.0;
  int split = 1;  // contacts per 2D point (calibrated divides k and c by it)
  // Standard form only: MuJoCo's refsafe raises timeconst to 2·timestep
  // (silently softening the contact); true when that happens here.
  bool refsafe_clamped = false;
  // MuJoCo 3's friction damper (friction_damper_settings; 0: the friction
  // rows share the contact's damper, as MuJoCo 2.2.2 must): φ, the friction
  // rows' damper as a fraction of the normal row's, and b, the stick slope
  // (N·s/m) of one 2D contact point that impratio then sets.
  double friction_ratio = 0.0;
  double stick_slope = 0.0;
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

// compensated: Â of the contact geoms' body is raised to kCompensatingGain
// times the largest true inverse mass A_max of a contact, so that MuJoCo's
// dependence on A, d·A/Â relative, falls from ≤ 6e-4 to ≤ d/gain = 1e-10.
constexpr double kCompensatingGain = 1e6;
// The lever L (m) at which a massless body fixed to the moving one has
// body_invweight0 = (2/m + L²/I)/3 = kCompensatingGain·max_inverse_mass
// (I: the inertia about the hinge that turns it; mapping.hpp).
double compensating_lever(double mass, double hinge_inertia, double max_inverse_mass);

// What calibrated and compensated multiply k/n and c/n by in solref: Â
// (calibrated), D = d/m + (1 − d)·Â (compensated); 0 for seed and exact.
double solref_scale(const SolverSettings& settings);

// MuJoCo 3's friction damper (solreffriction, from 2.3.6, on explicit
// <pair>s, elliptic cone only): the friction rows of a contact get the damper
// B_f = φ·B of their own instead of the normal row's B, with R_t = R/impratio
// as before. Then (docs/mujoco3.md, measured to 1.7e-10 relative)
//   stick:  f_t = −b·v_t per 2D point, b = impratio·φ·c;
//   slide:  f_n = (k·p − c·v_n + μ·φ·c·|v_t|)/(1 + μ²/impratio):
// the push μ·c·|v_t| of the shared damper (mapping.hpp) shrinks by φ, and
// impratio, which is large now, removes the divisor. The settings here:
//   b = min((√6/π)·μ·α·m·g/N, 1/(Δt·A_t)) per 2D point, N the points the
//       body rests on: the tanh law's slope μ·F·α scaled so that the
//       saturated-viscous stopping excess μ·g·m²/(2·B²) of the body (B = N·b)
//       equals tanh's π²/(12·α²·μ·g) — a body sliding to rest stops where
//       the reference's does — capped where the explicit friction would
//       reverse a slip within one step (A_t as for calibrated's impratio);
//   φ = 1e3·A_t·b/(R·c), R = (1 − d)/d·Â the normal row's regulariser: the
//       smallest ratio that keeps R_t ≥ 1e3·A_t, so that f_t = −B_f·v_t/(A_t
//       + R_t) is b·v_t to 0.1 % while the push is as small as that allows;
//   impratio = b/(φ·c).
// Only over compensated (whose R ≈ 1e10·A_max leaves room for a small φ;
// under calibrated φ ≤ 1e-4 breaks, docs/mujoco3.md). A scene without
// friction (μ = 0) is left as it is; one without a resting load (gravity
// 0: m·g = 0, so b would be 0 and impratio 0/0) takes b at its cap.
void set_friction_damper(SolverSettings& s, const ContactParams& contact, const RigidBody& body,
                         double dt, double gravity);

// The 2D contact points a body rests on, flat on the ground (θ = 0): 1 for a
// point mass or disc, the lowest corners of a box or T.
int resting_points(const RigidBody& body);

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
