// A converged reference trajectory: Dormand–Prince 5(4) with error control,
// dense output and event location at every point where the right-hand side
// is not smooth.
//
// Why events. The contact force is only piecewise smooth in the state:
//   * a point starting or ending penetration (c_y = 0): with damping the force
//     even jumps at entry, by c·|v_c,y|;
//   * the compression-only damper switching on or off (v_c,y = 0);
//   * the Kelvin–Voigt force reaching zero (k·d − c·v_c,y = 0).
// A Runge–Kutta step across such a point loses its order (its error expansion
// assumes derivatives that do not exist) and its embedded error estimate stops
// meaning anything. So the integrator keeps a *mode* — for every contact point
// "in contact" and "damper/force active" — and evaluates the force on the
// smooth branch of that mode, extended past the switching surface (the
// spring pulls a little, the damper pulls a little: polynomials in the
// state). Every switching function is watched along each accepted step; at a
// sign change the crossing is located on the dense output to rounding level,
// the step is redone exactly up to the crossing, the mode flips and the
// integration restarts there. Between events the right-hand side is analytic
// (tanh friction and tanh rolling resistance are smooth), so the method keeps
// its fifth order and its error estimate through impacts.
//
// Grazing: a switching function that stays on one side at both ends of a step
// but has an interior extremum (a corner swinging down and up again within
// one step) is caught by locating the extremum from the end derivatives and
// checking the sign there.
//
// All switching functions have mode-independent time derivatives on their
// surfaces (the force is continuous where the damper or the Kelvin–Voigt
// force switches, and the velocity is continuous at entry), so there are no
// sliding modes: a crossing is transversal or a tangency, and the new mode is
// the side the function crosses to.
//
// Chatter. Those derivatives being equal, a function's rate at a point on
// its surface is the true solution's, and says which side it leaves to.
// Flipping at the start of a step (a function already on its wrong side
// there) is right when that rate points away from the current mode's side.
// But at a rounding-level distance from the surface it can happen that both
// modes see themselves past it: e.g. a point leaving the ground whose step,
// redone up to the located exit, stops one ulp short of the surface while
// the next step holds the whole following flight; in the free mode the
// contact function is then "wrong" at both ends of the step, in the contact
// mode it is "wrong" (by an ulp) at the start and the exit is found again
// within an ulp. After kMaxZeroLengthFlips such zero-length flips the
// function is no longer flipped at the start, and — rather than accepting
// the step and integrating the point, e.g., 2.4 mm inside the ground with no
// force — it is resolved:
//   * rate into the current mode's side: the mode is right (the start value
//     is rounding at the surface); the function comes back within the step,
//     after an interior maximum: that crossing is located like any other;
//   * otherwise the step is rejected and halved, and the search repeats on
//     the shorter step; if the step underflows first, the integration fails
//     with a message naming the time, the contact point and the function.
// This is no Filippov sliding mode being cut short: sliding needs the
// vector fields of the two modes to point into the surface from both sides,
// i.e. opposite normal rates on it, and the rates here are equal on the
// surface. Equal and zero (a tangency, e.g. a body at rest with v_c,y = 0
// exactly on the damper's surface) is the only case where the modes' next
// orders can disagree at rounding level; where that leaves the function on
// the wrong side of both modes on every step, the run is reported, never
// silently integrated in an inconsistent mode.
//
// Runs that never reach the flip limit are unaffected: the resolution acts
// only at that limit.
//
// The right-hand side reproduces dynamics.cpp's acceleration() branch by
// branch (ground contact, sliding friction, rolling resistance, the model's
// constant applied load); tests/reference checks that the two agree to rounding
// on random states, so a change in the core's force law shows up there.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "core/dynamics.hpp"
#include "core/scene.hpp"

namespace contact2d {

using Vec6 = Eigen::Matrix<double, 6, 1>;

struct DenseOptions {
  double rtol = 1e-12;               // relative tolerance on every component
  double atol = 1e-12;               // absolute tolerance (m, rad, m/s, rad/s alike)
  double h_max = 0.0;                // largest step; 0 = duration / 100
  long long max_steps = 20'000'000;  // accepted + rejected; beyond: failed
};

struct DenseStats {
  long long accepted = 0;
  long long rejected = 0;
  long long evaluations = 0;  // right-hand side evaluations
  long long events = 0;       // mode switches
};

// The piecewise polynomial trajectory; state(t) is Dormand–Prince's fourth-
// order continuous extension on the step containing t.
class DenseTrajectory {
 public:
  double t_end() const { return t_end_; }
  bool ok() const { return failure_.empty(); }
  const std::string& failure() const { return failure_; }  // empty when ok
  const DenseStats& stats() const { return stats_; }
  const std::vector<double>& event_times() const { return event_times_; }

  // State at t ∈ [0, t_end] (clamped). O(log n).
  State at(double t) const;

 private:
  friend DenseTrajectory integrate_dense(const Model&, const State&, double, const DenseOptions&);
  struct Segment {
    double t0 = 0.0;
    double h = 0.0;
    Vec6 r[5];
  };
  std::vector<Segment> segments_;
  std::vector<double> event_times_;
  DenseStats stats_;
  double t_end_ = 0.0;
  std::string failure_;
};

// Integrates the model from `initial` over [0, duration]. Never throws; a run
// that exceeds max_steps, underflows its step or leaves the finite numbers is
// returned with ok() == false and the trajectory up to that point. A model
// with static obstacles (core/obstacles.hpp) is refused the same way: only
// the ground's switching functions are located.
DenseTrajectory integrate_dense(const Model& model, const State& initial, double duration,
                                const DenseOptions& options = {});

// The scene's converged reference at tolerance tol (rtol = atol = tol).
DenseTrajectory converged_reference(const Scene& scene, double tol = 1e-12);

// Frozen-mode right-hand side, exposed for the consistency test: the mode of
// each contact point is taken from the state itself (c_y < 0; damper on when
// v_c,y < 0, Kelvin–Voigt active when k·d − c·v_c,y > 0), which must equal
// acceleration(model, q, v).
Vec3 dense_reference_acceleration(const Model& model, const Vec3& q, const Vec3& v);

}  // namespace contact2d
