// MuJoCo as a Stepper (core/stepper.hpp): a scene run through its generated
// MJCF, driven by the same run loop as the reference.
//
// mj_step advances the model with the scene's integrator (Euler, RK4 or
// implicit, mujoco_integrator()) from the keyframe "initial". The planar
// state is read from qpos and qvel: x = x0 + qpos[0], y = y0 + qpos[1] (x0,
// y0 the body's model position), θ = qpos[2], (vx, vy, ω) = qvel (0 for θ, ω
// without a hinge). After each step the reference's contact stage is run on
// that state for the divergence monitor.
//
// Divergence: MuJoCo resets mjData silently when qacc goes bad (it only
// counts a warning), so step() reports StepStatus::NonFinite when one of the
// bad-number counters moved; the run loop then stops, as it does for the
// reference's own rule. MuJoCo's text warnings are collected while stepping.
#pragma once

#include <string>
#include <vector>

#include "core/stepper.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/model.hpp"

namespace contact2d::mujoco {

// What a MuJoCo run reports beyond its trajectory (Stepper::facts), from the
// settings its model was written with: its warnings, "refsafe" when the
// timeconst was raised, and solref, impratio and the rolling coefficient the
// model writes. Both versions' steppers report through it.
RunFacts mujoco_run_facts(const Scene& scene, const SolverSettings& settings,
                          std::vector<std::string> warnings);

class MujocoStepper final : public Stepper {
 public:
  // Generates the model and loads it (InputError on a load error or warning).
  MujocoStepper(const Scene& scene, const MjcfOptions& options);
  // Already generated MJCF text (`origin` names it in messages).
  MujocoStepper(const Scene& scene, const std::string& xml, const std::string& origin);

  void reset(const State& state) override;
  void set_applied(const Vec3& force) override;
  StepStatus step() override;
  // A moving obstacle's mocap body (mjcf.hpp): mocap_pos, and the model the
  // reference's contact stage reads.
  bool move_obstacle(int index, const Vec2& offset) override;
  const State& state() const override { return state_; }
  const ContactSet& contacts() const override { return contacts_; }
  const Model& model() const override { return model_; }
  // MuJoCo's soft constraint under its integrator (mujoco/divergence.hpp).
  StepStability stability() const override;
  std::string describe() const override;
  // MuJoCo's terms (mujoco/divergence.hpp).
  std::string explain(const Divergence& d, const Scene& scene) const override;
  // warnings(); "refsafe" when the timeconst was raised; solref, impratio
  // and the rolling coefficient the model writes (cone_mu_roll).
  RunFacts facts(const Scene& scene) const override;

  const SolverSettings& settings() const { return settings_; }
  // MuJoCo's text warnings so far, then its non-zero warning counters.
  std::vector<std::string> warnings() const;

 private:
  double contact_inv_weight() const;  // Â of the contact geoms' body
  MujocoStepper(const Scene& scene, const GeneratedModel& generated, const std::string& source);
  void read_state();

  Model model_;
  Integrator integrator_;
  double dt_;
  SolverSettings settings_;
  ModelPtr model_ptr_;
  DataPtr data_;
  double x0_ = 0.0, y0_ = 0.0;
  bool hinge_ = false;
  // Box geoms that collide with box obstacles (the boxes geometry): each
  // step's contacts are checked to lie on the geoms they join
  // (outside_contact), once, the first one off both named in warnings().
  bool check_outside_ = false;
  void check_outside_contacts();
  std::string outside_;
  std::vector<Obstacle> placed_;  // the scene's obstacles where it put them
  std::vector<int> mocap_;        // per obstacle: its mocap index, −1 when static
  std::vector<Vec2> offsets_;     // per obstacle: where move_obstacle put it
  State state_;
  ContactSet contacts_;
  std::vector<std::string> messages_;
};

}  // namespace contact2d::mujoco
