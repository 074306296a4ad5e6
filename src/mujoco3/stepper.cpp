#include "mujoco3/stepper.hpp"

#include <algorithm>
#include <cmath>

#include "core/format.hpp"
#include "core/input_error.hpp"
#include "mujoco/divergence.hpp"
#include "mujoco/stepper.hpp"

namespace contact2d::mujoco3 {
namespace {

mujoco::GeneratedModel generate(const Scene& scene, mujoco::MjcfOptions& options) {
  options.version = mujoco::Version::V3;
  return mujoco::generate_mjcf(scene, options);
}

}  // namespace

Mujoco3Stepper::Mujoco3Stepper(const Scene& scene, mujoco::MjcfOptions options)
    : Mujoco3Stepper(scene, generate(scene, options), options.source) {}

Mujoco3Stepper::Mujoco3Stepper(const Scene& scene, const mujoco::GeneratedModel& generated,
                               const std::string& source)
    : Mujoco3Stepper(scene, generated.xml, mujoco::generated_origin(source), generated.settings) {
  // The mapping's Â was read from MuJoCo 2.2.2's compile (mujoco/mjcf.hpp);
  // the model is written so that 3.14 has the same (the point mass's spin).
  // Translational body_invweight0 of the body whose contacts it maps: body 1,
  // or compensated's "contacts" (body 2).
  const size_t body = settings_.mapping == mujoco::Mapping::Compensated ? 2 : 1;
  const double a3 = loaded_.body_invweight0.at(2 * body);
  if (settings_.inv_mass > 0.0 && std::abs(a3 - settings_.inv_mass) > 1e-12 * settings_.inv_mass)
    throw EngineError("mujoco3: MuJoCo " + std::string(kVersion) + " gives body_invweight0 " +
                      format_shortest(a3) + " where the model was mapped for " +
                      format_shortest(settings_.inv_mass) + " (MuJoCo 2.2.2's)");
}

Mujoco3Stepper::Mujoco3Stepper(const Scene& scene, const std::string& xml,
                               const std::string& origin, const mujoco::SolverSettings& settings)
    : model_(make_model(scene)),
      integrator_(scene.sim.integrator),
      dt_(scene.sim.dt),
      settings_(settings),
      xml_(xml),
      node_(Node::of_this_thread()),
      contacts_(model_) {
  node_->take_messages();  // another's, on this thread's Node
  loaded_ = node_->load(xml_, origin);
  collect_messages();
  x0_ = loaded_.body_pos.at(3);
  y0_ = loaded_.body_pos.at(5);
  turns_ = shape_features(scene.shape).turns;
  reset(initial_state(scene));
}

Mujoco3Stepper::~Mujoco3Stepper() {
  try {
    node_->free(loaded_.id);
  } catch (const std::exception&) {  // NOLINT(bugprone-empty-catch)
    // The process is gone, and the model with it.
  }
}

void Mujoco3Stepper::read(const double* q) {
  const double* v = q + loaded_.nq;
  state_.q = Vec3(x0_ + q[0], y0_ + q[1], turns_ ? q[2] : 0.0);
  state_.v = Vec3(v[0], v[1], turns_ ? v[2] : 0.0);
  find_contacts(model_, state_.q, contacts_);
}

void Mujoco3Stepper::reset(const State& state) {
  std::vector<double> qpos(static_cast<size_t>(loaded_.nq), 0.0);
  std::vector<double> qvel(static_cast<size_t>(loaded_.nv), 0.0);
  qpos[0] = state.q.x() - x0_;
  qpos[1] = state.q.y() - y0_;
  qvel[0] = state.v.x();
  qvel[1] = state.v.y();
  if (turns_) {
    qpos[2] = state.q.z();
    qvel[2] = state.v.z();
  }
  node_->reset(loaded_.id, qpos, qvel);
  collect_messages();
  batch_steps_ = read_ = 0;
  planned_ = 0;
  std::vector<double> both = qpos;
  both.insert(both.end(), qvel.begin(), qvel.end());
  read(both.data());
  if (applied_ != Vec3::Zero()) {  // mj_resetData cleared it
    const Vec3 force = applied_;
    applied_ = Vec3::Zero();
    set_applied(force);
  }
}

void Mujoco3Stepper::set_applied(const Vec3& force) {
  model_.applied = force;
  if (force == applied_) return;
  if (read_ < batch_steps_) {  // back to the state read last
    messages_.resize(batch_messages_);
    node_->rewind(loaded_.id, read_);
    collect_messages();
  }
  batch_steps_ = read_ = 0;
  planned_ = 0;
  next_batch_ = 16;
  applied_ = force;
  // xfrc_applied of body 1: force (x, y, z), torque (x, y, z); the plane is
  // x–z, θ turns about −y (mujoco/stepper.cpp).
  node_->applied(loaded_.id, 1, {force.x(), 0.0, force.y(), 0.0, -force.z(), 0.0});
  collect_messages();
}

void Mujoco3Stepper::fetch() {
  int n = next_batch_;
  batch_planned_ = planned_ > 0;
  if (planned_ > 0) {
    n = static_cast<int>(std::min<long long>(planned_, kMaxBatch));
    planned_ -= n;
  } else {
    next_batch_ = std::min(2 * next_batch_, kMaxBatch);
  }
  batch_messages_ = messages_.size();
  batch_steps_ = node_->step(loaded_.id, n, loaded_.nq + loaded_.nv, batch_, batch_bad_);
  collect_messages();
  read_ = 0;
  if (batch_steps_ <= 0) throw EngineError("mujoco3: MuJoCo 3 took no step");
}

StepStatus Mujoco3Stepper::step() {
  if (read_ == batch_steps_) fetch();
  const size_t width = static_cast<size_t>(loaded_.nq) + static_cast<size_t>(loaded_.nv);
  read(batch_.data() + width * static_cast<size_t>(read_));
  ++read_;
  return batch_bad_ && read_ == batch_steps_ ? StepStatus::NonFinite : StepStatus::Ok;
}

std::string Mujoco3Stepper::describe() const {
  return "mujoco3 " + std::string(mujoco::mapping_name(settings_.mapping)) + " " +
         std::string(mujoco::mujoco_integrator(integrator_));
}

double Mujoco3Stepper::contact_inv_weight() const {
  // As MujocoStepper's: the mapping's Â, else body 1's.
  return settings_.inv_mass > 0.0 ? settings_.inv_mass : loaded_.body_invweight0.at(2);
}

StepStability Mujoco3Stepper::stability() const {
  return mujoco::mujoco_stability(model_, integrator_, dt_, settings_, contact_inv_weight());
}

std::string Mujoco3Stepper::explain(const Divergence& d, const Scene& scene) const {
  return mujoco::describe_mujoco_divergence(d, scene, settings_, contact_inv_weight());
}

void Mujoco3Stepper::collect_messages() const {
  for (std::string& m : node_->take_messages()) messages_.push_back(std::move(m));
}

void Mujoco3Stepper::drop_read_ahead() const {
  if (read_ >= batch_steps_) return;
  messages_.resize(batch_messages_);  // the batch's, printed ahead too
  node_->rewind(loaded_.id, read_);   // counters restored, then read_ steps again
  collect_messages();
  if (batch_planned_) planned_ += batch_steps_ - read_;
  batch_steps_ = read_;
  batch_bad_ = false;  // a bad step, if any, was one not read
}

std::vector<std::string> Mujoco3Stepper::warnings() const {
  drop_read_ahead();
  std::vector<std::string> out = messages_;
  for (const std::string& w : node_->counters(loaded_.id)) out.push_back("mjData.warning: " + w);
  return out;
}

RunFacts Mujoco3Stepper::facts(const Scene& scene) const {
  return mujoco::mujoco_run_facts(scene, settings_, warnings());
}

}  // namespace contact2d::mujoco3
