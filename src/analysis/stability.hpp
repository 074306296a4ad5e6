// Largest stable Δt per contact stiffness k and integrator, found by
// bisection, next to the linear theory.
//
// Stable means the run of the scene (its initial state and duration, with k
// and possibly c replaced) passes the core's divergence rule at every step
// (core/divergence.hpp): the state stays finite, the energy never rises above
// what the system ever held, no point sinks deeper than twice what all that
// energy could push it, and implicit Euler's Newton iteration converges. An
// engine other than "ref" is held to the same rule (its adapter checks it
// every step) and any runtime warning it raises counts as a failure.
//
// Theory: in its linear regime a contact point is the oscillator
// x'' + 2ζω·x' + ω²·x = 0 with ω = √(k/m_eff), ζ = c/(2√(k·m_eff)) and m_eff
// the smallest effective mass of a point (core contact_stiffness()); each
// method is stable while ω·Δt stays below core stability_limit(method, ζ).
//
// Search: a first probe just below the theoretical Δt (or at dt_max for an
// unconditionally stable method), then steps of ×4 up or down until the
// answer changes, then bisection on log Δt until the bracket is within
// `precision`. This assumes that stability is monotone in Δt, which holds
// for the linear oscillator; a nonlinear run could in principle be stable
// again at some larger Δt that the search never visits.
#pragma once

#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "analysis/engine.hpp"

namespace contact2d::analysis {

struct StabilityConfig {
  std::vector<double> ks{1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};
  std::vector<Integrator> integrators{std::begin(kAllIntegrators), std::end(kAllIntegrators)};
  std::vector<std::string> engines{"ref"};
  std::optional<double> zeta;           // c = 2ζ√(k·m_eff) at every k; none: the scene's c
  double dt_max = 1e-2;                 // search range, s
  long long max_steps = 2'000'000;      // per probe of "ref": dt_min = duration / max_steps
  long long max_steps_other = 200'000;  // per probe of any other engine (≈50× dearer per step)
  double precision = 0.02;              // stop when dt_unstable / dt_stable ≤ 1 + precision
  unsigned threads = 0;                 // 0: one per core
  std::function<void(size_t done, size_t total, const std::string& what)> progress;
};

enum class StabilityVerdict {
  Bracketed,      // dt_stable < dt_unstable within `precision`
  StableAtMax,    // stable up to dt_max
  UnstableAtMin,  // unstable down to dt_min
  Failed,         // the engine could not run the scene
};

struct StabilityRow {
  std::string engine;
  Integrator integrator = Integrator::SemiImplicitEuler;
  double k = 0.0, c = 0.0;
  double m_eff = 0.0, omega = 0.0, zeta = 0.0;
  double theory = 0.0;              // largest stable ω·Δt of the linear oscillator
  double dt_stable = std::nan("");  // largest Δt found stable
  double dt_unstable = INFINITY;    // smallest Δt found unstable
  double dt_min = 0.0;
  StabilityVerdict verdict = StabilityVerdict::Failed;
  std::string failure;  // how the smallest unstable probe failed
  int probes = 0;
  // Deepest penetration of the run at dt_stable (over every step for an
  // engine other than "ref", over the output samples for "ref"), of a run at
  // a small step (ω·Δt = 0.2, where nothing is softened; only when MuJoCo's
  // refsafe was active at dt_stable), and of the converged reference. A contact that MuJoCo's
  // refsafe softens at large steps sinks deeper there than at the small step: that ratio is the
  // signature of "stable because the model changed".
  double penetration = std::nan("");
  double penetration_small_step = std::nan("");
  double reference_penetration = std::nan("");
  // MuJoCo's refsafe raised the timeconst of the run at dt_stable.
  bool refsafe_at_stable = false;
  std::string note;
};

struct StabilityResult {
  std::string scene_name;
  double duration = 0.0;
  double dt_max = 0.0;
  double precision = 0.0;
  std::optional<double> zeta;
  unsigned threads = 1;
  std::vector<StabilityRow> rows;
};

// Throws std::invalid_argument for an empty or invalid list.
StabilityResult run_stability(const Scene& scene, const StabilityConfig& config,
                              const EngineRunner& runner = registry_runner());

// The scene with contact stiffness k (and c from ζ when given).
Scene scene_with_stiffness(const Scene& scene, double k, std::optional<double> zeta);

const char* verdict_name(StabilityVerdict verdict);

}  // namespace contact2d::analysis
