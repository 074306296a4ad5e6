// Divergence rule: when a run stops being physics.
//
// Contact, damping and friction only remove energy, and gravity is
// conservative, so without applied forces the mechanical energy E (kinetic +
// gravitational + contact-spring, see energy()) never rises above E(0). The
// energy a run can ever have available is
//   E_avail = E(0)_kinetic + m·g·(h0 + L) + E(0)_spring
// with h0 the height of the lowest contact point above the ground (≥ 0) and L
// the body's extent (turning over can lower the COM by at most L).
// A step is divergent when
//   1. any component of the state is not finite, or
//   2. E(t) − E(0) > E_avail + |W_applied|: the run gained more energy than the
//      whole system ever held, or
//   3. the deepest penetration exceeds 2·d_max, where d_max solves
//      ½·k·d² = E_avail + |W_applied| + m·g·d (all available energy, the
//      applied forces' work and gravity's work in one spring), i.e.
//      d_max = (m·g + √((m·g)² + 2·k·(E_avail + |W_applied|)))/k, or
//   4. implicit Euler's Newton iteration failed even after step splitting.
// Rules 2 and 3 leave a factor of two or more above anything physical, so a
// stable run never trips them and an unstable one does within a few steps.
#pragma once

#include <limits>
#include <optional>
#include <string>

#include "core/contacts.hpp"
#include "core/scene.hpp"

namespace contact2d {

enum class DivergenceKind { NonFinite, EnergyGain, Penetration, NewtonFailed };

struct Divergence {
  DivergenceKind kind = DivergenceKind::NonFinite;
  double time = 0.0;
  double value = 0.0;  // energy gain (J) or penetration (m) that tripped the rule
  double limit = 0.0;  // the bound it exceeded
};

// Linear-regime numbers of the contact at the scene's parameters.
struct ContactStiffness {
  double m_eff = 0.0;  // smallest effective mass of one contact point, kg
  double omega = 0.0;  // √(k/m_eff), rad/s
  double zeta = 0.0;   // c/(2√(k·m_eff))
};
ContactStiffness contact_stiffness(const Model& model);

class DivergenceMonitor {
 public:
  // `contacts`: the contact stage's output at initial.q (core/contacts.hpp).
  DivergenceMonitor(const Model& model, const State& initial, const ContactSet& contacts);
  // Checks a state after a step ending at time t, with its contacts;
  // applied_work is the work done by Model::applied so far (0 without a player).
  // When `energy` is given it receives E(s) (computed for the rule anyway).
  std::optional<Divergence> check(const State& s, const ContactSet& contacts, double t,
                                  double applied_work = 0.0, double* energy = nullptr) const;
  double available_energy() const { return available_; }

 private:
  double depth_limit(double energy) const;  // 2·d_max for that much energy
  const Model* model_;
  double initial_energy_ = 0.0;
  double available_ = 0.0;
  double max_depth_ = 0.0;
};

// An engine's contact in its linear regime at its step (Stepper::stability()):
// the scheme that integrates the contact force, ω·Δt, and that scheme's
// stability limit on ω·Δt (core/integrators.hpp, stability_limit) at the
// contact's damping.
struct StepStability {
  Integrator scheme = Integrator::SemiImplicitEuler;
  double omega_dt = 0.0;
  double limit = 0.0;
  bool beyond() const { return omega_dt > limit; }
};

// The reference's: ω = √(k_max/m_eff) and ζ of contact_stiffness(). The
// compression law damps only while the point moves in, so its rebound is an
// undamped oscillator and the limit is the smaller of those at ζ and at 0 —
// except for explicit Euler, which has no stable step on an undamped
// oscillator: its rebound gain is an allowance of its own (the growth term
// below), and its limit is the one at ζ.
StepStability reference_stability(const Model& model, Integrator integrator, double dt);

// The tanh friction law (contact.hpp) linearised at rest: at a slip speed
// well below 1/α, with the body's weight m·g on its contacts, it is a
// damper on the slip speed of rate
//   λ = μ·g·α·m·(1/m + ℓ²/I)
// (ℓ: the largest lever of a contact point, body_extent; 0 for a point
// mass: a disc's slip v + ω·R gives 3·μ·g·α), and with rolling resistance
// the rolling torque −μ_roll·Fn·tanh(α·R·ω) adds a damper on ω of rate
//   λ_roll = μ_roll·m·g·α·R/I.
// A scheme integrates v' = −λ·v stably only for λ·Δt below its limit on the
// negative real axis: 2 for explicit and semi-implicit Euler (their
// velocity update is explicit), 2.785 for RK4 (|1 − z + z²/2 − z³/6 +
// z⁴/24| = 1), none for implicit Euler. Beyond it the slip overshoots zero
// on every step: tanh's saturation bounds it, so the run stays finite and
// loses energy, but at rest the body holds a two-step cycle in place of
// static friction, and a disc creeps (its slip and rolling cycles do not
// cancel: 1 mm/s at α = 1e5 s/m, Δt = 1e-4 s). Rate 0 for the cone laws and
// without gravity.
struct FrictionStep {
  double rate_dt = 0.0;  // (λ + λ_roll)·Δt
  double limit = std::numeric_limits<double>::infinity();
  // The fraction of the limit where the cycle begins: 1 on one contact; on
  // several, 0.8: the contacts' compliance couples the slip with the body's
  // pitch, which λ leaves out (the box of validation/scenes/box.toml, on
  // its two bottom corners, cycles from 0.85 of it: Δt 2.2e-3 s against
  // the 2.55e-3 s of λ; 2.15e-3 s comes to rest).
  double onset = 1.0;
  bool beyond() const { return rate_dt > onset * limit; }
};
FrictionStep friction_step(const Model& model, Integrator integrator, double dt);
// The same at the ground contacts `contacts` (a state the body rests in):
// each contact's own load k·d and lever r_y in place of the weight and the
// largest lever, λ = Σ μ·α·k·d·(1/m + r_y²/I) (+ μ_roll·α·k·d·R/I) — a
// box resting on a face has lever h/2, not its half-diagonal. Without a
// loaded ground contact, the bound above.
FrictionStep friction_step(const Model& model, Integrator integrator, double dt,
                           const ContactSet& contacts);

// The energy balance of a run without applied forces. A passive system's
// mechanical energy never rises: E(t₂) ≤ E(t₁) for t₂ > t₁. An integrator
// makes it oscillate: semi-implicit Euler on the contact oscillator of
// frequency ω keeps |ΔE| ≤ (ω·Δt/2)/(1 − ω·Δt/2) of the energy in play
// (tests/core/test_energy.cpp checks that bound), so its largest rise above
// an earlier minimum is twice that; a contact entered or left inside a step
// costs O((ω·Δt)²) of it. Explicit Euler multiplies the oscillator's energy
// by exactly 1 + (ω·Δt)² on every step, which over one undamped contact
// (π/ω long, π/(ω·Δt) steps) compounds to
//   growth = (1 + (ω·Δt)²)^(π/(ω·Δt)) − 1 ≈ π·ω·Δt
// (0 for the other integrators): what one bounce gains; a rise that keeps
// growing over several bounces or a long rest exceeds it. The tolerance on
// the rise is therefore
//   rise_tolerance = E_avail·min(1, 2·(ω·Δt/2)/(1 − ω·Δt/2) + growth) + 1e-9·E_avail
// (E_avail: the monitor's available energy; the 1e-9 covers rounding) below
// the scheme's stability limit, the rounding term alone beyond it, plus, for
// explicit Euler, its own gain in free flight (free_flight_gain()). A rise
// beyond it is not physics: the command line fails the run (exit 3) unless
// --allow-nonphysical keeps it with a warning; beyond E_avail itself the
// divergence rule stops the run.
struct EnergyBalance {
  double initial = 0.0;           // E(0), J
  double final = 0.0;             // E at the last step, J
  double max_rise = 0.0;          // largest E(t) − min_{s≤t} E(s), J
  double time_of_max_rise = 0.0;  // s
  double tolerance = 0.0;         // rise_tolerance above, J
  double free_flight_gain = 0.0;  // the part of it that is explicit Euler's free flight, J
  bool rise_in_contact = false;   // a contact was active during the largest rise
  StepStability stability;        // the engine's contact at its step
  bool exceeded() const { return max_rise > tolerance; }
};

// The tolerance of the rise (the oscillation in contact; without the
// free-flight term). Beyond the limit the oscillation bound does not hold:
// the contact's linear update has an eigenvalue of modulus above one, so the
// energy in contact grows every step and no rise is the integrator's
// bounded error — the tolerance is the rounding term (1e-9·E_avail) and,
// for explicit Euler, one contact's growth (below; it has no stable step on
// an undamped rebound, so that growth is its every contact's, derived, and
// a rise beyond it is not). A run that gains more there is not physics.
double energy_rise_tolerance(const StepStability& stability, double available_energy);

// An integrator's own energy gain in free flight under gravity, over `steps`
// steps of dt (all of them in flight, at most). Explicit Euler moves the body
// by v·Δt while gravity changes v by −g·Δt, so its local error −½·g·Δt² in
// height raises E = ½·m·v² + m·g·y by exactly ½·m·g²·Δt² on every step
// (rotation and horizontal motion are exact in flight). Semi-implicit and
// implicit Euler lose that much instead, and RK4 is exact for a constant
// acceleration: 0 for them.
double free_flight_gain(const Model& model, Integrator integrator, double dt, long long steps);

// The body's own size D, m: twice the largest distance of a contact point from
// the COM (a box's diagonal, a circle's diameter, a point mass's 2·half_height).
double body_size(const RigidBody& body);

// Below the divergence rule, where a run ended: a contact point deeper than
// the body's size D puts every contact point below the surface (no two are
// more than D apart), and the COM more than D below the ground (y < −D) is
// further still: a body that ends inside the surface rather than on it is not
// physics, whatever its energy (a point mass of no size has no such bound).
// Only the end counts: an impact on a soft contact may pass through such a
// depth on the way back up, losing energy as the penalty law says.
struct DepthRecord {
  double size = 0.0;   // D, m
  double time = 0.0;   // of the last step, s
  double depth = 0.0;  // deepest penetration of any contact point then, m
  double y = 0.0;      // height of the COM then, m
  bool too_deep() const { return size > 0.0 && depth > size; }
  bool below_ground() const { return size > 0.0 && y < -size; }
};

// Why a finished run is not physics, as one line (the depth rules, then the
// energy rise, joined by "; "); empty when it is physics.
std::string describe_nonphysical(const EnergyBalance& balance, const DepthRecord& depth,
                                 double available_energy, const Scene& scene);

// One line for a rise beyond the tolerance: size in J and % of E_avail, time,
// and the likely cause (the integrator and ω·Δt).
std::string describe_energy_rise(const EnergyBalance& balance, double available_energy,
                                 const Scene& scene);

// What tripped the rule, as a clause: "the state became non-finite", "the
// energy rose by … J, more than …", ….
std::string divergence_event(const Divergence& d);

// One-paragraph diagnosis: what happened, when, the likely cause in terms of
// ω·Δt against the integrator's limit (and friction stiffness μ·g·α·Δt), and
// what to try.
std::string describe(const Divergence& d, const Scene& scene);

}  // namespace contact2d
