// MuJoCo 3 (the engine mujoco3) as a Stepper (core/stepper.hpp): the scene's
// MJCF written for MuJoCo 3 (mujoco/mjcf.hpp, Version::V3) and stepped in
// the Node process of mujoco3/node_mujoco.hpp, read back as MujocoStepper
// reads MuJoCo 2.2.2 (mujoco/stepper.hpp): x = x0 + qpos[0], y = y0 +
// qpos[1], θ = qpos[2] for a body that turns, (vx, vy, ω) = qvel.
//
// Steps come in batches: plan(n) (the run loop's) fetches the n steps ahead
// in requests of up to kMaxBatch; without a plan (the game) batches grow
// from 16 by doubling. A change of the applied force with steps of a batch
// still unread rewinds MuJoCo to the step read last before applying it, so
// the trajectory is the one a step-by-step run gives, bit for bit. So does
// warnings() (and facts()): MuJoCo's warning counters (restored with the
// state) and printed messages are of the steps read, never of a batch's
// steps run ahead (a run stopped at step 100 of a plan of 20,000 reported
// the bad qpos of step 15,812), and of this stepper's requests only.
//
// A step that raised MuJoCo's bad-number counters (qpos, qvel, qacc; the
// driver reads them, autoreset off, so the state stays where it went bad)
// is StepStatus::NonFinite, as on 2.2.2 (where MuJoCo resets mjData): the
// same steps on both versions.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/stepper.hpp"
#include "mujoco/mapping.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco3/node_mujoco.hpp"

namespace contact2d::mujoco3 {

// The largest batch: 16384 steps of a body with 3 joints is 786 kB.
constexpr int kMaxBatch = 16384;

class Mujoco3Stepper final : public Stepper {
 public:
  // Writes the model for MuJoCo 3 (options.version is set to V3) and loads
  // it there (InputError on MuJoCo 3's refusal or when it cannot run here).
  Mujoco3Stepper(const Scene& scene, mujoco::MjcfOptions options);
  // MJCF text as given (`origin` names it in messages), with the settings it
  // was written with (facts, the divergence message): the measurements that
  // run a model changed by hand (bench/version_table.cpp).
  Mujoco3Stepper(const Scene& scene, const std::string& xml, const std::string& origin,
                 const mujoco::SolverSettings& settings);
  ~Mujoco3Stepper() override;
  Mujoco3Stepper(const Mujoco3Stepper&) = delete;
  Mujoco3Stepper& operator=(const Mujoco3Stepper&) = delete;

  void reset(const State& state) override;
  void set_applied(const Vec3& force) override;
  void plan(long long steps) override { planned_ = steps; }
  StepStatus step() override;
  const State& state() const override { return state_; }
  const ContactSet& contacts() const override { return contacts_; }
  const Model& model() const override { return model_; }
  // MuJoCo's soft constraint under its integrator (mujoco/divergence.hpp).
  StepStability stability() const override;
  std::string describe() const override;
  std::string explain(const Divergence& d, const Scene& scene) const override;
  RunFacts facts(const Scene& scene) const override;

  const mujoco::SolverSettings& settings() const { return settings_; }
  const std::string& xml() const { return xml_; }
  // MuJoCo 3's printed warnings so far, then its non-zero warning counters,
  // both of the steps read (the batch's steps not read are undone first).
  std::vector<std::string> warnings() const;

 private:
  double contact_inv_weight() const;  // Â of the contact geoms' body
  Mujoco3Stepper(const Scene& scene, const mujoco::GeneratedModel& generated,
                 const std::string& source);
  void fetch();
  void read(const double* qpos_qvel);
  void collect_messages() const;  // the Node's, printed during this stepper's request
  // The steps of the last batch not read are undone: MuJoCo back at the step
  // read last, its counters and messages as of it (warnings(), facts()).
  void drop_read_ahead() const;

  Model model_;
  Integrator integrator_;
  double dt_;
  mujoco::SolverSettings settings_;
  std::string xml_;
  std::shared_ptr<Node> node_;  // this thread's, kept alive while the model is loaded
  LoadedModel loaded_;
  double x0_ = 0.0, y0_ = 0.0;
  bool turns_ = false;  // θ = qpos[2] (a point mass's "spin" is no θ)
  State state_;
  ContactSet contacts_;
  Vec3 applied_ = Vec3::Zero();
  std::vector<double> batch_;  // qpos, qvel of each step of the last batch
  // Mutable: warnings() undoes the steps fetched and not read.
  mutable int batch_steps_ = 0;
  int read_ = 0;
  mutable bool batch_bad_ = false;  // its last step raised a bad-number counter
  mutable long long planned_ = 0;   // steps of the run still ahead (0: unknown)
  bool batch_planned_ = false;      // the last batch was taken from planned_
  int next_batch_ = 16;             // without a plan
  // MuJoCo's printed messages during this stepper's requests (not another
  // stepper's on the same Node); batch_messages_ of them before the last batch.
  mutable std::vector<std::string> messages_;
  mutable size_t batch_messages_ = 0;
};

}  // namespace contact2d::mujoco3
