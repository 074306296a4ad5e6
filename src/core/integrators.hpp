// Time stepping of (q, v) with a = M⁻¹·F(q, v) (docs/physics.md).
//
//   explicit Euler       v' = v + a(q, v)·Δt,    q' = q + v·Δt
//   semi-implicit Euler  v' = v + a(q, v)·Δt,    q' = q + v'·Δt
//   implicit Euler       v' = v + a(q', v')·Δt,  q' = q + v'·Δt
//   RK4                  classical fourth order on (q, v)
//
// Implicit Euler solves G(v') = v' − v − Δt·a(q + Δt·v', v') = 0 by Newton's
// method. The Jacobian ∂G/∂v' = I − Δt·(Δt·∂a/∂q + ∂a/∂v) includes the contact
// forces' derivatives, analytic on the branch of the piecewise-smooth law the
// iterate is on (acceleration_jacobian, core/dynamics.hpp; obstacle contacts'
// ∂a/∂q by forward differences). Each Newton step is
// backtracked until |G|∞ strictly decreases; when no fraction down to 1/1024
// decreases it, the iteration has stalled and counts as not converged.
// Converged when the full Newton step and the residual are both small:
// |δv'|∞ ≤ 1e-10·(1 + |v'|∞) and |G(v')|∞ ≤ 1e-10·(1 + |v'|∞) — far below
// the method's O(Δt) error.
// Fallback: after 30 iterations without convergence the step is split into
// two half steps, recursively up to 6 levels (Δt/64); if that still fails the
// step reports StepStatus::NewtonFailed and the run stops as diverged.
#pragma once

#include <optional>
#include <string_view>

#include "core/dynamics.hpp"

namespace contact2d {

enum class Integrator { ExplicitEuler, SemiImplicitEuler, ImplicitEuler, RK4 };

constexpr Integrator kAllIntegrators[] = {Integrator::ExplicitEuler, Integrator::SemiImplicitEuler,
                                          Integrator::ImplicitEuler, Integrator::RK4};

std::string_view integrator_name(Integrator integrator);   // "explicit_euler", …
std::string_view integrator_title(Integrator integrator);  // "explicit Euler", …
std::optional<Integrator> parse_integrator(std::string_view name);

// What a step reports. NonFinite is for engines that detect bad numbers
// themselves (MuJoCo); the reference leaves that to the divergence monitor.
enum class StepStatus { Ok, NewtonFailed, NonFinite };

// The contacts an integrator works with: `contacts` holds those of the
// state being stepped — valid on entry, refreshed for the new state on exit,
// so the next step and the divergence monitor read them instead of finding
// them again — and `scratch` those of intermediate configurations (RK4's
// stages, Newton's trial states). Sized once for the model: no allocation
// in a step.
struct StepWorkspace {
  StepWorkspace() = default;
  explicit StepWorkspace(const Model& model) : contacts(model), scratch(model), probe(model) {}
  ContactSet contacts;
  ContactSet scratch;
  ContactSet probe;  // Newton's finite differences for obstacle contacts
  // Implicit Euler: a(q', v') at the state its last accepted solve ended in,
  // with that state, the model and its applied force — the next step's
  // predictor needs exactly this value, so it is reused (bit for bit the
  // same) instead of evaluated again when all of them are unchanged.
  struct Accepted {
    Vec3 q = Vec3::Zero(), v = Vec3::Zero(), applied = Vec3::Zero(), a = Vec3::Zero();
    const Model* model = nullptr;  // nullptr: nothing accepted yet
  } accepted;
};

// Implicit Euler's Newton solve for one step of Δt, without splitting:
// true and the new state when it converged; false (state untouched) when it
// did not. ws.contacts must be the contacts at state.q; on success they are
// left stale and ws.scratch holds those of the new state (step() swaps them
// in). Exposed for its tests.
bool implicit_euler_newton(const Model& model, double dt, State& state, StepWorkspace& ws);

// Newton's linear algebra (core/integrators.cpp), exposed for its tests.
// a·x = b for a 3×3 a: Gaussian elimination with partial pivoting, written out.
Vec3 solve3(Eigen::Matrix3d a, Vec3 b);
// An upper bound on |(I − E)⁻¹·g|∞: |g|∞/(1 − ‖E‖∞) when ‖E‖∞ ≤ 1/2, else +∞.
double newton_step_bound(const Eigen::Matrix3d& e, const Vec3& g);

// One step of Δt from `state`. On entry ws.contacts must be the contacts at
// state.q (find_contacts); on exit they are those of the new state.
StepStatus step(const Model& model, Integrator integrator, double dt, State& state,
                StepWorkspace& ws);

// Largest stable ω·Δt of the integrator on the damped linear oscillator
// x'' + 2ζω·x' + ω²·x = 0 (the contact in its linear regime). Infinity for
// implicit Euler. Explicit Euler: ω·Δt < 2ζ for ζ ≤ 1; semi-implicit Euler:
// ω·Δt < min(1/ζ, 2(√(1+ζ²) − ζ)) (Jury criterion of its 2×2 update matrix);
// RK4 from its stability polynomial, found numerically (2√2 at ζ = 0).
double stability_limit(Integrator integrator, double zeta);

}  // namespace contact2d
