// `contact2d solref`: the MuJoCo numbers for a user's own model.
//
// Given a contact's k, c, the timestep Δt and the body (a mass and how it is
// jointed, optionally an inertia and a lever; or body_invweight0 read from
// the user's compiled model), it runs the generator's own mapping code (mapping.hpp,
// solver_settings) and says what MuJoCo 2.2 will then do with each mapping's
// solref/solimp (engine_core_constraint.c; docs/mujoco.md):
//
//   Â = body_invweight0: MuJoCo's set0 (engine_setconst.c) takes the mean of
//   the translational diagonal of J·M⁻¹·Jᵀ at the body's COM, so a free
//   joint gives (1/m + 1/m + 1/m)/3 = 1/m; slide x, slide z and a hinge
//   (planar) (1/m + 0 + 1/m)/3 = 2/(3m); one slide joint along the normal
//   1/(3m); one hinge with the COM at distance r from its axis
//   r²/(3·(I + m·r²)) (the COM moves on a circle: J·Jᵀ has trace r²).
//
//   K = S/d_max², B = D/d_max with (S, D) = acceleration_gains(solref) after
//   refsafe (standard form: timeconst raised to 2Δt); R = (1 − d)/d·Â.
//
// Natural frequency and damping ratio of the contact point (flat impedance
// at d_max, the stiffest value the impedance reaches):
//   ω² = A·d²K/(d·A + (1 − d)·Â),   2ζω = A·d·B/(d·A + (1 − d)·Â).
//
// Static penetration: at rest every contact row has J·qacc = 0, and in the
// solver's quadratic zone f = −(J·qacc − aref)/R, so f·R = aref = K·d·p
// (v = 0, p = −efc_pos): p = f·(1 − d)·Â/(K·d²), whatever A and however
// many contacts share the load. d depends on p for a non-flat solimp (the
// default 0.9 → 0.95 over 1 mm), so p solves p·K·d(p)² = f·Â·(1 − d(p)),
// found by bisection (the left side grows and the right side falls with p).
// For calibrated (K·d² = k·Â, flat d = 1e-4): p = (1 − d)·f/k. With
// MuJoCo's default pyramidal cone and friction (seed, exact with μ > 0) the
// normal force is the sum of 2(condim − 1) edge rows whose regulariser is
// 2μ²(1 + μ²)·R/impratio: Â becomes Â·μ²(1 + μ²)/((condim − 1)·impratio) in
// all of the above (0.16·Â at μ = 0.5, condim 3: a 6× stiffer contact).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mujoco/mapping.hpp"
#include "mujoco/model_state.hpp"

namespace contact2d::mujoco {

// How the user's body is jointed to the world (the joints of its MuJoCo body).
enum class Joint { Free, Planar, Slide, Hinge };
std::string_view joint_name(Joint joint);  // "free", "planar", "slide", "hinge"
std::optional<Joint> parse_joint(std::string_view name);
// body_invweight0 as MuJoCo 2.2's set0 computes it for that joint set (the
// header comment); pivot: the COM's distance from the hinge axis (hinge only).
// MuJoCo 3 (mujoco3): a body whose joints are all slides does not rotate
// and gets 1/m (engine_setconst.c: body_simple == 2), so one slide joint is
// 1/m there, 1/(3m) in 2.2.2.
double joint_inv_weight(Joint joint, double mass, double inertia, double pivot,
                        bool mujoco3 = false);

// The user's friction when the snippet does not write it (no --mu): what the
// pyramidal cone's effect on the normal force is computed with.
struct UserFriction {
  double mu = 1.0;  // MuJoCo's default geom friction
  int condim = 3;   // MuJoCo's default
  double impratio = 1.0;
  bool elliptic = false;
  int noslip_iterations = 0;  // the model's: > 0, no creep is estimated (inspect.hpp)
  std::string source = "MuJoCo's defaults: μ = 1, condim 3, pyramidal cone, impratio 1";
};

// The contact as a mechanism: A, the true inverse mass along the normal
// (1/m + lever²/I; a hinge lever²/(I + m·pivot²)), and f, the normal load
// per MuJoCo contact at rest (m·g/contacts; a hinge m·g·pivot/(lever·contacts)).
struct ContactMechanics {
  double inv_mass = 0.0;
  double load = 0.0;
};
// A geom of a contact, as a <pair> must name it: MuJoCo's name or, for an
// unnamed geom (which MuJoCo and this tool show as "geom #ID"), where it
// sits in the model file: its body and its place among that body's geoms.
struct GeomRef {
  std::string name;       // MuJoCo's name, or "geom #ID"
  bool named = true;      // false: the model gives it no name
  int id = -1;            // MuJoCo's geom id
  std::string body;       // its body's name ("world": the <worldbody>)
  int index_in_body = 0;  // 0: the body's first geom
};
// One of the body's contacts in the settled model, as MuJoCo has it.
struct SettledContact {
  std::string geom1, geom2;
  GeomRef ref1, ref2;
  // What MuJoCo resolved for the geom pair (its mixing of the two geoms'
  // values, or an explicit <pair>'s): what --apply's pairs write back.
  int condim = 1;
  std::array<double, 5> friction{};
  double margin = 0.0, gap = 0.0;
  bool explicit_pair = false;
  double A = 0.0;            // n·J·M⁻¹·Jᵀ·n at the contact, 1/kg
  double A_t = 0.0;          // the same along its larger tangent direction (condim ≥ 3)
  double load = 0.0;         // MuJoCo's normal force, N
  double penetration = 0.0;  // −dist, m
  double inv_weight = 0.0;   // Â of the contact: both bodies' body_invweight0, 1/kg
  // What the default class snippet meets (class_caveats): which geom is the
  // body's (0: geom1), both geoms' priority and solref as compiled, and the
  // class the body's geom has in the model's own file ("" none, or not
  // written there), which class="contact2d" would replace: its name and
  // where it comes from ("" its class attribute, or "the childclass of body
  // 'B'").
  int own = 0;
  std::array<int, 2> priority{};
  std::array<std::array<double, 2>, 2> geom_solref{};
  std::string own_class, own_class_from;
};

struct SolrefInput {
  double k = 0.0;         // N/m, per MuJoCo contact
  double c = 0.0;         // N·s/m, per MuJoCo contact
  double dt = 0.0;        // s, MuJoCo's timestep
  std::string dt_source;  // "" (--dt) or where Δt comes from, for the text
  double mass = 0.0;      // kg
  Joint joint = Joint::Free;
  double inertia = 0.0;  // kg·m² about the COM, the axis the lever turns the body (0: no rotation)
  double lever = 0.0;    // m, distance of the contact point from the COM across the normal
                         // (hinge: the contact normal's moment arm about the hinge axis)
  double pivot = 0.0;    // m, hinge only: distance of the COM from the hinge axis
  double inv_weight = 0;       // Â = body_invweight0, 1/kg; 0: joint_inv_weight(joint, ...)
  bool keep_friction = false;  // no --mu: write no condim/friction, keep the user's
  UserFriction user_friction;  // used when keep_friction
  double mu = 0.0;             // sliding friction
  double mu_roll = 0.0;        // rolling friction, m (needs inertia and lever, the rolling radius)
  int contacts = 1;            // MuJoCo contacts that share the body's weight at rest
  std::string contacts_source = "--contacts";  // where that number comes from, for the text
  // solref --model: the contact as MuJoCo has it in the settled model (A at
  // the contact point through the body's whole chain of joints, MuJoCo's
  // normal force); contact_mechanics returns it instead of the joint set's
  // formula, and the body's contacts are listed.
  std::optional<ContactMechanics> measured;
  std::string measured_source;
  std::vector<SettledContact> settled_contacts;
  std::string model_version;  // the MuJoCo that settled --model ("2.2.2", "3.14.0")
  // The tangential inverse mass of the body's settled contacts slipping
  // together (their friction rows' J·M⁻¹·Jᵀ, largest eigenvalue):
  // calibrated's impratio cap 1/(Δt·A_t·c) uses it in place of 1/m.
  double tangential_inv_mass = 0.0;
  bool mujoco3 = false;         // Â by MuJoCo 3's rule (joint_inv_weight)
  std::optional<double> slope;  // --slope, degrees in [0, 90)
  double gravity = 9.81;        // m/s²
  // Where the numbers come from, for the text ("--mass 1" or "model.xml, body 'box'").
  std::string body_source;
  // How k and c were found when targets gave them (solve_targets), for the
  // text; empty when --k and --c were given.
  std::string targets_note;
};

ContactMechanics contact_mechanics(const SolrefInput& input);

// What a user wants of a contact instead of k and c (`contact2d solref
// --restitution e [--k K | --contact-time T] | --penetration p`):
//   restitution e   the Kelvin–Voigt law with its force clamped at zero
//                   rebounds at e = v_out/v_in, a function of ζ alone
//                   (inspect.hpp, decreasing from 1 at ζ = 0): ζ by bisection,
//                   then c = 2ζ·√(k/A);
//   contact time T  the same oscillator's time until its force returns to
//                   zero is τ(ζ)/ω: with e's ζ, ω = τ(ζ)/T, k = ω²/A;
//   penetration p   the calibrated mapping's static depth per contact is
//                   (1 − d)·f/k (d = 1e-4, its flat impedance): k = (1 − d)·f/p.
// k comes from exactly one of --k, --penetration, --contact-time; c from
// --c or --restitution.
struct SolrefTargets {
  std::optional<double> restitution;
  std::optional<double> contact_time;
  std::optional<double> penetration;
};
// Sets input.k and/or input.c from the targets (the others stay as given)
// and input.targets_note; throws InputError naming the option for a value
// out of range or a combination that over- or under-determines k or c.
// `k_given`, `c_given`: whether --k and --c were on the command line.
void solve_targets(SolrefInput& input, const SolrefTargets& targets, bool k_given, bool c_given);

// A contact of the body where the default class snippet does not give it the
// mapping's solref and solimp (MuJoCo's mixing of a geom pair without a
// <pair>, mj_collideGeoms in 2.2.2's engine_collision_driver.c): case
// "priority" (the other geom's priority is higher, or equal to the --mu
// snippet's 1: MuJoCo takes the higher one's values, or mixes them),
// "direct_solref" (a solref in direct form, negative: MuJoCo takes the
// element-wise min of the two, not the solmix weight), "explicit_pair" (a
// <pair> makes the contact: its values are used), "class_replaced" (the
// body's geom has a class of its own that class="contact2d" replaces, with
// whatever else it sets). <pair>s (--apply) hold in every case.
struct ClassCaveat {
  std::string kind;     // "priority", "direct_solref", "explicit_pair", "class_replaced"
  std::string contact;  // "floor – box"
  std::string why;
};

struct MappingOutcome {
  Mapping mapping = kDefaultMapping;
  std::string unavailable;  // non-empty: why this mapping cannot express k, c (or is not offered)
  std::string unfit;        // non-empty: why this mapping is not one to build a model on
  SolverSettings settings;
  int condim = 1;               // 0: not written (the user's friction is kept)
  double timeconst_used = 0.0;  // standard form: after refsafe; 0 for the direct form
  double K = 0.0, B = 0.0;      // MuJoCo's KBIP[0], KBIP[1]
  double normal_weight = 0.0;   // Â, or Â·φ for a pyramidal cone with friction (.cpp)
  double impedance = 0.0;       // d_max (solimp[1], clamped to [1e-4, 0.9999])
  double impedance_at_rest = 0.0;
  double omega = 0.0, zeta = 0.0;
  double omega_dt = 0.0;
  double euler_limit = 0.0;  // MuJoCo Euler and implicit (contacts explicit): semi-implicit Euler
  double rk4_limit = 0.0;
  double static_penetration = 0.0;  // m, per contact at rest
  // --slope θ: the speed the contact creeps at under friction (inspect.hpp's
  // formula with this mapping's K, B, solimp, impratio and cone), NaN with
  // creep_note saying why when there is no such number.
  double creep = NAN;
  std::string creep_note;
  double nominal_penetration = 0.0;        // f/k, m
  std::string default_snippet;             // <option> + <default class>
  std::string pair_snippet;                // <option> + <contact><pair>
  std::vector<ClassCaveat> class_caveats;  // where default_snippet does not hold (--model)
};

// solref --model: one <pair> per geom pair among the body's contacts at
// rest, with the mapping's solref and solimp and every other field as
// MuJoCo resolved it for that geom pair (condim, friction, margin, gap), or
// --mu's condim and friction. A pair takes nothing from its geoms (MuJoCo's
// pair defaults are condim 3, friction 1 1 0.005 0.0001 0.0001, margin and
// gap 0), and MuJoCo then skips the geom pair in its own collision pass, so
// the pair changes the contact's solref and solimp and nothing else, and only
// for those two geoms (not the body's other contacts).
struct RestPair {
  GeomRef geom1, geom2;
  int condim = 1;
  std::array<double, 5> friction{};
  double margin = 0.0, gap = 0.0;
  bool explicit_pair = false;  // the model has a <pair> for them already: edit it
};
std::vector<RestPair> rest_pairs(const SolrefInput& input, const MappingOutcome& outcome);
// The name a pair gives an unnamed geom (--apply names it so in the file).
std::string pair_name(const GeomRef& geom);
// A pair's attributes but the geoms' names: condim, friction, margin, gap,
// solref, solimp.
std::string pair_attributes(const RestPair& pair, const SolverSettings& settings);

// solref --apply: the model with the recommended mapping written into it
// (mujoco/solref_apply.hpp), settled again: the body's contacts there.
struct AppliedContact : SettledContact {
  double predicted = 0.0;  // the mapping's rest depth at its load, m
  bool mapped = false;     // a geom pair --apply gave the mapping (else its own law: no prediction)
};

struct Applied {
  std::string path;
  std::string mapping;
  int pairs = 0;  // the <pair>s written or edited
  double settled = 0.0;
  bool at_rest = false;
  std::vector<AppliedContact> contacts;
};

struct SolrefReport {
  SolrefInput input;
  double inv_mass = 0.0;    // A = 1/m + lever²/I (hinge: lever²/(I + m·pivot²))
  double inv_weight = 0.0;  // Â
  double load = 0.0;  // f = m·g/contacts, N per contact (hinge: m·g·pivot/(lever·contacts))
  std::vector<MappingOutcome> mappings;  // the recommended one first
  std::string recommendation;            // the mapping to use and why ("" when none is fit)
  // No mapping fit: the largest Δt (at this k) and the largest k (at this
  // Δt) at which one is, as "Try --dt … or --k …" (fit_hint); else "".
  std::string fit_hint;
  std::optional<Applied> applied;  // --apply
  // --apply that was not carried out (no mapping is fit), with why: the
  // report is still printed, then this is the command's error.
  std::string apply_refused;
};

// The report's fit_hint: bisection over Δt and over k of solref_report's
// recommendation (ω·Δt grows with both; the physical ω with k). "" when a
// mapping is fit or none is at any Δt or k down to a millionth.
std::string fit_hint(const SolrefReport& report);

// The mappings `contact2d solref` offers for a user's own model, in the
// order it prints them: the recommended one first. Compensated is not
// offered (solref_report says why under --mapping all).
std::vector<Mapping> offered_mappings();
// Why compensated is not offered for a user's own model (one line).
std::string compensated_not_offered();

// Throws InputError naming the option for a value outside its range.
void validate(const SolrefInput& input);

SolrefReport solref_report(const SolrefInput& input, const std::vector<Mapping>& mappings);

// MuJoCo 2.2's impedance d at a constraint distance `pos` (margin 0), from
// the solimp function as MuJoCo's documentation defines it, with MuJoCo's
// clamps (d in [1e-4, 0.9999]).
double mujoco_impedance(const std::array<double, 5>& solimp, double pos);

// p solving p·K·d(p)² = f·Â·(1 − d(p)) (see the header comment).
double static_penetration(const std::array<double, 5>& solimp, double K, double inv_weight,
                          double force);

// A body of a MuJoCo model file: mass, body_invweight0 (translational), its
// joints, its friction, and the contacts MuJoCo makes for it at rest.
struct ModelBody {
  std::string version;    // the MuJoCo that compiled and settled the model
  double timestep = 0.0;  // the model's <option timestep>, s
  double mass = 0.0;
  double inv_weight = 0.0;
  std::optional<Joint> joint;  // none: a joint set other than the four
  std::string joints;          // the body's joints as MuJoCo types, e.g. "slide, slide, hinge"
  // The friction of the body's most loaded contact at rest as MuJoCo mixed
  // it (else its first colliding geom's), and the model's cone.
  UserFriction friction;
  int rest_contacts = 0;  // MuJoCo contacts of the body after settling
  std::vector<SettledContact> contacts;
  double tangential_inv_mass =
      0.0;  // its contacts' friction rows slipping together (model_state.hpp)
  double settle_seconds = 0.0;
  double rest_speed = 0.0;   // largest |qvel| of the model at the end of the settling
  bool at_rest = false;      // model_state.hpp's criterion
  std::string load_warning;  // MuJoCo's warning while loading, if any
};
// How long solref lets a user's model settle (mj_step from qpos0, or the
// keyframe) by default before it reads the body's contacts.
constexpr double kSettleSeconds = 3.0;
// The body `body` of the state a version read from `path`. Throws
// InputError "--body NAME: ..." when the model has no such body (or it is
// the world), or its mass or body_invweight0 is not positive.
ModelBody read_model_body(const ModelState& state, const std::string& path,
                          const std::string& body);

std::string format_report_text(const SolrefReport& report);
std::string format_report_json(const SolrefReport& report);

}  // namespace contact2d::mujoco
