// One interface for every engine that advances the planar body: the
// reference solver (one per integrator, here) and MuJoCo
// (mujoco/stepper.hpp). The run loop (core/run.hpp) and the game drive
// engines only through it, so "run a scene" means the same thing for all of
// them; the benchmark steps the reference through it and times bare mj_step
// for MuJoCo's own cost (bench/bench_step.cpp says why).
//
// A stepper starts at the scene's initial state. After every step it holds
// the new state and the contacts of that state found by the reference's
// contact stage (core/contacts.hpp) on the scene's model — the divergence
// monitor reads those, whatever the engine.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/divergence.hpp"
#include "core/integrators.hpp"
#include "core/scene.hpp"

namespace contact2d {

// What an engine reports about a run beyond its trajectory, as plain data
// the run loop passes on without knowing the engine: its warnings, facts
// that are not failures (notes, e.g. "refsafe"), and named values of the
// model it ran (MuJoCo: "solref[0]", "solref[1]", "impratio", "mu_roll").
struct RunFacts {
  std::vector<std::string> warnings;
  std::vector<std::string> notes;
  std::vector<std::pair<std::string, double>> values;

  double value(const std::string& name) const;  // NaN when it is not given
};

class Stepper {
 public:
  virtual ~Stepper() = default;
  virtual void reset(const State& state) = 0;
  // (Fx, Fy, τ) at the COM, held until changed (the game's player).
  virtual void set_applied(const Vec3& force) = 0;
  virtual StepStatus step() = 0;  // one Δt
  // Places obstacle `index` (one with Obstacle::moves) `offset` from where
  // the scene put it, for the steps that follow (the game's keeper). It is
  // geometry that moves between steps: its velocity does not enter the
  // contact law, on the reference as for MuJoCo's mocap bodies (the solver
  // sees them at rest), so a moving obstacle pushes the ball through its
  // spring only. Returns false when the engine cannot move obstacles
  // (the default) or `index` is not a moving obstacle.
  virtual bool move_obstacle(int /*index*/, const Vec2& /*offset*/) { return false; }
  // The next `steps` steps will be taken with no reset and no change of the
  // applied force (the run loop says so before it starts): an engine that
  // works in batches (mujoco3/stepper.hpp) fetches them in few requests.
  // Nothing by default.
  virtual void plan(long long /*steps*/) {}
  virtual const State& state() const = 0;
  virtual const ContactSet& contacts() const = 0;  // at state().q
  // The scene's model (the divergence rule and energies use it).
  virtual const Model& model() const = 0;
  // Its contact in the linear regime at its step: the scheme that integrates
  // the contact force, ω·Δt and that scheme's limit (core/divergence.hpp);
  // the run loop allows an energy rise by it.
  virtual StepStability stability() const = 0;
  // "ref semi_implicit_euler", "mujoco calibrated Euler", …
  virtual std::string describe() const = 0;
  // Why a run on this engine diverged, and what to try, in the engine's own
  // terms; the reference's diagnosis (core/divergence.hpp) by default.
  virtual std::string explain(const Divergence& d, const Scene& scene) const {
    return contact2d::describe(d, scene);
  }
  // What it has to say about the run so far; nothing by default.
  virtual RunFacts facts(const Scene& /*scene*/) const { return {}; }
};

// The reference solver: core step() with the scene's integrator and Δt.
// Allocation-free per step.
// How the reference's warning of a friction stiffer than its step begins:
// a limit of the friction law's own, apart from the contact's stability
// (`stability` maps the contact's and leaves it out).
constexpr const char* kFrictionStepWarning = "friction stiffer than the step";

class ReferenceStepper final : public Stepper {
 public:
  explicit ReferenceStepper(const Scene& scene);
  void reset(const State& state) override;
  void set_applied(const Vec3& force) override { model_.applied = force; }
  StepStatus step() override { return contact2d::step(model_, integrator_, dt_, state_, ws_); }
  bool move_obstacle(int index, const Vec2& offset) override;
  const State& state() const override { return state_; }
  const ContactSet& contacts() const override { return ws_.contacts; }
  const Model& model() const override { return model_; }
  StepStability stability() const override { return reference_stability(model_, integrator_, dt_); }
  std::string describe() const override;
  // A warning, beginning kFrictionStepWarning, when the tanh friction is
  // stiffer than the step (friction_step).
  RunFacts facts(const Scene& scene) const override;

 private:
  Model model_;
  std::vector<Obstacle> placed_;  // the scene's obstacles where it put them
  Integrator integrator_;
  double dt_;
  State state_;
  StepWorkspace ws_;
};

// The scene's initial state (a point mass keeps θ = ω = 0 whatever was given).
State initial_state(const Scene& scene);

}  // namespace contact2d
