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

// How many of a contact's rows are in the solver's quadratic zone, from
// their forces (efc_state is stale after MuJoCo 3's early exits: a row of
// 46 N marked satisfied on the settled humanoid): a pyramidal or
// frictionless row is there when it pushes (a satisfied row carries 0
// exactly); an elliptic contact, all its rows, when its force is strictly
// inside the cone, ‖(f_i/μ_i)‖ < f_n (on the cone's surface it slides).
int quadratic_rows(const double* force, int rows, bool elliptic, const double* mu) {
  if (!elliptic) {
    int n = 0;
    for (int k = 0; k < rows; ++k) n += force[k] > 0.0;
    return n;
  }
  double t = 0.0;
  for (int k = 1; k < rows; ++k) t += (force[k] / mu[k - 1]) * (force[k] / mu[k - 1]);
  return force[0] > 0.0 && std::sqrt(t) < force[0] * (1.0 - 1e-9) ? rows : 0;
}

// <option>, the bodies and the geoms: what does not change with the state.
void read_model_arrays(const mjModel* m, ModelState& s) {
  s.timestep = m->opt.timestep;
  s.integrator = integrator_name(m->opt.integrator);
  s.elliptic = m->opt.cone == mjCONE_ELLIPTIC;
  s.impratio = m->opt.impratio;
  for (int i = 0; i < 3; ++i) s.gravity[static_cast<size_t>(i)] = m->opt.gravity[i];
  s.refsafe = !(m->opt.disableflags & mjDSBL_REFSAFE);
  if (m->opt.disableflags & (mjDSBL_CONSTRAINT | mjDSBL_CONTACT))
    s.disabled = m->opt.disableflags & mjDSBL_CONTACT ? "contacts" : "constraints";
  for (int b = 0; b < m->nbody; ++b) {
    s.body_names.push_back(name_of(m, mjOBJ_BODY, b, "body"));
    s.body_weld.push_back(m->body_weldid[b]);
    s.body_mass.push_back(m->body_mass[b]);
    for (std::ptrdiff_t k = 0; k < 3; ++k)
      s.body_inertia.push_back(m->body_inertia[3 * static_cast<std::ptrdiff_t>(b) + k]);
    s.body_invweight0.push_back(m->body_invweight0[2 * static_cast<std::ptrdiff_t>(b)]);
    s.body_invweight0.push_back(m->body_invweight0[2 * static_cast<std::ptrdiff_t>(b) + 1]);
  }
  s.body_joints.assign(static_cast<size_t>(m->nbody), "");
  for (int j = 0; j < m->njnt; ++j) {
    std::string& list = s.body_joints[static_cast<size_t>(m->jnt_bodyid[j])];
    const int type = m->jnt_type[j];
    list += std::string(list.empty() ? "" : ", ") + (type == mjJNT_FREE    ? "free"
                                                     : type == mjJNT_SLIDE ? "slide"
                                                     : type == mjJNT_HINGE ? "hinge"
                                                                           : "ball");
  }
  for (int b = 0; b < m->nbody; ++b) s.body_parent.push_back(m->body_parentid[b]);
  for (int g = 0; g < m->ngeom; ++g) {
    s.geom_names.push_back(name_of(m, mjOBJ_GEOM, g, "geom"));
    s.geom_body.push_back(m->geom_bodyid[g]);
    s.geom_mu.push_back(m->geom_friction[3 * static_cast<std::ptrdiff_t>(g)]);
    s.geom_condim.push_back(m->geom_condim[g]);
    s.geom_collides.push_back((m->geom_contype[g] | m->geom_conaffinity[g]) != 0);
  }
}

// Every contact in the constraint problem, with its rows' numbers: one
// within its gap (exclude 1) or otherwise left out of it has no rows, and
// is not listed (as the driver of mujoco3 reads 3.14).
void read_contacts(const mjModel* m, mjData* d, ModelState& s) {
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& con = d->contact[i];
    if (con.exclude != 0 || con.efc_address < 0) continue;
    StateContact c;
    c.geom1 = con.geom1;
    c.geom2 = con.geom2;
    c.body1 = m->geom_bodyid[con.geom1];
    c.body2 = m->geom_bodyid[con.geom2];
    // 2.2.2's mj_collideGeoms: a pair's own margin and gap, else the larger geom's.
    c.margin = std::max(m->geom_margin[con.geom1], m->geom_margin[con.geom2]);
    c.gap = std::max(m->geom_gap[con.geom1], m->geom_gap[con.geom2]);
    for (int p = 0; p < m->npair; ++p) {
      if ((m->pair_geom1[p] == con.geom1 && m->pair_geom2[p] == con.geom2) ||
          (m->pair_geom1[p] == con.geom2 && m->pair_geom2[p] == con.geom1)) {
        c.explicit_pair = true;
        c.margin = m->pair_margin[p];
        c.gap = m->pair_gap[p];
      }
    }
    c.dist = con.dist - con.includemargin;
    for (size_t k = 0; k < 3; ++k) {
      c.pos[k] = con.pos[k];
      c.normal[k] = con.frame[k];
    }
    c.condim = con.dim;
    for (size_t k = 0; k < 5; ++k) c.friction[k] = con.friction[k];
    for (size_t k = 0; k < 2; ++k) c.solref[k] = con.solref[k];
    for (size_t k = 0; k < 5; ++k) c.solimp[k] = con.solimp[k];
    const std::vector<double> row = normal_jacobian(m, d, c.body1, c.body2, c.pos, c.normal);
    std::vector<double> solved(row.size());
    mj_solveM(m, d, solved.data(), row.data(), 1);
    c.jacobian = SparseRow::of(row);
    c.solved = SparseRow::of(solved);
    c.A = c.jacobian.dot(c.solved);
    if (con.dim >= 3) {
      for (size_t axis = 1; axis < 3; ++axis) {
        const std::array<double, 3> t{con.frame[3 * axis], con.frame[3 * axis + 1],
                                      con.frame[3 * axis + 2]};
        const std::vector<double> trow = normal_jacobian(m, d, c.body1, c.body2, c.pos, t);
        std::vector<double> tsolved(trow.size());
        mj_solveM(m, d, tsolved.data(), trow.data(), 1);
        c.tangent[axis - 1] = SparseRow::of(trow);
        c.tangent_solved[axis - 1] = SparseRow::of(tsolved);
        c.A_t = std::max(c.A_t, c.tangent[axis - 1].dot(c.tangent_solved[axis - 1]));
      }
    }
    double force[6] = {};
    mj_contactForce(m, d, i, force);
    c.force = force[0];
    c.rows = m->opt.cone == mjCONE_ELLIPTIC || con.dim == 1 ? con.dim : 2 * (con.dim - 1);
    c.quadratic = quadratic_rows(d->efc_force + con.efc_address, c.rows,
                                 m->opt.cone == mjCONE_ELLIPTIC && con.dim > 1, con.friction);
    s.contacts.push_back(c);
  }
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
  for (int i = 0; i < m->nv; ++i) {
    s.speed = std::max(s.speed, std::abs(d->qvel[i]));
    s.accel = std::max(s.accel, std::abs(d->qacc[i]));
  }
  s.settled = static_cast<double>(steps) * m->opt.timestep;
  for (const std::string& w : warning_counters(d)) messages.push_back(w);

  read_model_arrays(m, s);
  s.nv = m->nv;

  s.qvel.assign(d->qvel, d->qvel + m->nv);
  s.qacc.assign(d->qacc, d->qacc + m->nv);

  read_contacts(m, d, s);
  // The gravity load at this configuration, at rest: qfrc_bias at qvel = 0,
  // in the same mjData (a second one would double MuJoCo's memory: 0.88 GB
  // for the particle sample); positions and contacts stay as read above.
  mju_zero(d->qvel, m->nv);
  mj_forward(m, d);
  s.bias.assign(d->qfrc_bias, d->qfrc_bias + m->nv);
  s.messages = messages;  // names: name_of gives them printable
  return out;
}

std::string settle_cap_note(double settle, double timestep) {
  if (!(settle / timestep > static_cast<double>(kMaxSettleSteps))) return "";
  return "--settle " + format_number(settle) + " s is more than the " +
         std::to_string(kMaxSettleSteps) + " steps a settle takes: settled " +
         format_number(static_cast<double>(kMaxSettleSteps) * timestep) + " s";
}

void make_names_printable(ModelState& state) {
  for (std::vector<std::string>* names : {&state.body_names, &state.geom_names})
    for (std::string& name : *names) name = printable_name(name);
}

ModelState read_model_state(const StateRequest& request) {
  return std::move(load_model_state(request).state);
}

}  // namespace contact2d::mujoco
