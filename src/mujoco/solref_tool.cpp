// `contact2d solref` (mujoco/solref_tool.hpp).
#include "mujoco/solref_tool.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <fstream>
#include <sstream>

#include "benchmarks/impact.hpp"
#include "core/format.hpp"
#include "core/input_error.hpp"
#include "core/integrators.hpp"
#include "io/json.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/model.hpp"

namespace contact2d::mujoco {
namespace {

constexpr double kMinImp = 1e-4;    // MuJoCo's mjMINIMP
constexpr double kMaxImp = 0.9999;  // MuJoCo's mjMAXIMP
constexpr double kMinVal = 1e-15;   // MuJoCo's mjMINVAL
// The default class's solmix without --mu (outcome()).
constexpr double kSolmixWins = 1e30;

void require(bool ok, const std::string& option, double value, const std::string& range) {
  if (!ok) throw InputError(option + " " + format_number(value, 6) + ": must be " + range);
}

std::string join(const std::vector<double>& values) {
  std::string out;
  for (double v : values) out += (out.empty() ? "" : " ") + format_exact(v);
  return out;
}

int condim_for(const SolrefInput& in) {
  if (in.keep_friction) return 0;  // not written: the user's
  if (in.mu_roll > 0.0) return 6;
  return in.mu > 0.0 ? 3 : 1;
}

// <option> with what differs from MuJoCo's defaults (cone, impratio), or "".
std::string option_line(const MappingOutcome& o) {
  std::string attributes;
  if (o.settings.elliptic) attributes += " cone=\"elliptic\"";
  if (o.condim > 1 && o.settings.impratio != 1.0)
    attributes += " impratio=\"" + format_exact(o.settings.impratio) + "\"";
  return attributes.empty() ? "" : "<option" + attributes + "/>\n";
}

std::string friction_attribute(const SolrefInput& in, int condim, bool pair) {
  if (condim <= 1) return "";
  const std::vector<double> values =
      pair ? std::vector<double>{in.mu, in.mu, 0.0, in.mu_roll, in.mu_roll}
           : std::vector<double>{in.mu, 0.0, in.mu_roll};
  return " friction=\"" + join(values) + "\"";
}

std::string contact_attributes(const SolrefInput& in, const MappingOutcome& o, bool pair) {
  const SolverSettings& s = o.settings;
  return (o.condim > 0 ? " condim=\"" + std::to_string(o.condim) + "\"" : std::string()) +
         friction_attribute(in, o.condim, pair) + " solref=\"" + join({s.solref[0], s.solref[1]}) +
         "\" solimp=\"" + join({s.solimp[0], s.solimp[1], s.solimp[2], s.solimp[3], s.solimp[4]}) +
         "\"";
}

// The creep at --slope θ under this mapping: inside the cone MuJoCo's
// friction rows have no spring (aref = −B·v) and R_t = R/impratio, so at
// steady creep a contact carries impratio·B·d·v/((1 − d)·Â) tangentially
// (÷ (1 + μ²) for the pyramidal cone's edges); with the load f·sinθ along
// the slope and d at the depth under f·cosθ (inspect.hpp, where it is
// measured against MuJoCo).
void creep_on_slope(const SolrefInput& in, double inv_weight, MappingOutcome& o, bool elliptic,
                    int condim) {
  if (!in.slope) return;
  const double th = *in.slope * std::acos(-1.0) / 180.0;
  const double mu = o.condim == 0 ? in.user_friction.mu : in.mu;
  if (condim <= 1) {
    o.creep_note = "condim 1, no friction: slides";
  } else if (std::tan(th) >= mu) {
    o.creep_note = "tanθ ≥ μ = " + format_number(mu) + ": slides (Coulomb)";
  } else if (!elliptic && std::tan(th) >= mu / (condim - 1)) {
    o.creep_note = "tanθ ≥ μ/(condim − 1): an edge of the pyramidal cone unloads";
  } else if (in.user_friction.noslip_iterations > 0) {
    o.creep_note = "not estimated: the model's noslip_iterations = " +
                   std::to_string(in.user_friction.noslip_iterations) +
                   " (MuJoCo's noslip pass re-solves the friction forces after the main solver, "
                   "which is not modelled)";
  } else if (th == 0.0) {
    o.creep = 0.0;
  } else {
    const double f = contact_mechanics(in).load;
    const double p = static_penetration(o.settings.solimp, o.K, o.normal_weight, f * std::cos(th));
    const double d = mujoco_impedance(o.settings.solimp, -p);
    const double shape = elliptic ? 1.0 : 1.0 + mu * mu;
    o.creep = f * std::sin(th) * (1.0 - d) * inv_weight * shape /
              (std::max(kMinVal, o.settings.impratio) * o.B * d);
  }
}

// The body's settled contacts where the default class snippet does not
// hold (solref_tool.hpp's ClassCaveat), each geom pair once, each of the
// body's geoms' own class once. MuJoCo 2.2.2's mj_collideGeoms (and 3.x's
// mj_contactParam, the same rules): the geom of higher priority gives
// solref and solimp outright; at equal priority both solrefs in standard
// form (> 0) mix by solmix, else each element is the smaller of the two.
// The snippet gives the body's geom priority 1 with --mu, else leaves its
// priority as it is.
std::vector<ClassCaveat> class_caveats(const SolrefInput& in, const MappingOutcome& o) {
  std::vector<ClassCaveat> out;
  std::vector<std::pair<int, int>> pairs;
  std::vector<int> geoms;
  const std::array<double, 2>& mine = o.settings.solref;
  for (const SettledContact& c : in.settled_contacts) {
    if (std::find(pairs.begin(), pairs.end(), std::make_pair(c.ref1.id, c.ref2.id)) != pairs.end())
      continue;
    pairs.emplace_back(c.ref1.id, c.ref2.id);
    const std::string contact = c.geom1 + " – " + c.geom2;
    const auto own = static_cast<size_t>(c.own), other = 1 - own;
    const GeomRef& own_geom = own == 0 ? c.ref1 : c.ref2;
    const std::string other_name = other == 0 ? c.geom1 : c.geom2;
    if (!c.own_class.empty() && std::find(geoms.begin(), geoms.end(), own_geom.id) == geoms.end()) {
      geoms.push_back(own_geom.id);
      out.push_back({"class_replaced", contact,
                     "geom " + own_geom.name + " has class \"" + c.own_class + "\"" +
                         (c.own_class_from.empty() ? "" : " (" + c.own_class_from + ")") +
                         ": class=\"contact2d\" replaces it, and whatever it sets (friction, "
                         "condim, priority, contype, …) with it; nest the snippet's class in "
                         "it, <default class=\"" +
                         c.own_class + "\"><default class=\"contact2d\">…, to keep them"});
    }
    if (c.explicit_pair) {
      out.push_back({"explicit_pair", contact,
                     "the model's <pair> of these geoms makes this contact: MuJoCo uses the "
                     "pair's solref and solimp, and the class changes nothing there"});
      continue;
    }
    const int priority = o.condim != 0 ? 1 : c.priority[own], theirs = c.priority[other];
    if (theirs > priority) {
      out.push_back({"priority", contact,
                     "geom " + other_name + " has priority " + std::to_string(theirs) +
                         ", above the body's geom's " + std::to_string(priority) +
                         ": MuJoCo takes its solref, solimp, friction and condim, not the "
                         "class's"});
    } else if (theirs == priority && o.condim != 0) {
      out.push_back({"priority", contact,
                     "geom " + other_name + " has priority " + std::to_string(theirs) +
                         ", as the class's: at equal priority MuJoCo mixes the two geoms' "
                         "solref and solimp by solmix, and takes the larger friction and "
                         "condim"});
    } else if (theirs == priority) {
      const std::array<double, 2>& ref = c.geom_solref[other];
      const std::array<double, 2> mixed{std::min(mine[0], ref[0]), std::min(mine[1], ref[1])};
      if (!(mine[0] > 0.0 && ref[0] > 0.0) && mixed != mine)
        out.push_back({"direct_solref", contact,
                       "geom " + other_name + "'s solref " + join({ref[0], ref[1]}) +
                           " and the class's " + join({mine[0], mine[1]}) +
                           " are not both in standard form (> 0): MuJoCo takes the smaller "
                           "of each element, " +
                           join({mixed[0], mixed[1]}) +
                           ", not the class's (solmix weighs standard forms only)"});
    }
  }
  return out;
}

MappingOutcome outcome(const SolrefReport& report, Mapping mapping) {
  const SolrefInput& in = report.input;
  MappingOutcome o;
  o.mapping = mapping;
  if (mapping == Mapping::Compensated) {
    o.unavailable = compensated_not_offered();
    return o;
  }
  o.condim = condim_for(in);
  ContactParams contact;
  contact.k = in.k;
  contact.c = in.c;
  contact.mu = in.keep_friction ? 0.0 : in.mu;
  contact.mu_roll = in.keep_friction ? 0.0 : in.mu_roll;
  RigidBody body;
  // One contact at the lever: a disc of that radius when it rolls, else a
  // turning body when it has an inertia, else a point mass.
  body.shape = in.mu_roll > 0.0 ? Shape::Circle : in.inertia > 0.0 ? Shape::Box : Shape::PointMass;
  body.mass = in.mass;
  body.inertia = in.inertia;
  body.rotates = in.inertia > 0.0;
  body.points = {Vec2(in.lever, 0.0)};
  body.roll_radius = in.mu_roll > 0.0 ? in.lever : 0.0;
  try {
    o.settings = solver_settings(contact, body, in.dt, mapping, report.inv_weight, 1);
  } catch (const InputError& e) {
    // The mapping code names the scene keys; here they are options.
    o.unavailable = e.what();
    for (const auto& [key, option] :
         {std::pair<std::string, std::string>{"contact.k", "--k"}, {"contact.c", "--c"}}) {
      for (size_t at = o.unavailable.find(key); at != std::string::npos;
           at = o.unavailable.find(key, at))
        o.unavailable.replace(at, key.size(), option);
    }
    return o;
  }
  // The measured contact turns the body: its tangential inverse mass, not
  // 1/m, bounds calibrated's impratio (mapping.cpp's calibrated_impratio).
  if (mapping == Mapping::Calibrated && o.condim > 1 && in.tangential_inv_mass > 0.0 && in.c > 0.0)
    o.settings.impratio =
        std::min(o.settings.impratio, 1.0 / (in.dt * in.tangential_inv_mass * in.c));
  if (o.condim == 1) o.settings.impratio = 1.0;  // no friction rows: not written, MuJoCo's 1
  if (o.condim == 0) o.settings.impratio = in.user_friction.impratio;  // not written: the user's
  SolverSettings& s = o.settings;
  std::array<double, 2> solref = s.solref;
  if (solref[0] > 0.0) {  // refsafe (MuJoCo's getsolparam)
    solref[0] = std::max(solref[0], 2.0 * in.dt);
    o.timeconst_used = solref[0];
  }
  const double dmax = std::clamp(s.solimp[1], kMinImp, kMaxImp);
  const AccelerationGains gains = acceleration_gains(solref);
  o.impedance = dmax;
  o.K = gains.stiffness / std::max(kMinVal, dmax * dmax);
  o.B = gains.damping / std::max(kMinVal, dmax);
  // Pyramidal cone with friction rows (seed, exact with μ > 0): MuJoCo gives
  // each of the 2(condim − 1) edge rows R_py = 2μ²·R_0/impratio with
  // R_0 = (1 − d)/d·(1 + μ²)·Â (diagApprox of an edge row, μ ≥ 1e-5), and the
  // normal force is their sum: the normal sees Â·φ in place of Â, with
  // φ = μ²(1 + μ²)/((condim − 1)·impratio).
  // Without --mu the friction is the user's (in.user_friction), and so is
  // the cone unless the mapping writes cone="elliptic".
  o.normal_weight = report.inv_weight;
  const bool elliptic = s.elliptic || (o.condim == 0 && in.user_friction.elliptic);
  const int condim = o.condim == 0 ? in.user_friction.condim : o.condim;
  if (!elliptic && condim > 1) {
    const double mu = std::max(o.condim == 0 ? in.user_friction.mu : in.mu, 1e-5);  // mjMINMU
    o.normal_weight *= mu * mu * (1.0 + mu * mu) / ((condim - 1) * s.impratio);
  }
  // The stiffest impedance (ω rises with d): d_max, or solimp's d0 when it is
  // above d_max (the impedance then falls with depth).
  const double A = report.inv_mass, Ahat = o.normal_weight,
               d = std::max(std::clamp(s.solimp[0], kMinImp, kMaxImp), dmax);
  const double denominator = d * A + (1.0 - d) * Ahat;
  o.omega = std::sqrt(A * d * d * o.K / denominator);
  o.zeta = A * d * o.B / denominator / (2.0 * o.omega);
  o.omega_dt = o.omega * in.dt;
  o.euler_limit = stability_limit(Integrator::SemiImplicitEuler, o.zeta);
  o.rk4_limit = stability_limit(Integrator::RK4, o.zeta);
  o.static_penetration = static_penetration(s.solimp, o.K, Ahat, report.load);
  o.impedance_at_rest = mujoco_impedance(s.solimp, -o.static_penetration);
  o.nominal_penetration = report.load / in.k;
  creep_on_slope(in, report.inv_weight, o, elliptic, condim);
  const std::string options = option_line(o);
  // Without --mu the class must change solref and solimp alone. MuJoCo mixes
  // two geoms of equal priority (engine_collision_driver.c): condim, friction
  // by the larger, margin and gap by the larger (2.2.2) or the sum (3.x),
  // solimp and a standard-form solref weighted by solmix, s₁/(s₁ + s₂), a
  // direct-form (negative) solref by the smaller per element. solmix 1e30
  // against MuJoCo's default 1 rounds that weight to 1 (or to 1e-30 on the
  // other geom's side, below half an ulp of any solref or solimp): the
  // class's values. priority would copy condim and friction from the class's
  // geom too, the defect it replaces; with --mu that is what is asked for.
  o.default_snippet =
      options + "<default>\n  <default class=\"contact2d\">\n    <geom" +
      contact_attributes(in, o, false) +
      (o.condim == 0 ? " solmix=\"" + format_exact(kSolmixWins) + "\"" : " priority=\"1\"") +
      "/>\n  </default>\n</default>\n";
  o.class_caveats = class_caveats(in, o);
  const std::vector<RestPair> pairs = rest_pairs(in, o);
  if (pairs.empty()) {
    o.pair_snippet = options + "<contact>\n  <pair geom1=\"BODY_GEOM\" geom2=\"ground\"" +
                     contact_attributes(in, o, true) + "/>\n</contact>\n";
  } else {
    o.pair_snippet = options + "<contact>\n";
    for (const RestPair& p : pairs)
      o.pair_snippet += "  <pair geom1=\"" + pair_name(p.geom1) + "\" geom2=\"" +
                        pair_name(p.geom2) + "\"" + pair_attributes(p, o.settings) + "/>\n";
    o.pair_snippet += "</contact>\n";
  }
  return o;
}

// A mapping unfit for a model to build on: MuJoCo's contact is not k and c.
// Threshold 10 %: calibrated is off by its O(d·A/Â) term, d = 1e-4
// (≤ 1e-3 relative for any lever the tool accepts with A/Â ≤ 10), while
// seed and exact are off by factors (at rest 0.02–0.07 × f/k, ω up to 7×:
// docs/mujoco.md's table), so 10 % separates them by over an order of
// magnitude on both sides; an ω·Δt beyond MuJoCo Euler's limit is unfit at
// any error.
std::string unfit_reason(const SolrefReport& r, const MappingOutcome& o) {
  const SolrefInput& in = r.input;
  const double omega = std::sqrt(in.k * r.inv_mass);
  const double zeta = in.c * r.inv_mass / (2.0 * omega);
  const double rest = o.static_penetration / o.nominal_penetration;
  auto off = [](double value, double want) { return !(std::abs(value / want - 1.0) <= 0.1); };
  std::string why;
  if (off(o.omega, omega) || (zeta > 0.0 && off(o.zeta, zeta)))
    why = "ω = " + format_number(o.omega) + " rad/s, ζ = " + format_number(o.zeta) +
          " against the physical ω = " + format_number(omega) +
          " rad/s, ζ = " + format_number(zeta);
  if (off(rest, 1.0))
    why += (why.empty() ? "" : "; ") + std::string("it rests at ") + format_number(rest) + " × f/k";
  if (!(o.omega_dt < o.euler_limit))
    why += (why.empty() ? "" : "; ") + std::string("ω·Δt = ") + format_number(o.omega_dt) +
           " exceeds MuJoCo Euler's limit " + format_number(o.euler_limit);
  return why;
}

}  // namespace

std::string_view joint_name(Joint joint) {
  switch (joint) {
    case Joint::Free: return "free";
    case Joint::Planar: return "planar";
    case Joint::Slide: return "slide";
    case Joint::Hinge: return "hinge";
  }
  return "?";
}

std::optional<Joint> parse_joint(std::string_view name) {
  for (Joint j : {Joint::Free, Joint::Planar, Joint::Slide, Joint::Hinge})
    if (joint_name(j) == name) return j;
  return std::nullopt;
}

double joint_inv_weight(Joint joint, double mass, double inertia, double pivot, bool mujoco3) {
  switch (joint) {
    case Joint::Free: return 1.0 / mass;
    case Joint::Planar: return 2.0 / (3.0 * mass);
    case Joint::Slide: return mujoco3 ? 1.0 / mass : 1.0 / (3.0 * mass);
    case Joint::Hinge: return pivot * pivot / (3.0 * (inertia + mass * pivot * pivot));
  }
  return 0.0;
}

std::vector<Mapping> offered_mappings() {
  return {Mapping::Calibrated, Mapping::Exact, Mapping::Seed};
}

std::string compensated_not_offered() {
  return "not offered for your own model: its solref assumes the contact geoms sit on a massless "
         "body at a lever computed from the body's contact points, which only `contact2d generate "
         "--mapping compensated` builds (for contact2d's scenes); calibrated differs from it by "
         "MuJoCo's O(d·A/Â) term, d = 1e-4";
}

void validate(const SolrefInput& in) {
  auto finite = [](double v) { return std::isfinite(v); };
  require(finite(in.k) && in.k > 0.0, "--k", in.k, "a finite number > 0 (N/m)");
  require(finite(in.c) && in.c >= 0.0, "--c", in.c, "a finite number >= 0 (N·s/m)");
  require(finite(in.dt) && in.dt > 0.0, "--dt", in.dt, "a finite number > 0 (s)");
  require(finite(in.mass) && in.mass > 0.0, "--mass", in.mass, "a finite number > 0 (kg)");
  require(finite(in.inertia) && in.inertia >= 0.0, "--inertia", in.inertia,
          "a finite number >= 0 (kg·m²)");
  require(finite(in.lever) && in.lever >= 0.0, "--lever", in.lever, "a finite number >= 0 (m)");
  require(finite(in.pivot) && in.pivot >= 0.0, "--pivot", in.pivot, "a finite number >= 0 (m)");
  const std::string joint = "--joint " + std::string(joint_name(in.joint));
  if (in.measured) {
    // A and the load were measured in the model: no lever or pivot needed.
  } else if (in.joint == Joint::Hinge) {
    if (!(in.pivot > 0.0))
      throw InputError("--pivot " + format_number(in.pivot) + ": " + joint +
                       " needs the COM's distance from the hinge axis > 0 (m; at 0 MuJoCo's "
                       "body_invweight0 is 0)");
    if (!(in.lever > 0.0))
      throw InputError("--lever " + format_number(in.lever) + ": " + joint +
                       " needs the contact normal's moment arm about the hinge axis > 0 (m)");
  } else {
    if (in.pivot > 0.0)
      throw InputError("--pivot " + format_number(in.pivot) + ": only for --joint hinge (here " +
                       joint + ")");
    if (in.joint == Joint::Slide && in.lever > 0.0)
      throw InputError("--lever " + format_number(in.lever) +
                       ": a body on one slide joint does not rotate (--joint slide)");
    if (in.lever > 0.0 && !(in.inertia > 0.0))
      throw InputError("--lever " + format_number(in.lever) +
                       ": needs --inertia > 0 (the body must rotate)");
  }
  require(finite(in.mu) && in.mu >= 0.0, "--mu", in.mu, "a finite number >= 0");
  require(finite(in.mu_roll) && in.mu_roll >= 0.0, "--mu-roll", in.mu_roll,
          "a finite number >= 0 (m)");
  if (in.mu_roll > 0.0 && (in.joint == Joint::Slide || in.joint == Joint::Hinge))
    throw InputError("--mu-roll " + format_number(in.mu_roll) +
                     ": needs --joint free or planar (here " + joint + ")");
  if (in.mu_roll > 0.0 && !(in.lever > 0.0))
    throw InputError("--mu-roll " + format_number(in.mu_roll) +
                     ": needs --inertia and --lever > 0 (the rolling radius)");
  if (in.slope && !(*in.slope >= 0.0 && *in.slope < 90.0))
    throw InputError("--slope " + format_number(*in.slope) + ": must be in [0, 90) degrees");
  if (in.contacts < 1)
    throw InputError("--contacts " + std::to_string(in.contacts) + ": must be an integer >= 1");
  require(finite(in.inv_weight) && in.inv_weight >= 0.0, "body_invweight0", in.inv_weight,
          "a finite number >= 0 (1/kg)");
}

double mujoco_impedance(const std::array<double, 5>& solimp_in, double pos) {
  std::array<double, 5> s = solimp_in;
  s[0] = std::clamp(s[0], kMinImp, kMaxImp);
  s[1] = std::clamp(s[1], kMinImp, kMaxImp);
  s[2] = std::max(0.0, s[2]);
  s[3] = std::clamp(s[3], kMinImp, kMaxImp);
  s[4] = std::max(1.0, s[4]);
  if (s[0] == s[1] || s[2] <= kMinVal) return 0.5 * (s[0] + s[1]);
  const double x = std::abs(pos) / s[2];
  if (x >= 1.0) return s[1];
  if (x <= 0.0) return s[0];
  double y = x;
  if (s[4] != 1.0) {
    y = x <= s[3] ? std::pow(x, s[4]) / std::pow(s[3], s[4] - 1.0)
                  : 1.0 - std::pow(1.0 - x, s[4]) / std::pow(1.0 - s[3], s[4] - 1.0);
  }
  return s[0] + y * (s[1] - s[0]);
}

double static_penetration(const std::array<double, 5>& solimp, double K, double inv_weight,
                          double force) {
  // residual(p) = p·K·d(p)² − f·Â·(1 − d(p)): increasing in p, negative at 0.
  auto residual = [&](double p) {
    const double d = mujoco_impedance(solimp, -p);
    return p * K * d * d - force * inv_weight * (1.0 - d);
  };
  const double d_low = std::min(mujoco_impedance(solimp, 0.0), mujoco_impedance(solimp, 1e300));
  double lo = 0.0;
  double hi = force * inv_weight * (1.0 - d_low) / (K * d_low * d_low);  // d ≥ d_low
  if (!(hi > 0.0) || !std::isfinite(hi)) return hi;
  if (residual(hi) <= 0.0) return hi;
  for (int i = 0; i < 2000; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;  // the interval is one ulp wide
    (residual(mid) < 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

ContactMechanics contact_mechanics(const SolrefInput& input) {
  if (input.measured) return *input.measured;
  ContactMechanics m;
  if (input.joint == Joint::Hinge) {
    const double hinge_inertia = input.inertia + input.mass * input.pivot * input.pivot;
    m.inv_mass = input.lever * input.lever / hinge_inertia;
    // The hinge axis horizontal, the COM level with it at the pivot distance
    // and the contact normal vertical at the lever: the torque balance
    // m·g·pivot = N·f·lever.
    m.load = input.mass * input.gravity * input.pivot / (input.lever * input.contacts);
  } else {
    m.inv_mass =
        1.0 / input.mass + (input.inertia > 0.0 ? input.lever * input.lever / input.inertia : 0.0);
    m.load = input.mass * input.gravity / input.contacts;
  }
  return m;
}

void solve_targets(SolrefInput& in, const SolrefTargets& t, bool k_given, bool c_given) {
  const int k_sources = (k_given ? 1 : 0) + (t.penetration ? 1 : 0) + (t.contact_time ? 1 : 0);
  if (k_sources > 1)
    throw InputError(std::string(k_given ? "--k" : "--penetration") +
                     ": give k one way only: --k, --penetration or --contact-time");
  if (k_sources == 0)
    throw InputError("--k: required (or --penetration, or --contact-time with --restitution)");
  if (c_given && t.restitution) throw InputError("--c: give c one way only: --c or --restitution");
  if (!c_given && !t.restitution) throw InputError("--c: required (or --restitution)");
  if (t.contact_time && !t.restitution)
    throw InputError("--contact-time: needs --restitution (the time depends on ζ too)");
  auto finite = [](double v) { return std::isfinite(v); };
  if (t.restitution)
    require(finite(*t.restitution) && *t.restitution > 0.0 && *t.restitution < 1.0, "--restitution",
            *t.restitution, "a number in (0, 1)");
  if (t.contact_time)
    require(finite(*t.contact_time) && *t.contact_time > 0.0, "--contact-time", *t.contact_time,
            "a finite number > 0 (s)");
  if (t.penetration)
    require(finite(*t.penetration) && *t.penetration > 0.0, "--penetration", *t.penetration,
            "a finite number > 0 (m)");
  {
    // The body's numbers first (A and f need them); k and c are placeholders.
    SolrefInput probe = in;
    probe.k = 1.0;
    probe.c = 0.0;
    validate(probe);
  }
  const ContactMechanics mech = contact_mechanics(in);
  std::string note;
  double zeta = 0.0;
  if (t.restitution) {
    // e(ζ) falls from 1 at ζ = 0 (2.5e-7 at ζ = 1000): bisection on log ζ.
    const double e = *t.restitution;
    double lo = 1e-9, hi = 1e4;
    if (!(benchmarks::kelvin_voigt_restitution(hi) < e))
      throw InputError("--restitution " + format_number(e) +
                       ": below what a Kelvin–Voigt contact reaches (" +
                       format_number(benchmarks::kelvin_voigt_restitution(hi)) + " at ζ = 1e4)");
    if (!(benchmarks::kelvin_voigt_restitution(lo) > e))
      throw InputError("--restitution " + format_number(e) + ": too close to 1 (ζ < 1e-9)");
    for (int i = 0; i < 200; ++i) {
      const double mid = std::sqrt(lo * hi);
      (benchmarks::kelvin_voigt_restitution(mid) > e ? lo : hi) = mid;
    }
    zeta = std::sqrt(lo * hi);
  }
  if (t.penetration) {
    constexpr double kCalibratedImpedance = 1e-4;  // calibrated's flat solimp
    in.k = (1.0 - kCalibratedImpedance) * mech.load / *t.penetration;
    note += "k = (1 − d)·f/p = (1 − 1e-4)·" + format_number(mech.load) + "/" +
            format_number(*t.penetration) + " = " + format_number(in.k) +
            " N/m (calibrated's rest depth per contact, f = " + format_number(mech.load) + " N)";
  }
  if (t.contact_time) {
    const double omega = benchmarks::kelvin_voigt_contact_time(zeta) / *t.contact_time;
    in.k = omega * omega / mech.inv_mass;
    note +=
        "k = ω²/A with ω = τ(ζ)/T = " + format_number(benchmarks::kelvin_voigt_contact_time(zeta)) +
        "/" + format_number(*t.contact_time) + " s = " + format_number(omega) +
        " rad/s: k = " + format_number(in.k) + " N/m";
  }
  if (t.restitution) {
    in.c = 2.0 * zeta * std::sqrt(in.k / mech.inv_mass);
    note += std::string(note.empty() ? "" : "; ") + "ζ = " + format_number(zeta) +
            " rebounds at e = " + format_number(*t.restitution) +
            " (Kelvin–Voigt, force clamped at zero): " + "c = 2ζ·√(k/A) = " + format_number(in.c) +
            " N·s/m (A = " + format_number(mech.inv_mass) + " 1/kg)";
  }
  in.targets_note = note;
}

SolrefReport solref_report(const SolrefInput& input, const std::vector<Mapping>& mappings) {
  validate(input);
  SolrefReport report;
  report.input = input;
  const ContactMechanics mech = contact_mechanics(input);
  report.inv_mass = mech.inv_mass;
  report.load = mech.load;
  report.inv_weight =
      input.inv_weight > 0.0
          ? input.inv_weight
          : joint_inv_weight(input.joint, input.mass, input.inertia, input.pivot, input.mujoco3);
  for (Mapping mapping : mappings) report.mappings.push_back(outcome(report, mapping));
  for (MappingOutcome& o : report.mappings)
    if (o.unavailable.empty()) o.unfit = unfit_reason(report, o);
  // The recommendation: the first offered mapping that is fit (computed
  // whether or not --mapping asked for it), printed first.
  for (Mapping candidate : offered_mappings()) {
    const auto it = std::find_if(report.mappings.begin(), report.mappings.end(),
                                 [&](const MappingOutcome& o) { return o.mapping == candidate; });
    MappingOutcome o = it != report.mappings.end() ? *it : outcome(report, candidate);
    if (!o.unavailable.empty()) continue;
    o.unfit = unfit_reason(report, o);
    if (!o.unfit.empty()) continue;
    const double omega = std::sqrt(input.k * report.inv_mass);
    report.recommendation =
        std::string(mapping_name(candidate)) +
        ": MuJoCo's contact then has ω = " + format_number(o.omega) +
        " rad/s against the physical " + format_number(omega) + " and rests at " +
        format_number(o.static_penetration / o.nominal_penetration) +
        " × f/k; it sets only solref, solimp and MuJoCo's options, so it is a model to build on" +
        (it == report.mappings.end()
             ? " (not printed below: --mapping " + std::string(mapping_name(candidate)) + ")"
             : std::string());
    if (it != report.mappings.end()) std::rotate(report.mappings.begin(), it, it + 1);
    break;
  }
  return report;
}

namespace {

// The largest x in [x·1e-6, x] at which `fits` holds, by bisection on log x
// (fits(x) false, and fit below some value: ω·Δt and ω grow with Δt and k),
// rounded down to 3 significant digits; NaN when it does not hold at x·1e-6.
template <typename Fits>
double largest_fit(double x, Fits fits) {
  double lo = x * 1e-6, hi = x;
  if (!fits(lo)) return NAN;
  for (int i = 0; i < 60; ++i) {
    const double mid = std::sqrt(lo * hi);
    (fits(mid) ? lo : hi) = mid;
  }
  const double scale = std::pow(10.0, std::floor(std::log10(lo)) - 2.0);
  const double rounded = std::floor(lo / scale) * scale;
  return fits(rounded) ? rounded : lo;
}

}  // namespace

std::string fit_hint(const SolrefReport& report) {
  if (!report.recommendation.empty()) return "";
  const SolrefInput& in = report.input;
  const std::vector<Mapping> calibrated{Mapping::Calibrated};
  auto fits_with = [&](auto change) {
    SolrefInput probe = in;
    change(probe);
    try {
      return !solref_report(probe, calibrated).recommendation.empty();
    } catch (const InputError&) {
      return false;
    }
  };
  const double dt =
      largest_fit(in.dt, [&](double x) { return fits_with([x](SolrefInput& p) { p.dt = x; }); });
  const double k =
      largest_fit(in.k, [&](double x) { return fits_with([x](SolrefInput& p) { p.k = x; }); });
  if (!std::isfinite(dt) && !std::isfinite(k)) return "";
  std::string hint = "Try";
  if (std::isfinite(dt))
    hint += " --dt " + format_number(dt, 3) +
            " (the largest Δt at which a mapping fits k = " + format_number(in.k) +
            " N/m, c = " + format_number(in.c) + " N·s/m)";
  if (std::isfinite(k))
    hint += std::string(std::isfinite(dt) ? " or" : "") + " --k " + format_number(k, 3) +
            " (the largest k a mapping fits at Δt = " + format_number(in.dt) +
            " s, c = " + format_number(in.c) + " N·s/m)";
  else
    hint += "; no k fits at Δt = " + format_number(in.dt) + " s with c = " + format_number(in.c) +
            " N·s/m (its damping alone is past the limit)";
  return hint + ".";
}

std::vector<RestPair> rest_pairs(const SolrefInput& in, const MappingOutcome& o) {
  std::vector<RestPair> pairs;
  for (const SettledContact& c : in.settled_contacts) {
    const bool seen = std::any_of(pairs.begin(), pairs.end(), [&](const RestPair& p) {
      return (p.geom1.id == c.ref1.id && p.geom2.id == c.ref2.id) ||
             (p.geom1.id == c.ref2.id && p.geom2.id == c.ref1.id);
    });
    if (seen) continue;
    RestPair p;
    p.geom1 = c.ref1;
    p.geom2 = c.ref2;
    p.explicit_pair = c.explicit_pair;
    p.margin = c.margin;
    p.gap = c.gap;
    if (o.condim > 0) {  // --mu: the mapping's condim and friction
      p.condim = o.condim;
      p.friction = {in.mu, in.mu, 0.0, in.mu_roll, in.mu_roll};
    } else {
      p.condim = c.condim;
      p.friction = c.friction;
    }
    pairs.push_back(p);
  }
  return pairs;
}

std::string pair_name(const GeomRef& geom) {
  return geom.named ? geom.name : "contact2d_geom" + std::to_string(geom.id);
}

std::string pair_attributes(const RestPair& p, const SolverSettings& s) {
  return " condim=\"" + std::to_string(p.condim) + "\" friction=\"" +
         join({p.friction[0], p.friction[1], p.friction[2], p.friction[3], p.friction[4]}) +
         "\" margin=\"" + format_exact(p.margin) + "\" gap=\"" + format_exact(p.gap) +
         "\" solref=\"" + join({s.solref[0], s.solref[1]}) + "\" solimp=\"" +
         join({s.solimp[0], s.solimp[1], s.solimp[2], s.solimp[3], s.solimp[4]}) + "\"";
}

ModelBody read_model_body(const ModelState& state, const std::string& path,
                          const std::string& body) {
  int id = -1;
  for (size_t b = 0; b < state.body_names.size(); ++b)
    if (state.body_names[b] == printable_name(body)) id = static_cast<int>(b);
  if (id <= 0)
    throw InputError("--body " + printable_name(body) + ": " +
                     (id == 0 ? std::string("is the world body, which does not move")
                              : "no body of that name in " + path));
  const auto bi = static_cast<size_t>(id);
  ModelBody out;
  out.version = state.version;
  out.timestep = state.timestep;
  out.mass = state.body_mass[bi];
  out.inv_weight = state.body_invweight0[2 * bi];
  out.load_warning = state.load_warning;
  if (!(out.mass > 0.0))
    throw InputError("--body " + printable_name(body) + ": has mass " + format_number(out.mass) +
                     " kg in " + path + "; it must be > 0");
  if (!(out.inv_weight > 0.0))
    throw InputError("--body " + printable_name(body) + ": body_invweight0 is " +
                     format_number(out.inv_weight) + " in " + path +
                     " (the body has no translational joint)");
  // The joint set, from the body's own joints (a body inside another moving
  // body is none of the four).
  out.joints = state.body_joints[bi];
  int slides = 0, hinges = 0, frees = 0, others = 0;
  for (size_t at = 0; at < out.joints.size();) {
    size_t end = out.joints.find(", ", at);
    if (end == std::string::npos) end = out.joints.size();
    const std::string type = out.joints.substr(at, end - at);
    (type == "free" ? frees : type == "slide" ? slides : type == "hinge" ? hinges : others)++;
    at = end + 2;
  }
  if (state.body_parent[bi] == 0 && others == 0) {
    if (frees == 1 && slides + hinges == 0) out.joint = Joint::Free;
    if (frees == 0 && slides == 2 && hinges <= 1) out.joint = Joint::Planar;
    if (frees == 0 && slides == 1 && hinges == 0) out.joint = Joint::Slide;
    if (frees == 0 && slides == 0 && hinges == 1) out.joint = Joint::Hinge;
  }
  // The friction the snippet keeps when --mu is absent: the body's first
  // colliding geom's, and the model's cone and impratio.
  for (size_t g = 0; g < state.geom_body.size(); ++g) {
    if (state.geom_body[g] != id || !state.geom_collides[g]) continue;
    out.friction.mu = state.geom_mu[g];
    out.friction.condim = state.geom_condim[g];
    out.friction.source = "geom '" + state.geom_names[g] + "' of " + path +
                          ": μ = " + format_number(out.friction.mu) + ", condim " +
                          std::to_string(out.friction.condim);
    break;
  }
  out.friction.elliptic = state.elliptic;
  out.friction.impratio = state.impratio;
  out.friction.noslip_iterations = state.noslip_iterations;
  out.friction.source += std::string(out.friction.elliptic ? ", elliptic" : ", pyramidal") +
                         " cone, impratio " + format_number(out.friction.impratio);
  // The body's contacts in the settled state, as MuJoCo has them: the
  // effective mass at each contact point (the whole chain of joints that
  // moves it) and MuJoCo's own normal force.
  out.settle_seconds = state.settled;
  out.rest_speed = state.speed;
  out.at_rest = at_rest(state);
  std::vector<int> own;
  for (size_t i = 0; i < state.contacts.size(); ++i)
    if (state.contacts[i].body1 == id || state.contacts[i].body2 == id)
      own.push_back(static_cast<int>(i));
  out.tangential_inv_mass = coupled_tangential_inverse_mass(state, own);
  auto ref = [&state](int g) {
    GeomRef r;
    r.id = g;
    r.name = state.geom_names[static_cast<size_t>(g)];
    r.named = r.name != "geom #" + std::to_string(g);  // model_state.hpp's unnamed geom
    const int b = state.geom_body[static_cast<size_t>(g)];
    r.body = state.body_names[static_cast<size_t>(b)];
    for (int k = 0; k < g; ++k) r.index_in_body += state.geom_body[static_cast<size_t>(k)] == b;
    return r;
  };
  for (const StateContact& c : state.contacts) {
    if (c.body1 != id && c.body2 != id) continue;
    SettledContact sc;
    sc.geom1 = state.geom_names[static_cast<size_t>(c.geom1)];
    sc.geom2 = state.geom_names[static_cast<size_t>(c.geom2)];
    sc.ref1 = ref(c.geom1);
    sc.ref2 = ref(c.geom2);
    sc.condim = c.condim;
    sc.friction = c.friction;
    sc.margin = c.margin;
    sc.gap = c.gap;
    sc.explicit_pair = c.explicit_pair;
    sc.A = c.A;
    sc.A_t = c.A_t;
    sc.load = std::max(0.0, c.force);
    sc.penetration = -c.dist;
    sc.inv_weight = state.body_invweight0[2 * static_cast<size_t>(c.body1)] +
                    state.body_invweight0[2 * static_cast<size_t>(c.body2)];
    sc.own = c.body1 == id ? 0 : 1;
    for (size_t k = 0; k < 2; ++k) {
      const auto g = static_cast<size_t>(k == 0 ? c.geom1 : c.geom2);
      sc.priority[k] = state.geom_priority[g];
      sc.geom_solref[k] = {state.geom_solref[2 * g], state.geom_solref[2 * g + 1]};
    }
    out.contacts.push_back(sc);
  }
  out.rest_contacts = static_cast<int>(out.contacts.size());
  // The friction the cone's effect is computed with: the most loaded
  // contact's, as MuJoCo mixed the two geoms (the body's own geom alone
  // says nothing of the partner's larger condim or friction).
  const SettledContact* most = nullptr;
  for (const SettledContact& c : out.contacts)
    if (!most || c.load > most->load) most = &c;
  if (most) {
    out.friction.mu = most->friction[0];
    out.friction.condim = most->condim;
    out.friction.source = "contact " + most->geom1 + " – " + most->geom2 +
                          " as MuJoCo mixes it: μ = " + format_number(most->friction[0]) +
                          ", condim " + std::to_string(most->condim) +
                          (out.friction.elliptic ? ", elliptic" : ", pyramidal") +
                          " cone, impratio " + format_number(out.friction.impratio);
  }
  return out;
}

namespace {

// solref --model: the body's contacts as MuJoCo settled them.
void measured_text(std::ostringstream& o, const SolrefReport& r) {
  const SolrefInput& in = r.input;
  o << "at rest MuJoCo's contacts of the body (" << in.contacts_source << "):\n";
  for (const SettledContact& c : in.settled_contacts)
    o << "  " << c.geom1 << " – " << c.geom2 << ": load " << format_number(c.load) << " N, depth "
      << format_number(c.penetration) << " m, A = " << format_number(c.A)
      << " 1/kg (effective mass " << format_number(1.0 / c.A) << " kg)\n";
  o << "the numbers below are for f = " << format_number(r.load)
    << " N, A = " << format_number(r.inv_mass) << " 1/kg (" << in.measured_source
    << "); f/k = " << format_number(r.load / in.k) << " m\n";
}

// solref --apply: the body's contacts in the applied model.
void applied_text(std::ostringstream& o, const SolrefReport& r) {
  if (!r.applied) return;
  const Applied& a = *r.applied;
  o << "\napplied: " << a.path << " is the model with " << a.mapping << " in " << a.pairs
    << " <pair>" << (a.pairs == 1 ? "" : "s") << " (the geom pairs the body rests on); MuJoCo "
    << r.input.model_version << " settled it " << format_number(a.settled) << " s ("
    << (a.at_rest ? "at rest" : "NOT at rest") << "):\n";
  if (a.contacts.empty()) o << "  the body has no contacts there\n";
  for (const AppliedContact& c : a.contacts) {
    o << "  " << c.geom1 << " – " << c.geom2 << ": load " << format_number(c.load) << " N, depth "
      << format_number(c.penetration);
    if (c.mapped)
      o << " m (the mapping's at that load: " << format_number(c.predicted) << " m, "
        << format_number(100.0 * (c.penetration - c.predicted) / c.predicted) << " %)\n";
    else
      o << " m (not a pair --apply wrote: the model's own contact law)\n";
  }
}

}  // namespace

namespace {

// One mapping's block of the text: its numbers, then the snippets.
void mapping_text(std::ostringstream& o, const SolrefReport& r, const MappingOutcome& m) {
  const SolrefInput& in = r.input;
  o << "\n"
    << mapping_name(m.mapping)
    << (r.recommendation.rfind(std::string(mapping_name(m.mapping)) + ":", 0) == 0
            ? " (recommended)"
            : "")
    << "\n";
  if (!m.unavailable.empty()) {
    o << "  " << (m.mapping == Mapping::Compensated ? "" : "not available: ") << m.unavailable
      << "\n";
    return;
  }
  if (!m.unfit.empty()) o << "  DO NOT USE for a model to build on: " << m.unfit << "\n";
  const SolverSettings& s = m.settings;
  o << "  solref = \"" << join({s.solref[0], s.solref[1]}) << "\"  solimp = \""
    << join({s.solimp[0], s.solimp[1], s.solimp[2], s.solimp[3], s.solimp[4]}) << "\"  cone = "
    << (s.elliptic      ? "elliptic"
        : m.condim == 0 ? "yours (not written)"
                        : "pyramidal")
    << "  impratio = "
    << (m.condim == 1   ? std::string("1 (condim 1: no friction rows)")
        : m.condim == 0 ? "yours (not written)"
                        : format_number(s.impratio))
    << "\n";
  if (s.solref[0] > 0.0) {
    o << "  refsafe: "
      << (s.refsafe_clamped
              ? "BITES: timeconst " + format_number(s.solref[0]) + " s < 2Δt; MuJoCo uses " +
                    format_number(m.timeconst_used) + " s, a softer contact than k"
              : "does not bite (timeconst " + format_number(s.solref[0]) +
                    " s ≥ 2Δt = " + format_number(2.0 * in.dt) + " s)")
      << "\n";
  } else {
    o << "  refsafe: does not apply (direct form)\n";
  }
  if (m.normal_weight != r.inv_weight)
    o << "  pyramidal cone with friction" << (m.condim == 0 ? " (yours)" : "")
      << ": the normal sees Â·μ²(1 + μ²)/((condim − 1)·impratio) "
         "= "
      << format_number(m.normal_weight) << " 1/kg in place of Â (a stiffer contact)\n";
  o << "  MuJoCo: K = " << format_number(m.K) << " 1/s², B = " << format_number(m.B)
    << " 1/s, impedance d = " << format_number(m.impedance) << " (max), "
    << format_number(m.impedance_at_rest) << " at rest\n";
  o << "  natural frequency ω = " << format_number(m.omega)
    << " rad/s, ζ = " << format_number(m.zeta)
    << " (the reference: ω = " << format_number(std::sqrt(in.k * r.inv_mass))
    << ", ζ = " << format_number(in.c * r.inv_mass / (2.0 * std::sqrt(in.k * r.inv_mass))) << ")\n";
  o << "  ω·Δt = " << format_number(m.omega_dt) << ": limit " << format_number(m.euler_limit)
    << " for MuJoCo's Euler and implicit (" << (m.omega_dt < m.euler_limit ? "ok" : "EXCEEDED")
    << "), " << format_number(m.rk4_limit) << " for RK4 ("
    << (m.omega_dt < m.rk4_limit ? "ok" : "EXCEEDED") << ")\n";
  o << "  static penetration = " << format_number(m.static_penetration)
    << " m = " << format_number(m.static_penetration / m.nominal_penetration)
    << " × f/k (per contact)\n";
  if (in.slope)
    o << "  slope " << format_number(*in.slope) << "°: "
      << (std::isfinite(m.creep) ? "creep " + format_number(m.creep) + " m/s" : m.creep_note)
      << "\n";
  o << "  MJCF, a default class (put class=\"contact2d\" on the body's contact geoms; "
    << (m.condim == 0
            ? "solmix 1e30 makes its solref and solimp outweigh the other geom's while "
              "condim, friction, margin and gap mix as before, on every contact of those geoms"
            : "priority 1 makes its condim, friction, solref and solimp win over the other "
              "geom's")
    << "):\n";
  std::istringstream a(m.default_snippet);
  for (std::string line; std::getline(a, line);) o << "    " << line << "\n";
  if (!m.class_caveats.empty()) {
    o << "    NOT SO here (the pairs below hold, and --apply writes them):\n";
    for (const ClassCaveat& c : m.class_caveats)
      o << "      " << c.contact << ": " << c.why << "\n";
  }
  if (in.settled_contacts.empty())
    o << "  or, for a contact with the ground, a pair (replace BODY_GEOM and ground; a pair "
         "takes no condim, friction, margin or gap from its geoms: without them it has "
         "MuJoCo's pair defaults, condim 3, friction 1 1 0.005 0.0001 0.0001):\n";
  else
    o << "  or pairs, one per geom pair the body rests on (only those contacts change; "
      << (m.condim == 0
              ? "condim, friction, margin and gap as MuJoCo " + in.model_version + " mixed them"
              : "margin and gap as MuJoCo " + in.model_version + " mixed them")
      << "):\n";
  std::istringstream b(m.pair_snippet);
  for (std::string line; std::getline(b, line);) o << "    " << line << "\n";
  std::vector<int> told;
  for (const RestPair& p : rest_pairs(in, m)) {
    for (const GeomRef* g : {&p.geom1, &p.geom2}) {
      if (g->named || std::find(told.begin(), told.end(), g->id) != told.end()) continue;
      told.push_back(g->id);
      o << "    (" << g->name << " has no name; a pair needs one: name it " << pair_name(*g)
        << ", geom " << g->index_in_body + 1 << " of body '" << g->body << "')\n";
    }
  }
}

}  // namespace

std::string format_report_text(const SolrefReport& r) {
  const SolrefInput& in = r.input;
  std::ostringstream o;
  if (!r.recommendation.empty())
    o << "Use " << r.recommendation << ".\n";
  else
    o << "No mapping is fit for a model to build on here (calibrated, exact and seed; each "
         "printed below says why).\n";
  o << "\nk = " << format_number(in.k) << " N/m, c = " << format_number(in.c)
    << " N·s/m per MuJoCo contact, Δt = " << format_number(in.dt) << " s"
    << (in.dt_source.empty() ? "" : " (" + in.dt_source + ")") << "; body: " << in.body_source
    << "\n";
  if (!in.targets_note.empty()) o << "from your targets: " << in.targets_note << "\n";
  const bool hinge = in.joint == Joint::Hinge;
  o << "m = " << format_number(in.mass) << " kg; A = "
    << (in.measured      ? "n·J·M⁻¹·Jᵀ·n"
        : hinge          ? "lever²/(I + m·pivot²)"
        : in.lever > 0.0 ? "1/m + r²/I"
                         : "1/m")
    << " = " << format_number(r.inv_mass)
    << " 1/kg (the contact's true inverse mass); Â = body_invweight0 = "
    << format_number(r.inv_weight) << " 1/kg";
  if (in.inv_weight > 0.0) {
    o << " (read from the compiled model)";
  } else {
    static const char* const kWhy[] = {"1/m: a free joint", "2/(3m): slide x, slide z and a hinge",
                                       "1/(3m): one slide joint",
                                       "pivot²/(3·(I + m·pivot²)): one hinge"};
    o << " ("
      << (in.joint == Joint::Slide && in.mujoco3 ? "1/m: slide joints only, MuJoCo 3"
                                                 : kWhy[static_cast<int>(in.joint)])
      << ", --joint " << joint_name(in.joint) << ", as MuJoCo's mj_setConst computes it)";
  }
  o << "\n";
  if (in.measured) {
    measured_text(o, r);
  } else {
    o << "at rest each of " << in.contacts << " MuJoCo contact" << (in.contacts > 1 ? "s" : "")
      << " (" << in.contacts_source << ") carries f = "
      << (hinge ? "m·g·pivot/(lever·" + std::to_string(in.contacts) + ")"
                : "m·g/" + std::to_string(in.contacts))
      << " = " << format_number(r.load) << " N; f/k = " << format_number(r.load / in.k) << " m\n";
  }
  if (in.keep_friction)
    o << "friction: no --mu, so the snippets write no condim and no friction: your geoms keep "
         "theirs (the pyramidal cone's effect on the rest depth is computed with "
      << in.user_friction.source << "); --mu writes them\n";
  for (const MappingOutcome& m : r.mappings) mapping_text(o, r, m);
  if (!r.fit_hint.empty()) o << "\n" << r.fit_hint << "\n";
  applied_text(o, r);
  return o.str();
}

std::string format_report_json(const SolrefReport& r) {
  const SolrefInput& in = r.input;
  std::ostringstream o;
  o << "{\n  \"k\": " << json::number(in.k) << ",\n  \"c\": " << json::number(in.c)
    << ",\n  \"dt\": " << json::number(in.dt) << ",\n  \"mass\": " << json::number(in.mass)
    << ",\n  \"inertia\": " << json::number(in.inertia)
    << ",\n  \"lever\": " << json::number(in.lever) << ",\n  \"mu\": " << json::number(in.mu)
    << ",\n  \"mu_roll\": " << json::number(in.mu_roll) << ",\n  \"joint\": \""
    << joint_name(in.joint) << "\",\n  \"pivot\": " << json::number(in.pivot)
    << ",\n  \"friction_kept\": " << (in.keep_friction ? "true" : "false")
    << ",\n  \"contacts\": " << in.contacts
    << ",\n  \"contacts_source\": " << json::string(in.contacts_source)
    << ",\n  \"body\": " << json::string(in.body_source)
    << ",\n  \"targets\": " << json::string(in.targets_note)
    << ",\n  \"inv_mass\": " << json::number(r.inv_mass)
    << ",\n  \"body_invweight0\": " << json::number(r.inv_weight)
    << ",\n  \"load_per_contact\": " << json::number(r.load)
    << ",\n  \"measured\": " << (in.measured ? json::string(in.measured_source) : "null")
    << ",\n  \"settled_contacts\": [";
  for (size_t i = 0; i < in.settled_contacts.size(); ++i) {
    const SettledContact& c = in.settled_contacts[i];
    o << (i ? ", " : "") << "{\"geom1\": " << json::string(c.geom1)
      << ", \"geom2\": " << json::string(c.geom2) << ", \"load\": " << json::number(c.load)
      << ", \"penetration\": " << json::number(c.penetration) << ", \"A\": " << json::number(c.A)
      << "}";
  }
  o << "]"
    << ",\n  \"nominal_penetration\": " << json::number(r.load / in.k)
    << ",\n  \"recommendation\": " << json::string(r.recommendation)
    << ",\n  \"fit_hint\": " << json::string(r.fit_hint)
    << ",\n  \"dt_source\": " << json::string(in.dt_source.empty() ? "--dt" : in.dt_source)
    << ",\n  \"mappings\": [";
  bool first = true;
  for (const MappingOutcome& m : r.mappings) {
    o << (first ? "\n" : ",\n") << "    {\n      \"mapping\": \"" << mapping_name(m.mapping)
      << "\"";
    first = false;
    if (!m.unavailable.empty()) {
      o << ",\n      \"unavailable\": " << json::string(m.unavailable) << "\n    }";
      continue;
    }
    const SolverSettings& s = m.settings;
    o << ",\n      \"unfit\": " << json::string(m.unfit);
    o << ",\n      \"solref\": [" << json::number(s.solref[0]) << ", " << json::number(s.solref[1])
      << "],\n      \"solimp\": [";
    for (size_t i = 0; i < s.solimp.size(); ++i) o << (i ? ", " : "") << json::number(s.solimp[i]);
    o << "],\n      \"cone\": \"" << (s.elliptic ? "elliptic" : "pyramidal")
      << "\",\n      \"impratio\": " << json::number(s.impratio)
      << ",\n      \"condim\": " << m.condim
      << ",\n      \"refsafe_bites\": " << (s.refsafe_clamped ? "true" : "false")
      << ",\n      \"timeconst_used\": "
      << (s.solref[0] > 0.0 ? json::number(m.timeconst_used) : "null")
      << ",\n      \"K\": " << json::number(m.K) << ",\n      \"B\": " << json::number(m.B)
      << ",\n      \"normal_weight\": " << json::number(m.normal_weight)
      << ",\n      \"impedance\": " << json::number(m.impedance)
      << ",\n      \"impedance_at_rest\": " << json::number(m.impedance_at_rest)
      << ",\n      \"omega\": " << json::number(m.omega)
      << ",\n      \"zeta\": " << json::number(m.zeta)
      << ",\n      \"omega_dt\": " << json::number(m.omega_dt)
      << ",\n      \"euler_limit\": " << json::number(m.euler_limit)
      << ",\n      \"rk4_limit\": " << json::number(m.rk4_limit)
      << ",\n      \"static_penetration\": " << json::number(m.static_penetration)
      << ",\n      \"creep\": " << (std::isfinite(m.creep) ? json::number(m.creep) : "null")
      << ",\n      \"creep_note\": " << json::string(m.creep_note)
      << ",\n      \"default_snippet\": " << json::string(m.default_snippet)
      << ",\n      \"default_snippet_fails\": [";
    for (size_t i = 0; i < m.class_caveats.size(); ++i) {
      const ClassCaveat& c = m.class_caveats[i];
      o << (i ? ", " : "") << "{\"case\": " << json::string(c.kind)
        << ", \"contact\": " << json::string(c.contact) << ", \"why\": " << json::string(c.why)
        << "}";
    }
    o << "]"
      << ",\n      \"pair_snippet\": " << json::string(m.pair_snippet) << "\n    }";
  }
  o << "\n  ]";
  o << ",\n  \"applied\": ";
  if (!r.applied) {
    o << "null";
  } else {
    const Applied& a = *r.applied;
    o << "{\"path\": " << json::string(a.path) << ", \"mapping\": " << json::string(a.mapping)
      << ", \"pairs\": " << a.pairs << ", \"settled\": " << json::number(a.settled)
      << ", \"at_rest\": " << (a.at_rest ? "true" : "false") << ", \"settled_contacts\": [";
    for (size_t i = 0; i < a.contacts.size(); ++i) {
      const AppliedContact& c = a.contacts[i];
      o << (i ? ", " : "") << "{\"geom1\": " << json::string(c.geom1)
        << ", \"geom2\": " << json::string(c.geom2) << ", \"load\": " << json::number(c.load)
        << ", \"penetration\": " << json::number(c.penetration)
        << ", \"predicted\": " << (c.mapped ? json::number(c.predicted) : "null")
        << ", \"mapped\": " << (c.mapped ? "true" : "false") << "}";
    }
    o << "]}";
  }
  o << "\n}\n";
  return o.str();
}

}  // namespace contact2d::mujoco
