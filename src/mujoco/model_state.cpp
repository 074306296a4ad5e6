// A user's model at one state, from MuJoCo 2.2.2 (mujoco/model_state.hpp).
#include "mujoco/model_state.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "core/cancel.hpp"
#include "core/format.hpp"
#include "core/input_error.hpp"
#include "io/read_file.hpp"
#include "mujoco/model_files.hpp"
#include "mujoco/state_arrays.hpp"

namespace contact2d::mujoco {
namespace {

std::string one_line(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  std::replace(text.begin(), text.end(), '\n', ' ');
  return text;
}

std::string prefix(const StateRequest& r) {
  return (r.option.empty() ? "" : r.option + " ") + r.path + ": ";
}

std::string integrator_name(int integrator) {
  switch (integrator) {
    case mjINT_EULER: return "Euler";
    case mjINT_RK4: return "RK4";
    case mjINT_IMPLICIT: return "implicit";
    default: return "integrator " + std::to_string(integrator);
  }
}

// <option>, decoded here: its enums and flag bits are 2.2.2's.
void read_option(const mjModel* m, ModelState& s) {
  s.timestep = m->opt.timestep;
  s.integrator = integrator_name(m->opt.integrator);
  s.elliptic = m->opt.cone == mjCONE_ELLIPTIC;
  s.impratio = m->opt.impratio;
  s.noslip_iterations = m->opt.noslip_iterations;
  for (int i = 0; i < 3; ++i) s.gravity[static_cast<size_t>(i)] = m->opt.gravity[i];
  s.refsafe = !(m->opt.disableflags & mjDSBL_REFSAFE);
  if (m->opt.disableflags & (mjDSBL_CONSTRAINT | mjDSBL_CONTACT))
    s.disabled = m->opt.disableflags & mjDSBL_CONTACT ? "contacts" : "constraints";
}

template <typename T>
std::vector<T> copy_of(const T* data, int count, int width = 1) {
  return std::vector<T>(data, data + static_cast<std::ptrdiff_t>(count) * width);
}

// mj_jac's translational rows of a body at a point, sparse.
std::array<SparseRow, 3> body_jacobian(const mjModel* m, const mjData* d, int body,
                                       const double* pos) {
  const auto nv = static_cast<std::ptrdiff_t>(m->nv);
  std::vector<double> jp(static_cast<size_t>(3 * nv)), jr(static_cast<size_t>(3 * nv));
  mj_jac(m, d, jp.data(), jr.data(), pos, body);
  std::array<SparseRow, 3> out;
  for (std::ptrdiff_t k = 0; k < 3; ++k)
    out[static_cast<size_t>(k)] =
        SparseRow::of(std::vector<double>(jp.begin() + k * nv, jp.begin() + (k + 1) * nv));
  return out;
}

// The model's and data's arrays state_arrays.hpp reads, and each contact's
// Jacobians and normal force.
StateArrays arrays_of(const mjModel* m, mjData* d) {
  StateArrays a;
  a.margin_rule = MarginRule::Larger;
  a.nv = m->nv;
  a.elliptic = m->opt.cone == mjCONE_ELLIPTIC;
  for (int b = 0; b < m->nbody; ++b) {
    const char* name = mj_id2name(m, mjOBJ_BODY, b);
    a.body_names.emplace_back(name ? name : "");
  }
  for (int g = 0; g < m->ngeom; ++g) {
    const char* name = mj_id2name(m, mjOBJ_GEOM, g);
    a.geom_names.emplace_back(name ? name : "");
  }
  a.body_weldid = copy_of(m->body_weldid, m->nbody);
  a.body_parentid = copy_of(m->body_parentid, m->nbody);
  a.body_mass = copy_of(m->body_mass, m->nbody);
  a.body_inertia = copy_of(m->body_inertia, m->nbody, 3);
  a.body_invweight0 = copy_of(m->body_invweight0, m->nbody, 2);
  a.jnt_bodyid = copy_of(m->jnt_bodyid, m->njnt);
  a.jnt_type = copy_of(m->jnt_type, m->njnt);
  a.geom_bodyid = copy_of(m->geom_bodyid, m->ngeom);
  a.geom_condim = copy_of(m->geom_condim, m->ngeom);
  a.geom_contype = copy_of(m->geom_contype, m->ngeom);
  a.geom_conaffinity = copy_of(m->geom_conaffinity, m->ngeom);
  a.geom_friction = copy_of(m->geom_friction, m->ngeom, 3);
  a.geom_margin = copy_of(m->geom_margin, m->ngeom);
  a.geom_gap = copy_of(m->geom_gap, m->ngeom);
  a.geom_priority = copy_of(m->geom_priority, m->ngeom);
  a.geom_solmix = copy_of(m->geom_solmix, m->ngeom);
  a.geom_solref = copy_of(m->geom_solref, m->ngeom, mjNREF);
  a.pair_geom1 = copy_of(m->pair_geom1, m->npair);
  a.pair_geom2 = copy_of(m->pair_geom2, m->npair);
  a.pair_margin = copy_of(m->pair_margin, m->npair);
  a.pair_gap = copy_of(m->pair_gap, m->npair);
  a.qvel = copy_of(d->qvel, m->nv);
  a.qacc = copy_of(d->qacc, m->nv);
  a.efc_force = copy_of(d->efc_force, d->nefc);
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& con = d->contact[i];
    ArrayContact c;
    c.geom1 = con.geom1;
    c.geom2 = con.geom2;
    c.dim = con.dim;
    c.exclude = con.exclude;
    c.efc_address = con.efc_address;
    c.dist = con.dist;
    c.includemargin = con.includemargin;
    std::copy(con.pos, con.pos + 3, c.pos.begin());
    std::copy(con.frame, con.frame + 9, c.frame.begin());
    std::copy(con.friction, con.friction + 5, c.friction.begin());
    std::copy(con.solref, con.solref + 2, c.solref.begin());
    std::copy(con.solimp, con.solimp + 5, c.solimp.begin());
    double force[6] = {};
    mj_contactForce(m, d, i, force);
    c.normal_force = force[0];
    c.jac1 = body_jacobian(m, d, m->geom_bodyid[con.geom1], con.pos);
    c.jac2 = body_jacobian(m, d, m->geom_bodyid[con.geom2], con.pos);
    a.contacts.push_back(std::move(c));
  }
  return a;
}

}  // namespace

double coupled_tangential_inverse_mass(const ModelState& state, const std::vector<int>& contacts) {
  std::vector<std::pair<const SparseRow*, const SparseRow*>> rows;
  for (const int i : contacts) {
    const StateContact& c = state.contacts[static_cast<size_t>(i)];
    for (size_t k = 0; k < 2; ++k)
      if (!c.tangent[k].index.empty()) rows.emplace_back(&c.tangent[k], &c.tangent_solved[k]);
  }
  if (rows.empty()) return 0.0;
  const auto n = static_cast<Eigen::Index>(rows.size());
  Eigen::MatrixXd A(n, n);
  for (Eigen::Index a = 0; a < n; ++a)
    for (Eigen::Index b = 0; b < n; ++b)
      A(a, b) = rows[static_cast<size_t>(a)].first->dot(*rows[static_cast<size_t>(b)].second);
  const Eigen::MatrixXd symmetric = 0.5 * (A + A.transpose());
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(symmetric, Eigen::EigenvaluesOnly)
      .eigenvalues()
      .maxCoeff();
}

void check_state_request(const StateRequest& r) {
  if (!(r.settle >= 0.0 && std::isfinite(r.settle)))
    throw InputError("--settle " + format_number(r.settle) +
                     ": must be a time in seconds, >= 0 and finite");
  // A regular file within the cap, checked without opening it: opening a
  // FIFO blocks until a writer comes, and a device reads without end.
  try {
    check_input_file(r.path, "the MJCF file");
  } catch (const InputError& e) {  // "PATH: cannot read …", named by its option
    throw InputError((r.option.empty() ? "" : r.option + " ") + e.what());
  }
}

LoadedState load_model_state(const StateRequest& r) {
  check_state_request(r);
  // The files 2.2.2 opens itself (includes, meshes, textures): a FIFO among
  // them would block mj_loadXML for ever, a device be read without end.
  try {
    check_files_read_by_2_2_2(r.path);
  } catch (const InputError& e) {
    throw InputError((r.option.empty() ? "" : r.option + " ") + e.what());
  }
  LoadedState out;
  ModelState& s = out.state;
  s.version = mj_versionString();
  std::vector<std::string> messages;
  WarningCapture capture(messages);
  char error[1000] = "";
  mjModel* raw = nullptr;
  try {
    raw = mj_loadXML(r.path.c_str(), nullptr, error, sizeof error);
  } catch (const MujocoError& e) {
    throw InputError(prefix(r) + "MuJoCo cannot load the model: " + one_line(e.what()));
  }
  if (!raw) throw InputError(prefix(r) + "MuJoCo cannot load the model: " + one_line(error));
  out.model.reset(raw);
  const mjModel* m = raw;
  s.load_warning = one_line(error);
  for (const std::string& w : messages)
    s.load_warning += (s.load_warning.empty() ? "" : "; ") + one_line(w);
  messages.clear();

  int key = -1;
  if (!r.key.empty()) {
    key = mj_name2id(m, mjOBJ_KEY, r.key.c_str());
    if (key < 0) {
      std::string names;
      for (int i = 0; i < m->nkey; ++i)
        names += (names.empty() ? "" : ", ") + name_of(m, mjOBJ_KEY, i, "key");
      throw InputError("--key " + r.key + ": no keyframe of that name in " + r.path +
                       (m->nkey ? " (its keyframes: " + names + ")" : " (it has none)"));
    }
  }
  if (!(m->opt.timestep > 0.0) || !std::isfinite(m->opt.timestep))
    throw InputError(prefix(r) + "<option timestep> is " + format_number(m->opt.timestep) +
                     " s: MuJoCo steps only with a finite timestep > 0");
  out.data = make_data(m);
  mjData* d = out.data.get();
  if (key >= 0)
    mj_resetDataKeyframe(m, d, key);
  else
    mj_resetData(m, d);
  for (int i = 0; i < m->nq; ++i)
    if (!std::isfinite(d->qpos[i]))
      throw InputError((key >= 0 ? "--key " + r.key + ": its qpos" : prefix(r) + "qpos0") +
                       " has a number that is not finite (" + format_number(d->qpos[i]) +
                       " at qpos[" + std::to_string(i) + "])");
  // At most kMaxSettleSteps, said so when the settle asked for more (a
  // settle of 1e16 s would overflow lround).
  const double wanted = r.settle / m->opt.timestep;
  const long steps =
      wanted >= static_cast<double>(kMaxSettleSteps) ? kMaxSettleSteps : std::lround(wanted);
  if (const std::string note = settle_cap_note(r.settle, m->opt.timestep); !note.empty())
    messages.push_back(note);
  for (long i = 0; i < steps; ++i) {
    if ((i & 1023) == 0) throw_if_cancelled();  // a Python Ctrl-C (core/cancel.hpp)
    mj_step(m, d);
  }
  mj_forward(m, d);
  // MuJoCo resets mjData when a state goes bad (autoreset): what is read
  // then is qpos0 again, not a settled model.
  for (const int w : {mjWARN_BADQPOS, mjWARN_BADQVEL, mjWARN_BADQACC}) {
    if (d->warning[w].number == 0) continue;
    std::string said;
    for (const std::string& line : warning_counters(d)) said += (said.empty() ? "" : "; ") + line;
    throw EngineError(prefix(r) + "MuJoCo diverged while settling (" + said +
                      "): there is no settled state to read");
  }
  s.settled = static_cast<double>(steps) * m->opt.timestep;
  for (const std::string& w : warning_counters(d)) messages.push_back(w);

  read_option(m, s);
  const StateArrays arrays = arrays_of(m, d);
  read_state_arrays(
      arrays,
      [&](const std::vector<SparseRow>& rows) {
        std::vector<SparseRow> out;
        std::vector<double> dense(static_cast<size_t>(m->nv)), solved(dense.size());
        for (const SparseRow& row : rows) {
          std::fill(dense.begin(), dense.end(), 0.0);
          for (size_t k = 0; k < row.index.size(); ++k)
            dense[static_cast<size_t>(row.index[k])] = row.value[k];
          mj_solveM(m, d, solved.data(), dense.data(), 1);
          out.push_back(SparseRow::of(solved));
        }
        return out;
      },
      s);
  // The gravity load at this configuration, at rest: qfrc_bias at qvel = 0,
  // in the same mjData (a second one would double MuJoCo's memory: 0.88 GB
  // for the particle sample); positions and contacts stay as read. After
  // the solves: this mj_forward factors M again, which moved A in its 16th
  // digit.
  mju_zero(d->qvel, m->nv);
  mj_forward(m, d);
  s.bias = copy_of(d->qfrc_bias, m->nv);
  s.messages = messages;
  return out;
}

std::string settle_cap_note(double settle, double timestep) {
  if (!(settle / timestep > static_cast<double>(kMaxSettleSteps))) return "";
  return "--settle " + format_number(settle) + " s is more than the " +
         std::to_string(kMaxSettleSteps) + " steps a settle takes: settled " +
         format_number(static_cast<double>(kMaxSettleSteps) * timestep) + " s";
}

ModelState read_model_state(const StateRequest& request) {
  return std::move(load_model_state(request).state);
}

}  // namespace contact2d::mujoco
