// A ModelState read from MuJoCo's arrays, one reader for both versions
// (mujoco/state_arrays.hpp).
#include "mujoco/state_arrays.hpp"

#include <algorithm>
#include <cmath>

#include "mujoco/model.hpp"

namespace contact2d::mujoco {
namespace {

// The solver's constraint rows of a contact: pyramidal 2(condim − 1), or 1
// without friction; elliptic condim.
int contact_rows(int dim, bool elliptic) { return elliptic || dim == 1 ? dim : 2 * (dim - 1); }

// How many of a contact's rows are in the solver's quadratic zone, from
// their forces (efc_state is stale after MuJoCo 3's early exits: a row of
// 46 N marked satisfied on the settled humanoid): a pyramidal or
// frictionless row is there when it pushes (a satisfied row carries 0
// exactly); an elliptic contact, all its rows, when its force is strictly
// inside the cone, ‖(f_i/μ_i)‖ < f_n (on the cone's surface it slides).
int quadratic_rows(const double* force, int rows, bool elliptic, const std::array<double, 5>& mu) {
  if (!elliptic) {
    int n = 0;
    for (int k = 0; k < rows; ++k) n += force[k] > 0.0;
    return n;
  }
  double t = 0.0;
  for (int k = 1; k < rows; ++k) {
    const double f = force[k] / mu[static_cast<size_t>(k - 1)];
    t += f * f;
  }
  return force[0] > 0.0 && std::sqrt(t) < force[0] * (1.0 - 1e-9) ? rows : 0;
}

// The contact's row along a direction: axis·(J₂ − J₁) over the dofs.
std::vector<double> frame_row(const ArrayContact& c, int nv, const double* axis) {
  const auto n = static_cast<size_t>(nv);
  std::vector<double> j1(3 * n, 0.0), j2(3 * n, 0.0), row(n, 0.0);
  for (size_t k = 0; k < 3; ++k) {
    for (size_t i = 0; i < c.jac1[k].index.size(); ++i)
      j1[k * n + static_cast<size_t>(c.jac1[k].index[i])] = c.jac1[k].value[i];
    for (size_t i = 0; i < c.jac2[k].index.size(); ++i)
      j2[k * n + static_cast<size_t>(c.jac2[k].index[i])] = c.jac2[k].value[i];
  }
  for (size_t k = 0; k < 3; ++k)
    for (size_t i = 0; i < n; ++i) row[i] += axis[k] * (j2[k * n + i] - j1[k * n + i]);
  return row;
}

std::string joint_name(int type) {
  // mjtJoint, the same in both versions
  switch (type) {
    case 0: return "free";
    case 1: return "ball";
    case 2: return "slide";
    case 3: return "hinge";
    default: return "joint type " + std::to_string(type);
  }
}

void read_bodies_and_geoms(const StateArrays& a, ModelState& s) {
  const size_t nbody = a.body_names.size(), ngeom = a.geom_names.size();
  for (size_t b = 0; b < nbody; ++b) {
    const std::string& name = a.body_names[b];
    s.body_names.push_back(!name.empty() ? printable_name(name)
                           : b == 0      ? "world"
                                         : "body #" + std::to_string(b));
  }
  s.body_weld = a.body_weldid;
  s.body_mass = a.body_mass;
  s.body_inertia = a.body_inertia;
  s.body_invweight0 = a.body_invweight0;
  s.body_parent = a.body_parentid;
  s.body_joints.assign(nbody, "");
  for (size_t j = 0; j < a.jnt_bodyid.size(); ++j) {
    std::string& list = s.body_joints[static_cast<size_t>(a.jnt_bodyid[j])];
    list += (list.empty() ? "" : ", ") + joint_name(a.jnt_type[j]);
  }
  for (size_t g = 0; g < ngeom; ++g) {
    const std::string& name = a.geom_names[g];
    s.geom_names.push_back(!name.empty() ? printable_name(name) : "geom #" + std::to_string(g));
    s.geom_mu.push_back(a.geom_friction[3 * g]);
    s.geom_collides.push_back((a.geom_contype[g] | a.geom_conaffinity[g]) != 0);
  }
  s.geom_body = a.geom_bodyid;
  s.geom_condim = a.geom_condim;
  s.geom_priority = a.geom_priority;
  s.geom_solmix = a.geom_solmix;
  s.geom_solref = a.geom_solref;
}

// A contact's fields other than its inverse masses (the rows' M⁻¹ come
// after, in one call for all contacts).
StateContact contact_fields(const StateArrays& a, const ArrayContact& con) {
  StateContact c;
  c.geom1 = con.geom1;
  c.geom2 = con.geom2;
  const auto g1 = static_cast<size_t>(con.geom1), g2 = static_cast<size_t>(con.geom2);
  c.body1 = a.geom_bodyid[g1];
  c.body2 = a.geom_bodyid[g2];
  if (a.margin_rule == MarginRule::Larger) {
    c.margin = std::max(a.geom_margin[g1], a.geom_margin[g2]);
    c.gap = std::max(a.geom_gap[g1], a.geom_gap[g2]);
  } else {
    c.margin = a.geom_margin[g1] + a.geom_margin[g2];
    c.gap = a.geom_gap[g1] + a.geom_gap[g2];
  }
  for (size_t p = 0; p < a.pair_geom1.size(); ++p) {  // a <pair>'s own margin and gap
    if ((a.pair_geom1[p] == con.geom1 && a.pair_geom2[p] == con.geom2) ||
        (a.pair_geom1[p] == con.geom2 && a.pair_geom2[p] == con.geom1)) {
      c.explicit_pair = true;
      c.margin = a.pair_margin[p];
      c.gap = a.pair_gap[p];
    }
  }
  c.dist = con.dist - con.includemargin;
  for (size_t k = 0; k < 3; ++k) {
    c.pos[k] = con.pos[k];
    c.normal[k] = con.frame[k];
  }
  c.condim = con.dim;
  c.friction = con.friction;
  c.solref = con.solref;
  c.solreffriction = con.solreffriction;
  c.solimp = con.solimp;
  c.force = con.normal_force;
  c.rows = contact_rows(con.dim, a.elliptic);
  c.quadratic = quadratic_rows(a.efc_force.data() + con.efc_address, c.rows,
                               a.elliptic && con.dim > 1, con.friction);
  return c;
}

bool listed(const ArrayContact& con) { return con.exclude == 0 && con.efc_address >= 0; }

}  // namespace

std::string arrays_misfit(const StateArrays& a) {
  const size_t nbody = a.body_names.size(), ngeom = a.geom_names.size();
  const size_t npair = a.pair_geom1.size(), njnt = a.jnt_bodyid.size();
  const auto nv = static_cast<size_t>(std::max(a.nv, 0));
  if (a.body_weldid.size() != nbody || a.body_parentid.size() != nbody ||
      a.body_mass.size() != nbody || a.body_inertia.size() != 3 * nbody ||
      a.body_invweight0.size() != 2 * nbody)
    return "the body arrays differ in length";
  if (a.jnt_type.size() != njnt) return "the joint arrays differ in length";
  if (a.geom_bodyid.size() != ngeom || a.geom_condim.size() != ngeom ||
      a.geom_contype.size() != ngeom || a.geom_conaffinity.size() != ngeom ||
      a.geom_friction.size() != 3 * ngeom || a.geom_margin.size() != ngeom ||
      a.geom_gap.size() != ngeom || a.geom_priority.size() != ngeom ||
      a.geom_solmix.size() != ngeom || a.geom_solref.size() != 2 * ngeom)
    return "the geom arrays differ in length";
  if (a.pair_geom2.size() != npair || a.pair_margin.size() != npair || a.pair_gap.size() != npair)
    return "the pair arrays differ in length";
  if (a.nv < 0 || a.qvel.size() != nv || a.qacc.size() != nv) return "qvel or qacc is not nv long";
  auto in = [](int i, size_t n) { return i >= 0 && static_cast<size_t>(i) < n; };
  for (const int b : a.geom_bodyid)
    if (!in(b, nbody)) return "a geom's body is out of range";
  for (const int b : a.jnt_bodyid)
    if (!in(b, nbody)) return "a joint's body is out of range";
  for (size_t p = 0; p < npair; ++p)
    if (!in(a.pair_geom1[p], ngeom) || !in(a.pair_geom2[p], ngeom))
      return "a pair's geom is out of range";
  for (const ArrayContact& c : a.contacts) {
    if (!in(c.geom1, ngeom) || !in(c.geom2, ngeom)) return "a contact's geom is out of range";
    if (c.dim < 1 || c.dim > 6) return "a contact's condim is not 1 to 6";
    if (listed(c) &&
        static_cast<size_t>(c.efc_address) + static_cast<size_t>(contact_rows(c.dim, a.elliptic)) >
            a.efc_force.size())
      return "a contact's constraint rows are out of range";
    for (const auto* jac : {&c.jac1, &c.jac2}) {
      for (const SparseRow& row : *jac) {
        if (row.index.size() != row.value.size()) return "a Jacobian row's lengths differ";
        for (size_t i = 0; i < row.index.size(); ++i)
          if (!in(row.index[i], nv) || (i > 0 && row.index[i] <= row.index[i - 1]))
            return "a Jacobian row's columns are out of range or order";
      }
    }
  }
  return "";
}

void read_state_arrays(const StateArrays& a, const SolveM& solve, ModelState& s) {
  read_bodies_and_geoms(a, s);
  s.nv = a.nv;
  s.qvel = a.qvel;
  s.qacc = a.qacc;
  for (size_t i = 0; i < a.qvel.size(); ++i) {
    s.speed = std::max(s.speed, std::abs(a.qvel[i]));
    s.accel = std::max(s.accel, std::abs(a.qacc[i]));
  }
  // Each listed contact's normal row, then (condim ≥ 3) its two tangent
  // rows; M⁻¹ times all of them in one call.
  std::vector<SparseRow> rows;
  for (const ArrayContact& con : a.contacts) {
    if (!listed(con)) continue;
    s.contacts.push_back(contact_fields(a, con));
    rows.push_back(SparseRow::of(frame_row(con, a.nv, con.frame.data())));
    if (con.dim >= 3) {
      rows.push_back(SparseRow::of(frame_row(con, a.nv, con.frame.data() + 3)));
      rows.push_back(SparseRow::of(frame_row(con, a.nv, con.frame.data() + 6)));
    }
  }
  const std::vector<SparseRow> solved = rows.empty() ? rows : solve(rows);
  size_t next = 0;
  for (StateContact& c : s.contacts) {
    c.jacobian = rows[next];
    c.solved = solved[next++];
    c.A = c.jacobian.dot(c.solved);
    if (c.condim < 3) continue;
    for (size_t axis = 0; axis < 2; ++axis) {
      c.tangent[axis] = rows[next];
      c.tangent_solved[axis] = solved[next++];
      c.A_t = std::max(c.A_t, c.tangent[axis].dot(c.tangent_solved[axis]));
    }
  }
}

}  // namespace contact2d::mujoco
