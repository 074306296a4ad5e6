#include "mujoco/stepper.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>

#include "core/format.hpp"
#include "mujoco/divergence.hpp"

namespace contact2d::mujoco {
namespace {

bool bad_numbers(const mjData* d) {
  return d->warning[mjWARN_BADQPOS].number > 0 || d->warning[mjWARN_BADQVEL].number > 0 ||
         d->warning[mjWARN_BADQACC].number > 0;
}

}  // namespace

MujocoStepper::MujocoStepper(const Scene& scene, const MjcfOptions& options)
    : MujocoStepper(scene, generate_mjcf(scene, options), options.source) {}

MujocoStepper::MujocoStepper(const Scene& scene, const GeneratedModel& generated,
                             const std::string& source)
    : MujocoStepper(scene, generated.xml, generated_origin(source)) {
  settings_ = generated.settings;
}

MujocoStepper::MujocoStepper(const Scene& scene, const std::string& xml, const std::string& origin)
    : model_(make_model(scene)),
      integrator_(scene.sim.integrator),
      dt_(scene.sim.dt),
      model_ptr_(load_model(xml, origin)),
      data_(make_data(model_ptr_.get())),
      contacts_(model_) {
  const mjModel* m = model_ptr_.get();
  x0_ = m->body_pos[3];
  y0_ = m->body_pos[5];
  hinge_ = m->nq == 3;
  placed_ = model_.obstacles;
  offsets_.assign(placed_.size(), Vec2::Zero());
  for (size_t i = 0; i < placed_.size(); ++i) {
    int id = -1;
    if (placed_[i].moves) {
      const std::string name = "obstacle" + std::to_string(i) + "_body";
      const int body = mj_name2id(m, mjOBJ_BODY, name.c_str());
      if (body >= 0) id = m->body_mocapid[body];
    }
    mocap_.push_back(id);
  }
  // MuJoCo 2.2.2's box–box collider can return a contact on neither box
  // (measured on a box dropped onto a post with --geometry boxes): where a
  // body's box meets a box obstacle, every contact is checked.
  int body_boxes = 0;
  for (int g = 0; g < m->ngeom; ++g)
    body_boxes += m->geom_type[g] == mjGEOM_BOX && m->geom_bodyid[g] > 0 &&
                  (m->geom_contype[g] != 0 || m->geom_conaffinity[g] != 0 || m->npair > 0);
  for (const Obstacle& o : placed_)
    check_outside_ = check_outside_ || (body_boxes > 0 && o.shape == ObstacleShape::Box);
  mj_resetDataKeyframe(m, data_.get(), 0);
  read_state();
}

namespace {

// How far `p` (world) is outside geom g (0 inside): a box's extents, a
// sphere's radius, a plane's half-space; other types count as inside.
double outside_geom(const mjModel* m, const mjData* d, int g, const mjtNum* p) {
  const auto at = static_cast<std::ptrdiff_t>(g);
  const mjtNum* c = d->geom_xpos + 3 * at;
  const mjtNum* r = d->geom_xmat + 9 * at;
  const mjtNum* size = m->geom_size + 3 * at;
  double local[3];
  for (int i = 0; i < 3; ++i)  // Rᵀ·(p − c)
    local[i] = r[i] * (p[0] - c[0]) + r[3 + i] * (p[1] - c[1]) + r[6 + i] * (p[2] - c[2]);
  switch (m->geom_type[g]) {
    case mjGEOM_BOX: {
      double out = 0.0;
      for (int i = 0; i < 3; ++i) out = std::max(out, std::abs(local[i]) - size[i]);
      return out;
    }
    case mjGEOM_SPHERE:
      return std::max(
          0.0,
          std::sqrt(local[0] * local[0] + local[1] * local[1] + local[2] * local[2]) - size[0]);
    case mjGEOM_PLANE: return std::max(0.0, local[2]);
    default: return 0.0;
  }
}

}  // namespace

// The first contact that lies off the body's geom it joins by more than
// 1 mm (plus its own depth), said once: a contact acts on the body where
// it is, and one off the body's surface pushes where the body is not.
void MujocoStepper::check_outside_contacts() {
  const mjModel* m = model_ptr_.get();
  const mjData* d = data_.get();
  for (int i = 0; i < d->ncon && outside_.empty(); ++i) {
    const mjContact& con = d->contact[i];
    const double tolerance = 1e-3 + std::abs(con.dist);
    const int body_geom = m->geom_bodyid[con.geom1] > 0 ? con.geom1 : con.geom2;
    if (m->geom_bodyid[body_geom] == 0) continue;  // two world geoms
    const double off = outside_geom(m, d, body_geom, con.pos);
    if (off <= tolerance) continue;
    outside_ = "MuJoCo 2.2.2 made a contact off the body: at t = " + format_number(d->time, 4) +
               " s, " + format_number(off, 3) + " m outside " +
               name_of(m, mjOBJ_GEOM, body_geom, "geom") + ", between " +
               name_of(m, mjOBJ_GEOM, con.geom1, "geom") + " and " +
               name_of(m, mjOBJ_GEOM, con.geom2, "geom") +
               " (its box-box collider), which pushes where the body is not";
  }
}

bool MujocoStepper::move_obstacle(int index, const Vec2& offset) {
  if (index < 0 || static_cast<size_t>(index) >= placed_.size()) return false;
  const auto i = static_cast<size_t>(index);
  if (mocap_[i] < 0) return false;
  const Obstacle& placed = placed_[i];
  const Vec2 c = 0.5 * (placed.a + placed.b) + offset;
  mjtNum* pos = data_->mocap_pos + 3 * static_cast<std::ptrdiff_t>(mocap_[i]);
  pos[0] = c.x();
  pos[1] = 0.0;
  pos[2] = c.y();
  Obstacle& o = model_.obstacles[i];
  o.a = placed.a + offset;
  o.b = placed.b + offset;
  offsets_[i] = offset;
  return true;
}

void MujocoStepper::read_state() {
  const mjData* d = data_.get();
  state_.q = Vec3(x0_ + d->qpos[0], y0_ + d->qpos[1], hinge_ ? d->qpos[2] : 0.0);
  state_.v = Vec3(d->qvel[0], d->qvel[1], hinge_ ? d->qvel[2] : 0.0);
  find_contacts(model_, state_.q, contacts_);
}

void MujocoStepper::reset(const State& state) {
  mjData* d = data_.get();
  mj_resetData(model_ptr_.get(), d);
  d->qpos[0] = state.q.x() - x0_;
  d->qpos[1] = state.q.y() - y0_;
  d->qvel[0] = state.v.x();
  d->qvel[1] = state.v.y();
  if (hinge_) {
    d->qpos[2] = state.q.z();
    d->qvel[2] = state.v.z();
  }
  set_applied(model_.applied);  // mj_resetData cleared it; the force is held, as the reference's
  // mj_resetData put the mocap bodies back where the model has them; moved
  // obstacles stay where they were moved, as on the reference.
  for (size_t i = 0; i < mocap_.size(); ++i) {
    if (mocap_[i] >= 0) move_obstacle(static_cast<int>(i), offsets_[i]);
  }
  read_state();
}

void MujocoStepper::set_applied(const Vec3& force) {
  // xfrc_applied of body 1 (the only moving body): force (x, y, z), torque
  // (x, y, z); the plane is x–z, rotation about −y (θ = qpos of the hinge).
  mjtNum* f = data_->xfrc_applied + 6;
  f[0] = force.x();
  f[2] = force.y();
  f[4] = -force.z();
  model_.applied = force;
}

StepStatus MujocoStepper::step() {
  {
    WarningCapture capture(messages_);
    mj_step(model_ptr_.get(), data_.get());
  }
  if (check_outside_ && outside_.empty()) check_outside_contacts();
  read_state();
  return bad_numbers(data_.get()) ? StepStatus::NonFinite : StepStatus::Ok;
}

std::string MujocoStepper::describe() const {
  return "mujoco " + std::string(mapping_name(settings_.mapping)) + " " +
         std::string(mujoco_integrator(integrator_));
}

double MujocoStepper::contact_inv_weight() const {
  // Â of the body the contact geoms are on: the mapping's (compensated moves
  // them onto a body of its own), else body 1's body_invweight0
  // (translational, rotational: Â is the first).
  return settings_.inv_mass > 0.0 ? settings_.inv_mass : model_ptr_->body_invweight0[2];
}

StepStability MujocoStepper::stability() const {
  return mujoco_stability(model_, integrator_, dt_, settings_, contact_inv_weight());
}

std::string MujocoStepper::explain(const Divergence& d, const Scene& scene) const {
  return describe_mujoco_divergence(d, scene, settings_, contact_inv_weight());
}

std::vector<std::string> MujocoStepper::warnings() const {
  std::vector<std::string> out = messages_;
  if (!outside_.empty()) out.push_back(outside_);
  // Counters of warnings whose text was already captured add the count.
  for (const std::string& w : warning_counters(data_.get())) out.push_back("mjData.warning: " + w);
  return out;
}

RunFacts mujoco_run_facts(const Scene& scene, const SolverSettings& settings,
                          std::vector<std::string> warnings) {
  RunFacts f;
  f.warnings = std::move(warnings);
  if (settings.refsafe_clamped) f.notes.emplace_back("refsafe");
  f.values = {{"solref[0]", settings.solref[0]},
              {"solref[1]", settings.solref[1]},
              {"impratio", settings.impratio},
              {"mu_roll", cone_mu_roll(scene, settings)}};
  return f;
}

RunFacts MujocoStepper::facts(const Scene& scene) const {
  return mujoco_run_facts(scene, settings_, warnings());
}

}  // namespace contact2d::mujoco
