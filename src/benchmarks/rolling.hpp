// Closed forms of a round body rolling on a flat floor (docs/closed-forms.md,
// sections 4, 5 and 5b).
//
// A round body of radius R (m), mass m and moment of inertia I = κ·m·R²
// (κ = ½ for a uniform disc, 1 for a ring) on the floor, x to the right,
// ω counter-clockwise (rad/s). The floor's friction F acts at the contact
// point R below the centre, where the slip (the contact point's velocity) is
//   u = v + ω·R,
// so with the rolling-resistance torque τ_r (N·m):
//   m·dv/dt = F,   I·dω/dt = R·F + τ_r,
//   du/dt = (1 + 1/κ)·F/m + R·τ_r/I.
// Rolling forward (v > 0, ω = −v/R) means u = 0; backspin is ω > 0. The
// friction laws are those of benchmarks/sliding.hpp: Coulomb F = −μ·Fn·sgn(u)
// and its regularisation F = −μ·Fn·tanh(α·u), Fn = m·g while the body rests
// on the floor; rolling resistance τ_r = −μ_roll·Fn·tanh(α·R·ω) (μ_roll in m).
#pragma once

namespace contact2d::benchmarks {

// κ = I/(m·R²) of a uniform disc (the scenes' circle) and of a solid sphere.
constexpr double kDiscInertiaRatio = 0.5;
constexpr double kSphereInertiaRatio = 0.4;

// Rolling without slip under rolling resistance (ω < 0): m·a = F,
// I·α_ω = R·F + μ_roll·m·g, a = −α_ω·R eliminate F:
//   |a| = μ_roll·g/(R·(1 + κ))   (m/s²; the disc: μ_roll·g/(1.5·R)).
double rolling_resistance_deceleration(double mu_roll, double gravity, double radius, double kappa);

// The distance to rest of that roll, launched rolling at v0 under the tanh
// laws, to first order in the slip and in 1/α:
//   s = v0²/(2a) + κ/(1 + κ)·v_s·v0/a + π²/(12α²a),   v_s = atanh(a/(μg))/α.
// v_s is the slip the tanh law needs to carry the force m·a. It builds up in
// the first moments: v + κ·(−ω·R) does not depend on F, so the slip raises v
// by κ·v_s/(1 + κ) and lowers the rim speed −ω·R by v_s/(1 + κ); the rim then
// stops after (v0 − v_s/(1 + κ))/a while v runs v_s ahead. The last term is
// the regularised stop of the rolling torque (benchmarks/sliding.hpp).
// Remainder O(v_s², 1/α²). The terms one by one: distance() = roll + slip + tanh.
struct RollingStop {
  double roll = 0.0;  // v0²/(2a), the Coulomb laws' distance
  double slip = 0.0;  // κ/(1 + κ)·v_s·v0/a
  double tanh = 0.0;  // π²/(12α²a)
  double distance() const { return roll + slip + tanh; }
};
RollingStop rolling_distance_terms(double v0, double deceleration, double mu, double gravity,
                                   double alpha, double kappa);
double rolling_distance(double v0, double deceleration, double mu, double gravity, double alpha,
                        double kappa);
// Under the Coulomb laws (α = ∞) the roll stops after
//   s = v0²/(2a)   (m).
double rolling_resistance_distance(double v0, double deceleration);

// Sliding into rolling (the bowling ball), μ_roll = 0. Friction changes
// v and ω·R by the same impulse, so L = κ·R·ω − v (I·ω − m·R·v over m·R) is
// conserved, and once the slip is gone (ω·R = −v):
//   v_final = (v0 − κ·R·ω0)/(1 + κ)   (no spin: v0/(1 + κ) = 2v0/3 for the disc).
// rim0 = R·ω0 (m/s).
double slide_to_roll_final_speed(double v0, double rim0, double kappa);
// Along the way, with the slip at u (from u0 = v0 + R·ω0): a slip change Δu
// is shared as Δv = κ/(1 + κ)·Δu, Δ(R·ω) = Δu/(1 + κ), so
//   v = v0 − (u0 − u)·κ/(1 + κ),   ω = ω0 − (u0 − u)/((1 + κ)·R).
double slide_to_roll_speed(double v0, double u0, double u, double kappa);
double slide_to_roll_spin(double omega0, double u0, double u, double radius, double kappa);
// The slip's own deceleration under Coulomb's law: du/dt = (1 + 1/κ)·F/m, so
//   a_u = (1 + 1/κ)·μ·g   (3μg for the disc),
// and under tanh du/dt = −a_u·tanh(α·u): benchmarks/sliding.hpp's
// tanh_sliding_speed and tanh_sliding_time with deceleration a_u (Coulomb's
// time to rolling u0/a_u).
double slide_to_roll_slip_deceleration(double mu, double gravity, double kappa);
// The distance the centre runs beyond v_final·t, for t ≫ t*: x(t) − x0 =
// v_final·t + κ/(1 + κ)·∫₀^∞ u dt, and ∫₀^∞ u dt = ∫₀^u0 u/(a_u·tanh(αu)) du
// = (u0²/2 + π²/(12α²))/a_u (sliding.hpp), so
//   x(t) − x0 − v_final·t → (u0²/2 + π²/(12α²))·κ/((1 + κ)·a_u)
// (for the disc (u0²/2 + π²/(12α²))/(9μg)); the remainder is
// −κ/(1 + κ)·u(t)/(a_u·α) once α·u ≪ 1. α = ∞: Coulomb, u0²·κ/(2(1 + κ)·a_u).
double slide_to_roll_distance_offset(double u0, double mu, double gravity, double alpha,
                                     double kappa);

// A round body hitting the floor with the normal impulse P (N·s, e.g.
// benchmarks/impact.hpp's m·(1 + e)·v_in) and slip u = v_x + R·ω > 0, under
// Coulomb friction: the friction impulse is μ·P at most and the slip's
// effective mass is m/(1 + 1/κ) (m/3 for the disc). It slides through the
// impact when u > (1 + 1/κ)·μ·P/m:
//   v_x′ = v_x − μ·P/m,            R·ω′ = R·ω − μ·P/(κ·m);
// otherwise the slip stops during the impact (u′ = 0) and it rolls out:
//   v_x′ = v_x − u·κ/(1 + κ),      R·ω′ = R·ω − u/(1 + κ).
// The disc: −μP/m and −2μP/m sliding, −u/3 and −2u/3 rolling out.
struct SpinImpact {
  double vx = 0.0;   // v_x′ (m/s)
  double rim = 0.0;  // R·ω′ (m/s)
  bool rolls = false;
};
SpinImpact spin_impact(double vx, double rim, double normal_impulse, double mass, double mu,
                       double kappa);

}  // namespace contact2d::benchmarks
