// `contact2d inspect` (mujoco/inspect.hpp).
#include "mujoco/inspect.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "benchmarks/impact.hpp"
#include "core/format.hpp"
#include "core/input_error.hpp"
#include "core/integrators.hpp"
#include "io/json.hpp"
#include "mujoco/bounce.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/model.hpp"
#include "mujoco/solref_tool.hpp"

namespace contact2d::mujoco {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kPi = 3.14159265358979323846;

std::string list_text(const double* v, int n) {
  std::string out;
  for (int i = 0; i < n; ++i) out += (i ? " " : "") + format_number(v[i]);
  return out;
}

// Element `id` of a model array of `width` numbers per element.
const double* element(const double* base, int id, int width) {
  return base + static_cast<std::ptrdiff_t>(id) * width;
}

// The solref, solimp, friction and condim mj_collideGeoms gives a geom pair
// (ipair ≥ 0: that explicit <pair>), then mj_assignRef / mj_assignImp.
void resolve_pair(const mjModel* m, int ipair, int g1, int g2, InspectRow& row) {
  if (ipair >= 0) {
    row.condim = m->pair_dim[ipair];
    std::copy_n(element(m->pair_friction, ipair, 5), 5, row.friction.begin());
    std::copy_n(element(m->pair_solref, ipair, mjNREF), mjNREF, row.solref.begin());
    std::copy_n(element(m->pair_solimp, ipair, mjNIMP), mjNIMP, row.solimp.begin());
  } else {
    const int p1 = m->geom_priority[g1], p2 = m->geom_priority[g2];
    if (p1 != p2) {
      const int gp = p1 > p2 ? g1 : g2;
      row.condim = m->geom_condim[gp];
      for (size_t i = 0; i < 3; ++i) row.friction[2 * i] = element(m->geom_friction, gp, 3)[i];
      std::copy_n(element(m->geom_solref, gp, mjNREF), mjNREF, row.solref.begin());
      std::copy_n(element(m->geom_solimp, gp, mjNIMP), mjNIMP, row.solimp.begin());
    } else {
      row.condim = std::max(m->geom_condim[g1], m->geom_condim[g2]);
      for (size_t i = 0; i < 3; ++i)
        row.friction[2 * i] =
            std::max(element(m->geom_friction, g1, 3)[i], element(m->geom_friction, g2, 3)[i]);
      const double s1 = m->geom_solmix[g1], s2 = m->geom_solmix[g2];
      double mix = 0.5;
      if (s1 >= mjMINVAL && s2 >= mjMINVAL)
        mix = s1 / (s1 + s2);
      else if (s1 < mjMINVAL && s2 >= mjMINVAL)
        mix = 0.0;
      else if (s1 >= mjMINVAL && s2 < mjMINVAL)
        mix = 1.0;
      const double* r1 = element(m->geom_solref, g1, mjNREF);
      const double* r2 = element(m->geom_solref, g2, mjNREF);
      const bool standard = r1[0] > 0.0 && r2[0] > 0.0;
      for (int i = 0; i < mjNREF; ++i)
        row.solref[static_cast<size_t>(i)] =
            standard ? mix * r1[i] + (1.0 - mix) * r2[i] : std::min(r1[i], r2[i]);
      const double* i1 = element(m->geom_solimp, g1, mjNIMP);
      const double* i2 = element(m->geom_solimp, g2, mjNIMP);
      for (int i = 0; i < mjNIMP; ++i)
        row.solimp[static_cast<size_t>(i)] = mix * i1[i] + (1.0 - mix) * i2[i];
    }
    row.friction[1] = row.friction[0];
    row.friction[3] = row.friction[4];
  }
  for (double& f : row.friction) f = std::max(mjMINMU, f);
  if (m->opt.enableflags & mjENBL_OVERRIDE) {
    for (int i = 0; i < mjNREF; ++i) row.solref[static_cast<size_t>(i)] = m->opt.o_solref[i];
    for (int i = 0; i < mjNIMP; ++i) row.solimp[static_cast<size_t>(i)] = m->opt.o_solimp[i];
  }
}

struct Context {
  const ModelState* s;
  Integrator integrator;
  bool pyramidal;
  std::optional<double> slope;
};

// The speed the bounces are computed at, m/s.
constexpr double kBounceSpeed = 1.0;

BounceRow bounce_row(const InspectRow& r) { return {r.K, r.B, r.solimp, r.normal_weight}; }

// Why no creep is printed under MuJoCo's noslip pass.
std::string noslip_note(int iterations) {
  return "not estimated: noslip_iterations = " + std::to_string(iterations) +
         " (MuJoCo's noslip pass re-solves the friction forces after the main solver, without "
         "their regulariser R_t = R/impratio that sets the viscous creep; it is not modelled)";
}

// What the main solver's friction advice leaves out under the noslip pass.
std::string noslip_caveat(int iterations) {
  return iterations > 0 ? " (the main solver's; noslip_iterations = " + std::to_string(iterations) +
                              ": MuJoCo's noslip pass re-solves the friction forces after it, "
                              "which is not modelled)"
                        : std::string();
}

// The friction rows' numbers and the creep at --slope (evaluate's last part).
void friction_and_creep(const Context& ctx, InspectRow& r) {
  const ModelState& s = *ctx.s;
  const double mu = r.friction[0];
  // The friction rows (MuJoCo's effective law of a contact with friction).
  r.impratio_cap = r.push = r.lift_off = kNaN;
  if (r.condim >= 3 && mu > 0.0 && moves_along_normal(r)) {
    // A friction row's step: its force f = (aref − J·a)/(A_t + R_t) with
    // aref = −B·v, R_t = R'/impratio, R' = (1 − d)/d·Â (·(1 + μ²) for the
    // pyramidal cone's edges), changes its slip by v·Δt·B·A_t/(A_t + R_t):
    // beyond v itself (the slip reverses, MuJoCo chatters) once
    // impratio > R'/(A_t·(Δt·B − 1)), and never when Δt·B ≤ 1. For a
    // small d this is generate's cap 1/(Δt·A_t·c) (mapping.cpp).
    const double shape = ctx.pyramidal ? 1.0 + mu * mu : 1.0;
    const double R = (1.0 - r.d_rest) / r.d_rest * r.inv_weight * shape;
    const double excess = s.timestep * r.B_friction - 1.0;
    if (r.A_t > 0.0 && excess > 0.0) r.impratio_cap = R / (r.A_t * excess);
    // The push law is exact as d·A/((1 − d)·Â) → 0 (solref's calibrated
    // contact: 4e-4 on a box, MuJoCo 1.8e-4 off it); at MuJoCo's default
    // d ≈ 0.9 the rows couple through A and it does not hold (11 % off).
    // The friction rows' damper sets it: c·B_friction/B (solreffriction).
    if (r.d_rest * r.A < 1e-2 * (1.0 - r.d_rest) * r.normal_weight) {
      const double c_t = r.B > 0.0 ? r.c * r.B_friction / r.B : r.c;
      r.push = mu * c_t;
      if (!ctx.pyramidal && std::isfinite(r.load) && c_t > 0.0)
        r.lift_off = r.load * (1.0 + mu * mu / std::max(mjMINVAL, s.impratio)) / (mu * c_t);
    }
  }
  r.creep = kNaN;
  r.creep_note.clear();
  if (ctx.slope) {
    const double th = *ctx.slope * kPi / 180.0;
    if (r.condim == 1) {
      r.creep_note = "condim 1, no friction: slides";
    } else if (std::tan(th) >= mu) {
      r.creep_note = "tanθ ≥ μ = " + format_number(mu) + ": slides (Coulomb)";
    } else if (ctx.pyramidal && std::tan(th) >= mu / (r.condim - 1)) {
      // Each edge row carries f/(2(condim − 1)) ± f_t/(2μ): one unloads at
      // f_t = μ·f/(condim − 1), and the solver leaves its quadratic zone.
      r.creep_note = "tanθ ≥ μ/(condim − 1) = " + format_number(mu / (r.condim - 1)) +
                     ": an edge of the pyramidal cone unloads; faster than the viscous creep "
                     "(slides at tanθ ≥ μ)";
    } else if (s.noslip_iterations > 0) {
      r.creep_note = noslip_note(s.noslip_iterations);
    } else if (std::isfinite(r.impratio_cap) && s.impratio > r.impratio_cap) {
      r.creep_note = "impratio " + format_number(s.impratio) + " is above " +
                     format_number(r.impratio_cap) +
                     ", where the friction rows' damper reverses a slip within one step: "
                     "MuJoCo chatters and creeps faster than the viscous formula";
    } else if (!std::isfinite(r.load)) {
      r.creep_note = "no static load known (not in contact now)";
    } else if (!(r.load > 0.0)) {
      r.creep_note = "carries no load at rest";
    } else if (th == 0.0) {
      r.creep = 0.0;
    } else {
      const double p = static_penetration(r.solimp, r.K, r.normal_weight, r.load * std::cos(th));
      const double dd = mujoco_impedance(r.solimp, -p);
      const double shape = ctx.pyramidal ? 1.0 + mu * mu : 1.0;
      r.creep = r.load * std::sin(th) * (1.0 - dd) * r.inv_weight * shape /
                (std::max(mjMINVAL, s.impratio) * r.B_friction * dd);
    }
  }
}

// The friction rows' B: solreffriction's where MuJoCo uses it (getsolparam,
// mj_makeImpedance: an elliptic contact's friction rows, when it is not
// 0 0; its two numbers of one sign, else MuJoCo warns and drops it; refsafe
// on a standard-form timeconst), else solref's. After r.B and r.dmax.
void friction_reference(const ModelState& s, InspectRow& r, std::vector<std::string>& warnings,
                        const std::string& label) {
  r.B_friction = r.B;
  r.friction_ref = false;
  std::array<double, 2> ref = r.solreffriction;
  if (ref[0] == 0.0 && ref[1] == 0.0) return;
  if ((ref[0] > 0.0) != (ref[1] > 0.0)) {
    warnings.push_back(label + ": solreffriction " + format_number(ref[0]) + " " +
                       format_number(ref[1]) +
                       " mixes the standard and direct forms: MuJoCo drops it and the friction "
                       "rows keep solref's damper");
    return;
  }
  if (!s.elliptic || r.condim < 3) return;  // only an elliptic cone's friction rows read it
  if (ref[0] > 0.0 && s.refsafe) ref[0] = std::max(ref[0], 2.0 * s.timestep);
  r.friction_ref = true;
  r.B_friction = ref[1] > 0.0 ? 2.0 / std::max(mjMINVAL, r.dmax * ref[0])
                              : -ref[1] / std::max(mjMINVAL, r.dmax);
}

// Everything that follows from solref, solimp, condim, friction, A, Â and the load.
void evaluate(const Context& ctx, InspectRow& r, std::vector<std::string>& warnings,
              const std::string& label) {
  const ModelState& s = *ctx.s;
  std::array<double, 2> ref = r.solref;
  if ((ref[0] > 0.0) != (ref[1] > 0.0)) {
    warnings.push_back(label + ": solref " + format_number(ref[0]) + " " + format_number(ref[1]) +
                       " mixes the standard and direct forms: MuJoCo replaces it with its "
                       "default 0.02 1");
    ref = {0.02, 1.0};
  }
  r.timeconst_used = 0.0;
  r.refsafe_changes = false;
  if (ref[0] > 0.0) {
    if (s.refsafe && ref[0] < 2.0 * s.timestep) {
      r.refsafe_changes = true;
      ref[0] = 2.0 * s.timestep;
    }
    r.timeconst_used = ref[0];
  }
  r.dmax = std::clamp(r.solimp[1], mjMINIMP, mjMAXIMP);
  r.K = ref[0] > 0.0 ? 1.0 / std::max(mjMINVAL, r.dmax * r.dmax * ref[0] * ref[0] * ref[1] * ref[1])
                     : -ref[0] / std::max(mjMINVAL, r.dmax * r.dmax);
  r.B = ref[1] > 0.0 ? 2.0 / std::max(mjMINVAL, r.dmax * ref[0])
                     : -ref[1] / std::max(mjMINVAL, r.dmax);
  friction_reference(s, r, warnings, label);
  r.inv_weight = s.body_invweight0[2 * static_cast<size_t>(r.body1)] +
                 s.body_invweight0[2 * static_cast<size_t>(r.body2)];
  r.motion_scale = r.inv_weight;
  for (const int b : {r.body1, r.body2}) {
    const double m = s.body_mass[static_cast<size_t>(b)];
    if (s.body_weld[static_cast<size_t>(b)] != 0 && m > 0.0)
      r.motion_scale = std::max(r.motion_scale, 1.0 / m);
  }
  const double mu = r.friction[0];
  r.phi = 1.0;
  if (ctx.pyramidal && r.condim > 1)
    r.phi = mu * mu * (1.0 + mu * mu) / ((r.condim - 1) * std::max(mjMINVAL, s.impratio));
  r.normal_weight = r.inv_weight * r.phi;
  if (!r.A_measured) r.A = r.inv_weight;
  r.d_now = mujoco_impedance(r.solimp, r.dist);
  if (std::isfinite(r.load)) {
    r.penetration = static_penetration(r.solimp, r.K, r.normal_weight, r.load);
    r.d_rest = mujoco_impedance(r.solimp, -r.penetration);
    // Every row at aref/R only in the quadratic zone: otherwise MuJoCo's
    // normal force is not the one the depth balances.
    if (r.active && r.quadratic < r.rows) {
      r.depth_note = std::to_string(r.rows - r.quadratic) + " of its " + std::to_string(r.rows) +
                     " constraint rows are out of the solver's quadratic zone (" +
                     (r.condim == 1 ? "it pushes nothing"
                      : s.elliptic  ? "on the friction cone's surface"
                                    : "a pyramid edge unloaded") +
                     ": it slips, or lifts): its depth does not follow its load";
      r.penetration = kNaN;
    }
  } else {
    r.penetration = kNaN;
    r.d_rest = mujoco_impedance(r.solimp, 0.0);
  }
  auto regime = [&](double dd, double& k, double& c, double& omega, double& zeta) {
    const double denominator = dd * r.A + (1.0 - dd) * r.normal_weight;
    k = dd * dd * r.K / denominator;
    c = dd * r.B / denominator;
    omega = std::sqrt(r.A * k);
    zeta = r.A * c / (2.0 * omega);
  };
  regime(r.d_rest, r.k, r.c, r.omega, r.zeta);
  // A contact not yet at rest: in the solver's quadratic zone MuJoCo's
  // force is f = (aref − J·qacc)/R with aref = −B·v + K·d·p, so the depth
  // that force sets differs from the rest depth of that load by the part
  // (B·v + J·qacc)/R, R = (1 − d)/d·Â at the depth now. Above 1 % of the
  // load, MuJoCo's depth now is not yet the rest depth (a lightly loaded
  // particle in a settling pile: a few percent).
  if (r.active && r.depth_note.empty() && std::isfinite(r.penetration) && r.load > 0.0) {
    const double R = (1.0 - r.d_now) / r.d_now * r.normal_weight;
    r.unsettled = std::abs(r.B * r.normal_speed + r.normal_accel) / R;
    if (r.unsettled > 0.01 * r.load)
      r.depth_note = "still moving along its normal (v = " + format_number(r.normal_speed) +
                     " m/s, a = " + format_number(r.normal_accel) +
                     " m/s²): the motion's part of MuJoCo's force, (B·v + J·qacc)/R = " +
                     format_number(r.unsettled) + " N, is " + format_number(r.unsettled / r.load) +
                     "× its load, so MuJoCo's depth now is not yet this one (a longer --settle)";
  }
  double k_max = 0.0, c_max = 0.0;
  r.d_stiff = std::max(std::clamp(r.solimp[0], mjMINIMP, mjMAXIMP), r.dmax);
  regime(r.d_stiff, k_max, c_max, r.omega_max, r.zeta_max);
  r.omega_dt = r.omega_max * s.timestep;
  r.limit = stability_limit(ctx.integrator, r.zeta_max);
  r.restitution = benchmarks::kelvin_voigt_restitution(r.zeta);
  r.restitution_dt = kNaN;
  if (moves_along_normal(r)) {
    const Bounce b = mujoco_bounce({bounce_row(r)}, Eigen::MatrixXd::Constant(1, 1, r.A),
                                   s.timestep, s.integrator == "RK4", kBounceSpeed);
    if (b.left) r.restitution_dt = b.restitution;
  }
  if (!moves_along_normal(r)) {  // the joints cannot move the contact along its normal
    r.zeta = r.zeta_max = r.limit = r.restitution = kNaN;
    r.omega = r.omega_max = r.omega_dt = 0.0;
  }

  friction_and_creep(ctx, r);
}

// MuJoCo's Euler and implicit integrators treat contacts as semi-implicit
// Euler does (core stability_limit); RK4 has its own limit.
Integrator integrator_of(const ModelState& s) {
  return s.integrator == "RK4" ? Integrator::RK4 : Integrator::SemiImplicitEuler;
}

// Where the contact is stiffest, in words.
std::string stiffest(const InspectRow& r) {
  return r.d_stiff > r.dmax ? "d0 = " + format_number(r.d_stiff) +
                                  ", the stiffest (solimp's d0 is above d_max: the impedance "
                                  "falls with depth)"
                            : std::string("d_max");
}

std::string label_of(const InspectRow& r) {
  return (r.active ? "contact " + std::to_string(r.contact) : std::string("pair")) + " (" +
         r.geom1_name + " – " + r.geom2_name + ")";
}

void fill_names(const ModelState& s, InspectRow& r) {
  r.body1 = s.geom_body[static_cast<size_t>(r.geom1)];
  r.body2 = s.geom_body[static_cast<size_t>(r.geom2)];
  r.geom1_name = s.geom_names[static_cast<size_t>(r.geom1)];
  r.geom2_name = s.geom_names[static_cast<size_t>(r.geom2)];
  r.body1_name = s.body_names[static_cast<size_t>(r.body1)];
  r.body2_name = s.body_names[static_cast<size_t>(r.body2)];
}

// Both geom types are plane or height field: mj_collision has no function.
bool no_collision_function(const mjModel* m, int g1, int g2) {
  auto flat = [&](int gi) {
    return m->geom_type[gi] == mjGEOM_PLANE || m->geom_type[gi] == mjGEOM_HFIELD;
  };
  return flat(g1) && flat(g2);
}

// mj_contactFilter: 1 discards the pair.
bool filtered(const mjModel* m, int g1, int g2) {
  const int w1 = m->body_weldid[m->geom_bodyid[g1]], w2 = m->body_weldid[m->geom_bodyid[g2]];
  const int p1 = m->body_weldid[m->body_parentid[w1]], p2 = m->body_weldid[m->body_parentid[w2]];
  if (!(m->geom_contype[g1] & m->geom_conaffinity[g2]) &&
      !(m->geom_contype[g2] & m->geom_conaffinity[g1]))
    return true;
  if (w1 == w2) return true;
  const bool filterparent = !(m->opt.disableflags & mjDSBL_FILTERPARENT) && w1 && w2;
  return filterparent && (w1 == p2 || w2 == p1);
}

void order_by_type(const mjModel* m, int& g1, int& g2) {
  if (m->geom_type[g1] > m->geom_type[g2]) std::swap(g1, g2);
}

// The closest points of a geom pair not in contact: MuJoCo's own collision
// function for the two geom types (mjCOLLISIONFUNC, what mj_collision calls
// for the pair) at the state `d` holds, with a margin that reaches them (the
// centres' distance and both bounding radii); the contacts of least
// distance (a capsule parallel to a plane has one at each end). No model
// copy and no mj_forward per pair: the cost is the pair's narrow phase.
struct ClosestPoints {
  std::array<double, 3> pos{}, normal{};
  double dist = 0.0;
};
std::vector<ClosestPoints> closest_points(const mjModel* m, const mjData* d, int g1, int g2) {
  const mjfCollision collide = mjCOLLISIONFUNC[m->geom_type[g1]][m->geom_type[g2]];
  if (!collide) return {};
  double between[3];
  mju_sub3(between, d->geom_xpos + 3 * static_cast<std::ptrdiff_t>(g1),
           d->geom_xpos + 3 * static_cast<std::ptrdiff_t>(g2));
  const double reach = mju_norm3(between) + m->geom_rbound[g1] + m->geom_rbound[g2] + 1.0;
  std::array<mjContact, mjMAXCONPAIR> found{};
  const int n = collide(m, d, found.data(), g1, g2, reach);
  std::vector<ClosestPoints> all;
  double least = INFINITY;
  for (int i = 0; i < n && i < mjMAXCONPAIR; ++i) {
    const mjContact& con = found[static_cast<size_t>(i)];
    ClosestPoints p;
    for (size_t k = 0; k < 3; ++k) {
      p.pos[k] = con.pos[k];
      p.normal[k] = con.frame[k];
    }
    p.dist = con.dist;
    least = std::min(least, p.dist);
    all.push_back(p);
  }
  std::vector<ClosestPoints> out;
  for (const ClosestPoints& p : all)
    if (p.dist <= least + 1e-9 * std::max(1.0, std::abs(least))) out.push_back(p);
  return out;
}

// The stages of inspect(), in order: the contacts, their static loads, the
// pairs, the warnings.

// The contacts MuJoCo has at this state, into rep.contacts, each with
// MuJoCo's own normal force as its load.
void collect_contacts(const ModelState& s, InspectReport& rep) {
  for (size_t i = 0; i < s.contacts.size(); ++i) {
    const StateContact& con = s.contacts[i];
    InspectRow r;
    r.active = true;
    r.contact = static_cast<int>(i);
    r.geom1 = con.geom1;
    r.geom2 = con.geom2;
    fill_names(s, r);
    r.source = con.explicit_pair ? "explicit <pair>" : "default collision";
    r.dist = con.dist;
    r.pos = con.pos;
    r.normal = con.normal;
    r.condim = con.condim;
    r.friction = con.friction;
    r.solref = con.solref;
    r.solreffriction = con.solreffriction;
    r.solimp = con.solimp;
    r.A = con.A;
    r.A_t = con.A_t;
    r.A_measured = true;
    r.force = con.force;
    r.rows = con.rows;
    r.normal_speed = con.jacobian.dot(s.qvel);
    r.normal_accel = con.jacobian.dot(s.qacc);
    r.quadratic = con.quadratic;
    r.load = std::max(0.0, con.force);
    rep.contacts.push_back(r);
  }
  // A friction row's slip couples to the other rows of its body (a box's
  // corners yawing together): each contact's A_t is at least its bodies'
  // coupled one, which sets the impratio cap.
  std::map<int, std::vector<int>> by_body;
  for (size_t i = 0; i < s.contacts.size(); ++i)
    for (const int b : {s.contacts[i].body1, s.contacts[i].body2})
      if (s.body_weld[static_cast<size_t>(b)] != 0) by_body[b].push_back(static_cast<int>(i));
  std::map<int, double> coupled;
  for (const auto& [b, list] : by_body) coupled[b] = coupled_tangential_inverse_mass(s, list);
  for (InspectRow& r : rep.contacts)
    for (const int b : {r.body1, r.body2})
      if (coupled.count(b) != 0) r.A_t = std::max(r.A_t, coupled[b]);
}

// The least-squares loads: Jₙᵀ·f = qfrc_bias (qvel = 0) over every
// contact, minimum norm — the normal forces alone holding the model at this
// configuration. An estimate: it ignores the friction forces and the
// joints' own limits and springs, and splits a statically indeterminate load
// by least norm, not by stiffness (MuJoCo's split). Sets rep.balanced and
// rep.residual; the loads only when `use` (--loads estimate).
void estimate_loads(const ModelState& s, InspectReport& rep, bool use) {
  const int nc = static_cast<int>(s.contacts.size());
  if (nc == 0) return;
  Eigen::MatrixXd jt = Eigen::MatrixXd::Zero(s.nv, nc);
  Eigen::VectorXd b(s.nv);
  for (int i = 0; i < s.nv; ++i) b(i) = s.bias[static_cast<size_t>(i)];
  for (int c = 0; c < nc; ++c) {
    const SparseRow& row = s.contacts[static_cast<size_t>(c)].jacobian;
    for (size_t k = 0; k < row.index.size(); ++k) jt(row.index[k], c) = row.value[k];
  }
  const Eigen::VectorXd f = jt.completeOrthogonalDecomposition().solve(b);
  const double scale = b.norm();
  rep.residual = scale > 0.0 ? (jt * f - b).norm() / scale : 0.0;
  rep.balanced =
      rep.residual < 1e-6 && f.minCoeff() >= -1e-9 * std::max(1.0, f.cwiseAbs().maxCoeff());
  for (int c = 0; c < nc; ++c) {
    InspectRow& r = rep.contacts[static_cast<size_t>(c)];
    r.estimate = std::max(0.0, f(c));
    if (use) r.load = r.estimate;
  }
}

// Every geom pair that can collide (--pairs), into rep.pairs.
void collect_pairs(const Context& ctx, const mjModel* m, mjData* d, InspectReport& rep,
                   const std::function<void(size_t, size_t)>& progress) {
  rep.pairs_listed = true;
  auto add = [&](int ipair, int g1, int g2) {
    InspectRow r;
    order_by_type(m, g1, g2);
    r.geom1 = g1;
    r.geom2 = g2;
    fill_names(*ctx.s, r);
    r.source = ipair >= 0 ? "explicit <pair>" : "default collision";
    resolve_pair(m, ipair, g1, g2, r);
    r.load = kNaN;
    for (const InspectRow& c : rep.contacts) {
      if (!((c.geom1 == g1 && c.geom2 == g2) || (c.geom1 == g2 && c.geom2 == g1))) continue;
      if (r.contacts_now++ == 0) {
        r.A = c.A;
        r.A_measured = true;
        r.load = c.load;
        r.dist = c.dist;
        r.pos = c.pos;
        r.normal = c.normal;
      }
    }
    if (r.contacts_now == 0) {
      // Of equally close points, the one the joints move most easily (the largest A).
      for (const ClosestPoints& near : closest_points(m, d, g1, g2)) {
        const double a =
            inverse_mass(m, d, normal_jacobian(m, d, r.body1, r.body2, near.pos, near.normal));
        if (r.closest && !(a > r.A)) continue;
        r.A = a;
        r.A_measured = r.closest = true;
        r.dist = near.dist;
        r.pos = near.pos;
        r.normal = near.normal;
      }
    }
    evaluate(ctx, r, rep.warnings, label_of(r));
    rep.pairs.push_back(r);
  };
  // mj_collision returns at once when contacts or constraints are disabled.
  const bool disabled = (m->opt.disableflags & (mjDSBL_CONSTRAINT | mjDSBL_CONTACT)) != 0;
  const bool use_pairs = !disabled && m->opt.collision != mjCOL_DYNAMIC;
  const bool use_dynamic = !disabled && m->opt.collision != mjCOL_PAIR && m->nbody >= 2;
  // The candidates first (their count is the progress's total), then each.
  struct Candidate {
    int ipair, g1, g2;
  };
  std::vector<Candidate> candidates;
  auto wanted = [&](int g1, int g2) {
    if (rep.body.empty()) return true;
    for (const int g : {g1, g2})
      if (ctx.s->body_names[static_cast<size_t>(m->geom_bodyid[g])] == rep.body) return true;
    return false;
  };
  if (use_pairs)
    for (int p = 0; p < m->npair; ++p)
      if (wanted(m->pair_geom1[p], m->pair_geom2[p]))
        candidates.push_back({p, m->pair_geom1[p], m->pair_geom2[p]});
  if (use_dynamic) {
    for (int b1 = 0; b1 < m->nbody; ++b1) {
      for (int b2 = b1 + 1; b2 < m->nbody; ++b2) {
        const int signature = ((b1 + 1) << 16) + (b2 + 1);
        bool excluded = false;
        for (int e = 0; e < m->nexclude; ++e) excluded |= m->exclude_signature[e] == signature;
        if (excluded) continue;
        for (int g1 = m->body_geomadr[b1]; g1 < m->body_geomadr[b1] + m->body_geomnum[b1]; ++g1) {
          for (int g2 = m->body_geomadr[b2]; g2 < m->body_geomadr[b2] + m->body_geomnum[b2]; ++g2) {
            bool explicit_pair = false;
            for (int p = 0; use_pairs && p < m->npair; ++p)
              explicit_pair |= (m->pair_geom1[p] == g1 && m->pair_geom2[p] == g2) ||
                               (m->pair_geom1[p] == g2 && m->pair_geom2[p] == g1);
            if (explicit_pair || no_collision_function(m, g1, g2) || filtered(m, g1, g2) ||
                !wanted(g1, g2))
              continue;
            candidates.push_back({-1, g1, g2});
          }
        }
      }
    }
  }
  for (size_t i = 0; i < candidates.size(); ++i) {
    if (progress && i % 1024 == 0) progress(i, candidates.size());
    add(candidates[i].ipair, candidates[i].g1, candidates[i].g2);
  }
  if (progress) progress(candidates.size(), candidates.size());
}

// The warnings on the rows and on the model, then MuJoCo's own messages.
void add_warnings(const ModelState& s, const InspectOptions& options, InspectReport& rep) {
  const size_t nc = rep.contacts.size();
  auto warn_rows = [&](const std::vector<InspectRow>& list) {
    for (const InspectRow& r : list) {
      const std::string label = label_of(r);
      if (moves_along_normal(r) && !(r.omega_dt < r.limit))
        rep.warnings.push_back(label + ": ω·Δt = " + format_number(r.omega_dt) + " at " +
                               stiffest(r) + " exceeds " + rep.integrator + "'s limit " +
                               format_number(r.limit) + " (ζ = " + format_number(r.zeta_max) +
                               "): unstable; a timestep below " +
                               format_number(r.limit / r.omega_max) + " s is stable");
      if (std::isfinite(r.impratio_cap) && rep.impratio > r.impratio_cap)
        rep.warnings.push_back(label + ": impratio " + format_number(rep.impratio) + " exceeds " +
                               format_number(r.impratio_cap) +
                               ", above which the friction rows' damper reverses a slip within "
                               "one step (Δt·B·A_t/(A_t + R/impratio) > 1): MuJoCo chatters" +
                               noslip_caveat(s.noslip_iterations));
      if (r.refsafe_changes)
        rep.warnings.push_back(
            label + ": refsafe raises the solref timeconst " + format_number(r.solref[0]) +
            " s to 2·timestep = " + format_number(r.timeconst_used) + " s: K is " +
            format_number(r.solref[0] * r.solref[0] / (r.timeconst_used * r.timeconst_used)) +
            "× and B " + format_number(r.solref[0] / r.timeconst_used) +
            "× what the timeconst asks");
      if (r.phi > 1.0)
        rep.warnings.push_back(
            label + ": pyramidal cone with μ = " + format_number(r.friction[0]) + ", condim " +
            std::to_string(r.condim) + ": the normal sees Â·μ²(1 + μ²)/((condim − 1)·impratio) = " +
            format_number(r.phi) + "·Â, a contact about " + format_number(r.phi) +
            "× softer than without friction that sinks deeper (cone=\"elliptic\" "
            "or impratio ≥ " +
            format_number(r.friction[0] * r.friction[0] * (1.0 + r.friction[0] * r.friction[0]) /
                          (r.condim - 1)) +
            " removes it)");
    }
  };
  warn_rows(rep.contacts);
  warn_rows(rep.pairs);
  bool friction = false;
  for (const auto* list : {&rep.contacts, &rep.pairs})
    for (const InspectRow& r : *list) friction |= r.condim > 1;
  if (friction && rep.impratio < 1.0)
    rep.warnings.push_back("impratio = " + format_number(rep.impratio) +
                           " < 1: MuJoCo gives the friction rows R_t = R/impratio, so friction "
                           "is " +
                           format_number(1.0 / rep.impratio) +
                           "× softer than the normal (a body creeps that much faster" +
                           noslip_caveat(s.noslip_iterations) +
                           "); impratio > 1 makes friction stiffer, not softer");
  std::map<int, std::pair<double, double>> masses;  // body → (min, max) of 1/A
  for (const InspectRow& r : rep.contacts) {
    for (int b : {r.body1, r.body2}) {
      if (s.body_weld[static_cast<size_t>(b)] == 0 || !moves_along_normal(r)) continue;
      auto [it, fresh] = masses.emplace(b, std::make_pair(1.0 / r.A, 1.0 / r.A));
      if (!fresh) {
        it->second.first = std::min(it->second.first, 1.0 / r.A);
        it->second.second = std::max(it->second.second, 1.0 / r.A);
      }
    }
  }
  for (const auto& [b, range] : masses)
    if (range.second > 10.0 * range.first)
      rep.warnings.push_back("body " + s.body_names[static_cast<size_t>(b)] +
                             ": its effective mass differs " +
                             format_number(range.second / range.first) + "× across its contacts (" +
                             format_number(range.first) + " to " + format_number(range.second) +
                             " kg): the same solref gives each a different k and c");
  if (options.estimate_loads && !rep.balanced && nc > 0)
    rep.warnings.push_back(
        "the contacts' normal forces alone do not hold the model at rest under gravity "
        "(relative residual " +
        format_number(rep.residual) +
        "): the estimated loads are a least-squares share, and the penetrations follow them");
  if (nc > 0 && !rep.at_rest)
    rep.warnings.push_back(
        "the model is not at rest (largest |qvel| " + format_number(rep.speed) + ", |qacc| " +
        format_number(rep.accel) + "; at rest: ≤ " + format_number(kRestSpeed) + " and ≤ " +
        format_number(kRestAccel) +
        (rep.settled > 0.0 ? " after " + format_number(rep.settled) + " s of settling"
                           : std::string()) +
        "): the loads are MuJoCo's forces at this instant, not its rest loads, and the rest "
        "depths follow them" +
        (rep.settled > 0.0 ? "; a longer --settle may bring it to rest"
                           : "; --settle SECONDS lets MuJoCo bring it to rest"));
  if (!s.disabled.empty())
    rep.warnings.push_back("the model disables " + s.disabled +
                           " (<option><flag>): MuJoCo makes no contacts at all");
  for (const std::string& w : s.messages) rep.warnings.push_back("MuJoCo: " + w);
}

bool involves(const InspectRow& r, const std::string& body) {
  return r.body1_name == body || r.body2_name == body;
}

// A warning about one of the rows kept (it starts with the row's label).
bool mentions_body(const std::string& warning, const std::vector<InspectRow>& rows) {
  for (const InspectRow& r : rows)
    if (warning.rfind(label_of(r), 0) == 0) return true;
  return false;
}

// Per moving body: its contacts, their loads, depths, effective masses and
// how close the stiffest is to the integrator's limit.
std::vector<BodySummary> summarize(const ModelState& s, const std::vector<InspectRow>& rows) {
  std::map<int, BodySummary> by_body;
  for (const InspectRow& r : rows) {
    for (const int b : {r.body1, r.body2}) {
      if (s.body_weld[static_cast<size_t>(b)] == 0) continue;  // the world and what is welded to it
      auto [it, fresh] = by_body.emplace(b, BodySummary{});
      BodySummary& sum = it->second;
      if (fresh) {
        sum.name = s.body_names[static_cast<size_t>(b)];
        sum.deepest = kNaN;
        sum.mass_min = INFINITY;
        sum.mass_max = 0.0;
      }
      ++sum.contacts;
      if (std::isfinite(r.load)) sum.load += r.load;
      if (std::isfinite(r.penetration))
        sum.deepest =
            std::isfinite(sum.deepest) ? std::max(sum.deepest, r.penetration) : r.penetration;
      if (moves_along_normal(r)) {
        sum.mass_min = std::min(sum.mass_min, 1.0 / r.A);
        sum.mass_max = std::max(sum.mass_max, 1.0 / r.A);
        if (r.limit > 0.0) sum.stability = std::max(sum.stability, r.omega_dt / r.limit);
      }
    }
  }
  std::vector<BodySummary> out;
  for (auto& [b, sum] : by_body) {
    if (!std::isfinite(sum.mass_min)) sum.mass_min = sum.mass_max = kNaN;
    out.push_back(sum);
  }
  return out;
}

// Each contact alone, then each body's contacts together, as MuJoCo steps
// them at the model's timestep (bounce.hpp).
void add_bounces(const ModelState& s, InspectReport& rep) {
  const bool rk4 = s.integrator == "RK4";
  for (BodySummary& body : rep.bodies) {
    body.bounce = body.bounce_spread = kNaN;
    std::vector<const InspectRow*> rows;
    for (const InspectRow& r : rep.contacts)
      if ((r.body1_name == body.name || r.body2_name == body.name) && moves_along_normal(r))
        rows.push_back(&r);
    if (rows.empty()) continue;
    const auto n = static_cast<Eigen::Index>(rows.size());
    Eigen::MatrixXd coupling(n, n);
    std::vector<BounceRow> bounce_rows;
    for (Eigen::Index i = 0; i < n; ++i) {
      const StateContact& ci =
          s.contacts[static_cast<size_t>(rows[static_cast<size_t>(i)]->contact)];
      for (Eigen::Index j = 0; j < n; ++j)
        coupling(i, j) = ci.jacobian.dot(
            s.contacts[static_cast<size_t>(rows[static_cast<size_t>(j)]->contact)].solved);
      bounce_rows.push_back(bounce_row(*rows[static_cast<size_t>(i)]));
    }
    const Bounce b = mujoco_bounce(bounce_rows, coupling, s.timestep, rk4, kBounceSpeed);
    if (!b.left) continue;
    body.bounce = b.restitution;
    body.bounce_spread = b.spread;
  }
}

// Each moving kinematic tree's weight against what its contacts with the
// rest push it up by (TreeLoad).
std::vector<TreeLoad> tree_loads(const ModelState& s, const std::vector<InspectRow>& rows) {
  const size_t nbody = s.body_mass.size();
  std::vector<int> root(nbody, 0);
  for (size_t b = 1; b < nbody; ++b) {
    const int parent = s.body_parent[b];
    root[b] = parent == 0 ? static_cast<int>(b) : root[static_cast<size_t>(parent)];
  }
  const double g = std::sqrt(s.gravity[0] * s.gravity[0] + s.gravity[1] * s.gravity[1] +
                             s.gravity[2] * s.gravity[2]);
  std::map<int, TreeLoad> trees;
  for (size_t b = 1; b < nbody; ++b) {
    const auto top = static_cast<size_t>(root[b]);
    if (s.body_weld[top] == 0) continue;  // welded to the world: it does not move
    auto [it, fresh] = trees.emplace(root[b], TreeLoad{});
    TreeLoad& t = it->second;
    if (fresh) {
      t.root = s.body_names[top];
      t.free = s.body_joints[top].rfind("free", 0) == 0;
    }
    ++t.bodies;
    t.mass += s.body_mass[b];
  }
  for (auto& [r, t] : trees) t.weight = t.mass * g;
  if (g > 0.0)
    for (const InspectRow& row : rows) {
      const int t1 = root[static_cast<size_t>(row.body1)],
                t2 = root[static_cast<size_t>(row.body2)];
      if (t1 == t2 || !std::isfinite(row.load)) continue;  // inside one tree: no support
      double up = 0.0;                                     // n·up
      for (size_t i = 0; i < 3; ++i) up -= row.normal[i] * s.gravity[i] / g;
      if (auto it = trees.find(t2); it != trees.end()) {
        it->second.support += row.load * up;
        ++it->second.contacts;
      }
      if (auto it = trees.find(t1); it != trees.end()) {
        it->second.support -= row.load * up;
        ++it->second.contacts;
      }
    }
  std::vector<TreeLoad> out;
  out.reserve(trees.size());
  for (auto& [r, t] : trees) out.push_back(t);
  return out;
}

// The report's contacts from the state: MuJoCo's loads (or the estimate),
// then everything that follows from each contact's parameters.
InspectReport begin_report(const ModelState& s, const InspectOptions& options) {
  if (options.slope && !(*options.slope >= 0.0 && *options.slope < 90.0))
    throw InputError("--slope " + format_number(*options.slope) + ": must be in [0, 90) degrees");
  InspectReport rep;
  rep.path = options.path;
  rep.key = options.key;
  rep.slope = options.slope;
  rep.version = s.version;
  rep.load_warning = s.load_warning;
  rep.integrator = s.integrator;
  rep.dt = s.timestep;
  rep.cone = s.elliptic ? "elliptic" : "pyramidal";
  rep.impratio = s.impratio;
  rep.noslip_iterations = s.noslip_iterations;
  rep.gravity = s.gravity;
  rep.refsafe_enabled = s.refsafe;
  rep.settled = s.settled;
  rep.speed = s.speed;
  rep.accel = s.accel;
  rep.at_rest = at_rest(s);
  rep.loads_estimated = options.estimate_loads;
  collect_contacts(s, rep);
  estimate_loads(s, rep, options.estimate_loads);
  const Context ctx{&s, integrator_of(s), !s.elliptic, options.slope};
  for (InspectRow& r : rep.contacts) evaluate(ctx, r, rep.warnings, label_of(r));
  rep.trees = tree_loads(s, rep.contacts);
  if (!options.body.empty()) {
    if (std::find(s.body_names.begin(), s.body_names.end(), printable_name(options.body)) ==
        s.body_names.end())
      throw InputError("--body " + printable_name(options.body) + ": no body of that name in " +
                       options.path);
    rep.body = printable_name(options.body);
    // The least-squares loads above used every contact; only the listing is filtered.
    rep.contacts.erase(std::remove_if(rep.contacts.begin(), rep.contacts.end(),
                                      [&](const InspectRow& r) { return !involves(r, rep.body); }),
                       rep.contacts.end());
    std::vector<std::string> kept;
    for (const std::string& w : rep.warnings)
      if (mentions_body(w, rep.contacts)) kept.push_back(w);
    rep.warnings = kept;
  }
  rep.bodies = summarize(s, rep.contacts);
  add_bounces(s, rep);
  return rep;
}

StateRequest state_request(const InspectOptions& options) {
  StateRequest request;
  request.path = options.path;
  request.key = options.key;
  request.settle = options.settle;
  return request;
}

}  // namespace

InspectReport inspect_state(const ModelState& state, const InspectOptions& options) {
  if (options.pairs)
    throw InputError(
        "--pairs: lists pairs with MuJoCo 2.2.2's collision functions; run it "
        "without --engine mujoco3");
  InspectReport rep = begin_report(state, options);
  add_warnings(state, options, rep);
  return rep;
}

InspectReport inspect(const InspectOptions& options) {
  if (options.slope && !(*options.slope >= 0.0 && *options.slope < 90.0))
    throw InputError("--slope " + format_number(*options.slope) + ": must be in [0, 90) degrees");
  LoadedState loaded = load_model_state(state_request(options));
  const ModelState& s = loaded.state;
  InspectReport rep = begin_report(s, options);
  if (options.pairs) {
    // The probes' own messages are not the model's (a collision function
    // at a margin raised to reach across the gap): kept off the terminal
    // and MUJOCO_LOG.TXT, and an mju_error becomes an exception.
    std::vector<std::string> messages;
    WarningCapture capture(messages);
    const Context ctx{&s, integrator_of(s), !s.elliptic, options.slope};
    collect_pairs(ctx, loaded.model.get(), loaded.data.get(), rep, options.progress);
  }
  add_warnings(s, options, rep);
  return rep;
}

namespace {

std::string state_name(const InspectReport& rep) {
  std::string out = rep.key.empty() ? "qpos0" : "keyframe " + rep.key;
  if (rep.settled > 0.0)
    out += " settled " + format_number(rep.settled) + " s (" +
           (rep.at_rest ? "at rest" : "not at rest") + ": largest |qvel| " +
           format_number(rep.speed) + ", |qacc| " + format_number(rep.accel) + ")";
  return out;
}

// What to try when a state has no contacts.
std::string no_contacts_hint(const InspectReport& rep) {
  std::string out;
  if (rep.settled <= 0.0)
    out +=
        "--settle SECONDS lets MuJoCo drop the model onto what it rests on (a few seconds; a "
        "body that creeps on its friction takes longer: Debian's humanoid sample is at rest "
        "after about 50 s)";
  else
    out += "after " + format_number(rep.settled) +
           " s of settling nothing touches (the model may fly, hang, or fall past everything: "
           "a longer --settle, or --key)";
  out +=
      "; --key NAME inspects a keyframe; --pairs lists every geom pair that can collide, "
      "with its numbers at the closest points";
  return out;
}

// Columns padded to their widest cell (UTF-8 counted by code points),
// two spaces apart, each line indented by two.
std::string text_table(const std::vector<std::vector<std::string>>& rows) {
  auto width = [](const std::string& text) {
    size_t n = 0;
    for (const char ch : text) n += (static_cast<unsigned char>(ch) & 0xC0) != 0x80 ? 1 : 0;
    return n;
  };
  std::vector<size_t> widths;
  for (const auto& row : rows)
    for (size_t i = 0; i < row.size(); ++i) {
      if (widths.size() <= i) widths.push_back(0);
      widths[i] = std::max(widths[i], width(row[i]));
    }
  std::string out;
  for (const auto& row : rows) {
    std::string line = " ";
    for (size_t i = 0; i < row.size(); ++i)
      line +=
          " " + row[i] +
          (i + 1 < row.size() ? std::string(widths[i] - width(row[i]) + 1, ' ') : std::string());
    out += line + "\n";
  }
  return out;
}

// The per-body table, with its header.
std::string bodies_text(const InspectReport& rep) {
  std::vector<std::vector<std::string>> rows = {{"body", "contacts", "load (sum)",
                                                 "deepest rest depth", "effective mass",
                                                 "ω·Δt / limit", "bounce at 1 m/s"}};
  for (const BodySummary& b : rep.bodies) {
    std::string mass = "-";
    if (std::isfinite(b.mass_min))
      mass = format_number(b.mass_min) +
             (b.mass_max > b.mass_min ? "–" + format_number(b.mass_max) : std::string()) + " kg";
    rows.push_back({b.name, std::to_string(b.contacts), format_number(b.load) + " N",
                    std::isfinite(b.deepest) ? format_number(b.deepest) + " m" : std::string("-"),
                    mass, format_number(b.stability) + (b.stability >= 1.0 ? " UNSTABLE" : ""),
                    std::isfinite(b.bounce) ? "e = " + format_number(b.bounce) + " ± " +
                                                  format_number(b.bounce_spread / 2.0)
                                            : std::string("-")});
  }
  return "\nper body (load: its contacts' loads summed; effective mass 1/A at its contacts; the "
         "stiffest contact's ω·Δt over the integrator's limit; bounce: its contacts hitting "
         "together at 1 m/s as MuJoCo steps them at Δt):\n" +
         text_table(rows);
}

// A tree's carried share of its weight, in percent.
double carried(const TreeLoad& t) { return t.weight > 0.0 ? 100.0 * t.support / t.weight : kNaN; }

// Load against weight per kinematic tree: every tree when there are a few,
// else one line and the trees more than 1 % off.
std::string trees_text(const InspectReport& rep) {
  std::vector<const TreeLoad*> touching;
  for (const TreeLoad& t : rep.trees)
    if (t.contacts > 0) touching.push_back(&t);
  if (touching.empty() ||
      !(rep.gravity[0] != 0.0 || rep.gravity[1] != 0.0 || rep.gravity[2] != 0.0))
    return "";
  std::ostringstream o;
  double weight = 0.0, support = 0.0;
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (const TreeLoad* t : touching) {
    weight += t->weight;
    support += t->support;
    low = std::min(low, carried(*t));
    high = std::max(high, carried(*t));
  }
  o << "\nload against weight, per kinematic tree (what its contacts with the world and other "
       "trees push it up by, Σ f·(n·up), against Σ m·|g|: equal at rest for a tree only "
       "contacts hold"
    << (rep.at_rest ? "" : "; the model is not at rest") << "):\n";
  const size_t n = touching.size();
  if (n > 1)
    o << "  " << n << " trees with contacts (of " << rep.trees.size() << "): they carry "
      << format_number(support) << " N of their " << format_number(weight) << " N ("
      << format_number(weight > 0.0 ? 100.0 * support / weight : kNaN) << " %), each "
      << format_number(low) << (high > low ? "–" + format_number(high) : std::string())
      << " % of its own\n";
  std::vector<std::vector<std::string>> rows = {
      {"tree", "bodies", "mass", "weight", "carried", "share"}};
  size_t listed = 0;
  for (const TreeLoad* t : touching) {
    const bool far = !(std::abs(carried(*t) - 100.0) <= 1.0);
    if (n > 8 && !far) continue;
    if (++listed > 8) continue;
    rows.push_back({t->root, std::to_string(t->bodies), format_number(t->mass) + " kg",
                    format_number(t->weight) + " N", format_number(t->support) + " N",
                    format_number(carried(*t)) + " %" +
                        (t->free ? std::string()
                                 : " (jointed to the world: its joints hold "
                                   "the rest)")});
  }
  if (rows.size() > 1) {
    if (n > 8) o << "  more than 1 % off:\n";
    o << text_table(rows);
    if (listed > 8) o << "  … and " << listed - 8 << " more\n";
  } else if (n > 8) {
    o << "  none is more than 1 % off\n";
  }
  return o.str();
}

// The first thing said about a state that is not at rest: how long MuJoCo
// takes to get there (settle_time), once.
std::string not_at_rest_text(const InspectReport& rep) {
  std::string out = "NOT AT REST: MuJoCo is still moving after " + format_number(rep.settled) +
                    " s (largest |qvel| " + format_number(rep.speed) + ", |qacc| " +
                    format_number(rep.accel) + "; at rest: ≤ " + format_number(kRestSpeed) +
                    " and ≤ " + format_number(kRestAccel) + "). ";
  if (std::isfinite(rep.rest_after))
    out += "It is at rest after " + format_number(rep.rest_after) + " s: run with --settle " +
           format_number(rep.rest_after) + ".";
  else if (std::isinf(rep.rest_after))
    out += "It is not at rest after " + format_number(rep.rest_search) +
           " s either (the longest settle tried): try --settle " +
           format_number(2.0 * rep.rest_search) + " or longer.";
  else
    out += "A longer --settle brings it closer to rest.";
  return out +
         " Until then the loads below are MuJoCo's forces at this instant and each rest depth is "
         "where that load would rest, not where the contact is now\n";
}

void text_row(std::ostringstream& o, const InspectReport& rep, const InspectRow& r) {
  o << (r.active ? "contact " + std::to_string(r.contact) : std::string("pair")) << ": "
    << r.body1_name << " / " << r.body2_name << " (geoms " << r.geom1_name << ", " << r.geom2_name
    << "), " << r.source;
  if (r.active)
    o << ", dist " << format_number(r.dist) << " m";
  else
    o << ", " << r.contacts_now << " contact" << (r.contacts_now == 1 ? "" : "s") << " now";
  o << "\n";
  o << "  condim " << r.condim << ", friction " << list_text(r.friction.data(), 5) << "\n";
  o << "  solref " << list_text(r.solref.data(), 2) << ", solimp " << list_text(r.solimp.data(), 5)
    << "\n";
  if (r.solref[0] > 0.0 && r.solref[1] > 0.0)
    o << "  refsafe: "
      << (r.refsafe_changes ? "CHANGES the timeconst " + format_number(r.solref[0]) + " s to " +
                                  format_number(r.timeconst_used) + " s (2·timestep)"
                            : std::string(rep.refsafe_enabled ? "keeps the timeconst (≥ 2·timestep)"
                                                              : "disabled"))
      << "\n";
  else
    o << "  refsafe: does not apply (direct form)\n";
  o << "  K = " << format_number(r.K) << " 1/s², B = " << format_number(r.B)
    << " 1/s; impedance d = " << format_number(r.d_rest) << " at rest, " << format_number(r.dmax)
    << " max\n";
  if (r.solreffriction[0] != 0.0 || r.solreffriction[1] != 0.0)
    o << "  solreffriction " << list_text(r.solreffriction.data(), 2) << ": "
      << (r.friction_ref ? "the friction rows' B = " + format_number(r.B_friction) + " 1/s"
          : rep.cone == "elliptic" && r.condim >= 3
              ? std::string("not used (its two numbers differ in sign)")
              : std::string("not used (MuJoCo reads it in the elliptic cone's friction rows only)"))
      << "\n";
  const bool moves = moves_along_normal(r);
  o << "  A = " << format_number(r.A) << " 1/kg ("
    << (moves       ? "effective mass " + format_number(1.0 / r.A) + " kg"
        : r.A > 0.0 ? std::string("round-off of 0: below 1e-12 of Â or 1/m")
                    : std::string("no effective mass"))
    << (r.closest      ? "; at the closest points, " + format_number(r.dist) + " m apart"
        : r.A_measured ? std::string()
                       : std::string("; no contact point: A = Â assumed"))
    << "), Â = " << format_number(r.inv_weight) << " 1/kg";
  if (r.phi != 1.0)
    o << ", the normal sees Â·φ = " << format_number(r.normal_weight)
      << " (φ = " << format_number(r.phi) << ")";
  o << "\n";
  if (!moves) {
    o << "  the joints cannot move this contact along its normal ("
      << (r.A > 0.0 ? "A below 1e-12 of Â or 1/m" : "A = 0")
      << "): it moves nothing, no contact dynamics\n";
  } else {
    o << "  k = " << format_number(r.k) << " N/m, c = " << format_number(r.c)
      << " N·s/m; ω = " << format_number(r.omega) << " rad/s, ζ = " << format_number(r.zeta)
      << "; restitution " << format_number(r.restitution) << " (continuous time), "
      << (std::isfinite(r.restitution_dt)
              ? format_number(r.restitution_dt) + " as MuJoCo steps it alone at Δt"
              : "not stepped: it lasts past the " + std::to_string(kMaxBounceSteps) +
                    " steps of Δt a bounce is stepped for")
      << "\n";
    o << "  ω·Δt = " << format_number(r.omega_dt) << " at " << stiffest(r)
      << " (ω = " << format_number(r.omega_max) << ", ζ = " << format_number(r.zeta_max)
      << "): " << rep.integrator << "'s limit " << format_number(r.limit) << " ("
      << (r.omega_dt < r.limit ? "ok" : "EXCEEDED") << ")\n";
  }
  // Not at rest, the first lines said so once: a contact's own note only
  // says which way it moves.
  const std::string note = rep.at_rest || r.depth_note.empty() ? r.depth_note
                           : std::isfinite(r.penetration)      ? "moving along its normal"
                                                               : "slipping or lifting";
  if (std::isfinite(r.load))
    o << "  load " << format_number(r.load) << " N" << (rep.loads_estimated ? " (estimate)" : "")
      << ", rest depth "
      << (note.empty()                   ? format_number(r.penetration) + " m"
          : std::isfinite(r.penetration) ? format_number(r.penetration) + " m (" + note + ")"
          : rep.at_rest                  ? "not known: " + note
                                         : "- (" + note + ")")
      << "\n";
  else
    o << "  static load: not known (not in contact now)\n";
  if (std::isfinite(r.push) || std::isfinite(r.impratio_cap)) {
    o << "  friction:";
    if (std::isfinite(r.push))
      o << " sliding pushes the normal force up by μ·c·|v_t| = " << format_number(r.push)
        << " N per m/s";
    if (std::isfinite(r.lift_off))
      o << ", lifting off above " << format_number(r.lift_off) << " m/s";
    if (std::isfinite(r.impratio_cap))
      o << (std::isfinite(r.push) ? ";" : "") << " impratio ≤ " << format_number(r.impratio_cap)
        << " keeps its damper stable (" << (rep.impratio <= r.impratio_cap ? "ok" : "EXCEEDED")
        << ")";
    o << "\n";
  }
  if (rep.slope) {
    o << "  slope " << format_number(*rep.slope) << "°: ";
    if (std::isfinite(r.creep))
      o << "creep " << format_number(r.creep) << " m/s\n";
    else
      o << r.creep_note << "\n";
  }
}

std::string json_array(const double* v, int n) {
  std::string out = "[";
  for (int i = 0; i < n; ++i) out += (i ? ", " : "") + json::number(v[i]);
  return out + "]";
}

void json_row(std::ostringstream& o, const InspectRow& r) {
  o << "    {\"contact\": " << (r.active ? std::to_string(r.contact) : "null")
    << ", \"body1\": " << json::string(r.body1_name)
    << ", \"body2\": " << json::string(r.body2_name)
    << ", \"geom1\": " << json::string(r.geom1_name)
    << ", \"geom2\": " << json::string(r.geom2_name) << ", \"source\": " << json::string(r.source);
  if (!r.active) o << ", \"contacts_now\": " << r.contacts_now;
  const bool point = r.active || r.contacts_now > 0 || r.closest;
  o << ",\n     \"dist\": " << (point ? json::number(r.dist) : "null")
    << ", \"pos\": " << (point ? json_array(r.pos.data(), 3) : "null")
    << ", \"normal\": " << (point ? json_array(r.normal.data(), 3) : "null")
    << ", \"closest_points\": " << (r.closest ? "true" : "false") << ", \"condim\": " << r.condim
    << ", \"friction\": " << json_array(r.friction.data(), 5)
    << ",\n     \"solref\": " << json_array(r.solref.data(), 2)
    << ", \"solimp\": " << json_array(r.solimp.data(), 5)
    << ", \"refsafe_changes\": " << (r.refsafe_changes ? "true" : "false")
    << ", \"timeconst_used\": "
    << (r.timeconst_used > 0.0 ? json::number(r.timeconst_used) : "null")
    << ",\n     \"K\": " << json::number(r.K) << ", \"B\": " << json::number(r.B);
  if (r.solreffriction[0] != 0.0 || r.solreffriction[1] != 0.0)
    o << ", \"solreffriction\": " << json_array(r.solreffriction.data(), 2)
      << ", \"B_friction\": " << (r.friction_ref ? json::number(r.B_friction) : "null");
  o << ", \"dmax\": " << json::number(r.dmax) << ", \"d_rest\": " << json::number(r.d_rest)
    << ", \"A\": " << json::number(r.A) << ", \"A_measured\": " << (r.A_measured ? "true" : "false")
    << ", \"invweight\": " << json::number(r.inv_weight)
    << ", \"normal_weight\": " << json::number(r.normal_weight)
    << ",\n     \"k\": " << json::number(r.k) << ", \"c\": " << json::number(r.c)
    << ", \"omega\": " << json::number(r.omega) << ", \"zeta\": " << json::number(r.zeta)
    << ", \"omega_max\": " << json::number(r.omega_max)
    << ", \"zeta_max\": " << json::number(r.zeta_max)
    << ", \"omega_dt\": " << json::number(r.omega_dt) << ", \"limit\": " << json::number(r.limit)
    << ",\n     \"restitution\": " << json::number(r.restitution)
    << ", \"restitution_dt\": " << json::number(r.restitution_dt)
    << ", \"load\": " << json::number(r.load)
    << ", \"force\": " << (r.active ? json::number(r.force) : "null")
    << ", \"estimate\": " << json::number(r.estimate)
    << ", \"penetration\": " << json::number(r.penetration)
    << ", \"normal_speed\": " << (r.active ? json::number(r.normal_speed) : "null")
    << ", \"depth_note\": " << json::string(r.depth_note)
    << ",\n     \"A_t\": " << json::number(r.A_t)
    << ", \"impratio_cap\": " << json::number(r.impratio_cap)
    << ", \"push\": " << json::number(r.push) << ", \"lift_off\": " << json::number(r.lift_off)
    << ", \"creep\": " << json::number(r.creep)
    << ", \"creep_note\": " << json::string(r.creep_note) << "}";
}

}  // namespace

std::string format_inspect_text(const InspectReport& rep) {
  std::ostringstream o;
  o << "model " << rep.path << " at " << state_name(rep) << ", MuJoCo " << rep.version << "\n";
  if (!rep.contacts.empty() && !rep.at_rest) o << not_at_rest_text(rep);
  if (!rep.load_warning.empty()) o << "MuJoCo warns while loading: " << rep.load_warning << "\n";
  o << "integrator " << rep.integrator << ", timestep " << format_number(rep.dt) << " s, cone "
    << rep.cone << ", impratio " << format_number(rep.impratio)
    << " (friction rows: R_t = R/impratio"
    << (rep.impratio > 1.0
            ? ", friction " + format_number(rep.impratio) + "× stiffer than the normal"
        : rep.impratio < 1.0
            ? ", friction " + format_number(1.0 / rep.impratio) + "× softer than the normal"
            : std::string())
    << "), gravity " << list_text(rep.gravity.data(), 3) << " m/s²\n";
  if (rep.noslip_iterations > 0)
    o << "noslip_iterations " << rep.noslip_iterations
      << ": MuJoCo's noslip pass re-solves the friction forces after the main solver; the "
         "creep is not estimated and the friction rows' advice below is the main solver's\n";
  if (rep.contacts.empty()) {
    o << "no contacts at " << state_name(rep) << ": " << no_contacts_hint(rep) << "\n";
  } else {
    o << rep.contacts.size() << " contact" << (rep.contacts.size() == 1 ? "" : "s") << "; loads: "
      << (rep.loads_estimated
              ? std::string("estimated, the least-squares normal forces holding the model "
                            "against gravity") +
                    (rep.balanced ? "" : " (they do not balance it)")
              : std::string("MuJoCo's own contact forces (mj_contactForce)") +
                    (rep.at_rest ? ", at rest" : ", NOT at rest"))
      << "\n";
  }
  if (!rep.body.empty()) o << "only body " << rep.body << "'s contacts and pairs (--body)\n";
  if (!rep.bodies.empty()) o << bodies_text(rep);
  o << trees_text(rep);
  // A contact whose text is that of the one before (but for its index), as
  // a box's corners on a plane: one line naming them.
  std::string previous_body;
  int first = -1;
  std::vector<int> same;
  auto flush = [&] {
    if (same.empty()) return;
    o << "\ncontact" << (same.size() > 1 ? "s " : " ");
    for (size_t i = 0; i < same.size(); ++i) o << (i ? ", " : "") << same[i];
    o << ": the same as contact " << first << " (to the digits printed)\n";
    same.clear();
  };
  for (const InspectRow& r : rep.contacts) {
    std::ostringstream row;
    text_row(row, rep, r);
    const std::string text = row.str();
    const std::string body = text.substr(text.find(':'));
    if (body == previous_body) {
      same.push_back(r.contact);
      continue;
    }
    flush();
    previous_body = body;
    first = r.contact;
    o << "\n" << text;
  }
  flush();
  if (rep.pairs_listed) {
    o << "\n"
      << rep.pairs.size() << " geom pair" << (rep.pairs.size() == 1 ? "" : "s")
      << " that can collide\n";
    for (const InspectRow& r : rep.pairs) {
      o << "\n";
      text_row(o, rep, r);
    }
  }
  if (!rep.warnings.empty()) {
    o << "\nwarnings:\n";
    for (const std::string& w : rep.warnings) o << "  " << w << "\n";
  }
  return o.str();
}

std::string format_inspect_json(const InspectReport& rep) {
  std::ostringstream o;
  o << "{\n  \"model\": " << json::string(rep.path)
    << ",\n  \"key\": " << (rep.key.empty() ? "null" : json::string(rep.key))
    << ",\n  \"mujoco\": " << json::string(rep.version)
    << ",\n  \"settled\": " << json::number(rep.settled)
    << ",\n  \"speed\": " << json::number(rep.speed)
    << ",\n  \"accel\": " << json::number(rep.accel)
    << ",\n  \"at_rest\": " << (rep.at_rest ? "true" : "false")
    << ",\n  \"loads\": " << json::string(rep.loads_estimated ? "estimate" : "mujoco")
    << ",\n  \"load_warning\": " << json::string(rep.load_warning)
    << ",\n  \"integrator\": " << json::string(rep.integrator)
    << ",\n  \"timestep\": " << json::number(rep.dt) << ",\n  \"cone\": " << json::string(rep.cone)
    << ",\n  \"impratio\": " << json::number(rep.impratio)
    << ",\n  \"gravity\": " << json_array(rep.gravity.data(), 3)
    << ",\n  \"slope\": " << (rep.slope ? json::number(*rep.slope) : "null")
    << ",\n  \"balanced\": " << (rep.balanced ? "true" : "false")
    << ",\n  \"residual\": " << json::number(rep.residual) << ",\n  \"rest_after\": "
    << (std::isfinite(rep.rest_after) ? json::number(rep.rest_after) : "null")
    << ",\n  \"rest_search\": " << json::number(rep.rest_search)
    << ",\n  \"body\": " << (rep.body.empty() ? "null" : json::string(rep.body))
    << ",\n  \"bodies\": [";
  for (size_t i = 0; i < rep.bodies.size(); ++i) {
    const BodySummary& b = rep.bodies[i];
    o << (i ? ",\n    " : "\n    ") << "{\"name\": " << json::string(b.name)
      << ", \"contacts\": " << b.contacts << ", \"load\": " << json::number(b.load)
      << ", \"deepest\": " << json::number(b.deepest)
      << ", \"mass_min\": " << json::number(b.mass_min)
      << ", \"mass_max\": " << json::number(b.mass_max)
      << ", \"stability\": " << json::number(b.stability)
      << ", \"bounce\": " << json::number(b.bounce)
      << ", \"bounce_spread\": " << json::number(b.bounce_spread) << "}";
  }
  o << (rep.bodies.empty() ? "]" : "\n  ]") << ",\n  \"trees\": [";
  for (size_t i = 0; i < rep.trees.size(); ++i) {
    const TreeLoad& t = rep.trees[i];
    o << (i ? ",\n    " : "\n    ") << "{\"root\": " << json::string(t.root)
      << ", \"bodies\": " << t.bodies << ", \"mass\": " << json::number(t.mass)
      << ", \"weight\": " << json::number(t.weight) << ", \"support\": " << json::number(t.support)
      << ", \"contacts\": " << t.contacts << ", \"free\": " << (t.free ? "true" : "false") << "}";
  }
  o << (rep.trees.empty() ? "]" : "\n  ]") << ",\n  \"contacts\": [";
  for (size_t i = 0; i < rep.contacts.size(); ++i) {
    o << (i ? ",\n" : "\n");
    json_row(o, rep.contacts[i]);
  }
  o << (rep.contacts.empty() ? "]" : "\n  ]");
  o << ",\n  \"pairs\": ";
  if (!rep.pairs_listed) {
    o << "null";
  } else {
    o << "[";
    for (size_t i = 0; i < rep.pairs.size(); ++i) {
      o << (i ? ",\n" : "\n");
      json_row(o, rep.pairs[i]);
    }
    o << (rep.pairs.empty() ? "]" : "\n  ]");
  }
  o << ",\n  \"warnings\": [";
  for (size_t i = 0; i < rep.warnings.size(); ++i)
    o << (i ? ",\n    " : "\n    ") << json::string(rep.warnings[i]);
  o << (rep.warnings.empty() ? "]" : "\n  ]") << "\n}\n";
  return o.str();
}

}  // namespace contact2d::mujoco
