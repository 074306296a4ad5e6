// `contact2d solref` (mujoco/solref_tool.hpp).
#include "mujoco/solref_tool.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <fstream>
#include <sstream>

#include "core/format.hpp"
#include "core/input_error.hpp"
#include "core/integrators.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/model.hpp"

namespace contact2d::mujoco {
namespace {

constexpr double kMinImp = 1e-4;    // MuJoCo's mjMINIMP
constexpr double kMaxImp = 0.9999;  // MuJoCo's mjMAXIMP
constexpr double kMinVal = 1e-15;   // MuJoCo's mjMINVAL

std::string g(double v) { return format_number(v, 6); }

void require(bool ok, const std::string& option, double value, const std::string& range) {
  if (!ok) throw InputError(option + " " + format_number(value, 6) + ": must be " + range);
}

std::string join(const std::vector<double>& values) {
  std::string out;
  for (double v : values) out += (out.empty() ? "" : " ") + format_exact(v);
  return out;
}

int condim_for(const SolrefInput& in) {
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
  if (condim == 1) return "";
  const std::vector<double> values =
      pair ? std::vector<double>{in.mu, in.mu, 0.0, in.mu_roll, in.mu_roll}
           : std::vector<double>{in.mu, 0.0, in.mu_roll};
  return " friction=\"" + join(values) + "\"";
}

std::string contact_attributes(const SolrefInput& in, const MappingOutcome& o, bool pair) {
  const SolverSettings& s = o.settings;
  return " condim=\"" + std::to_string(o.condim) + "\"" + friction_attribute(in, o.condim, pair) +
         " solref=\"" + join({s.solref[0], s.solref[1]}) + "\" solimp=\"" +
         join({s.solimp[0], s.solimp[1], s.solimp[2], s.solimp[3], s.solimp[4]}) + "\"";
}

MappingOutcome outcome(const SolrefReport& report, Mapping mapping) {
  const SolrefInput& in = report.input;
  MappingOutcome o;
  o.mapping = mapping;
  o.condim = condim_for(in);
  ContactParams contact;
  contact.k = in.k;
  contact.c = in.c;
  contact.mu = in.mu;
  contact.mu_roll = in.mu_roll;
  RigidBody body;
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
  if (o.condim == 1) o.settings.impratio = 1.0;  // no friction rows: not written, MuJoCo's 1
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
  o.normal_weight = report.inv_weight;
  if (!s.elliptic && o.condim > 1) {
    const double mu = std::max(in.mu, 1e-5);  // MuJoCo's mjMINMU
    o.normal_weight *= mu * mu * (1.0 + mu * mu) / ((o.condim - 1) * s.impratio);
  }
  const double A = report.inv_mass, Ahat = o.normal_weight, d = dmax;
  const double denominator = d * A + (1.0 - d) * Ahat;
  o.omega = std::sqrt(A * d * d * o.K / denominator);
  o.zeta = A * d * o.B / denominator / (2.0 * o.omega);
  o.omega_dt = o.omega * in.dt;
  o.euler_limit = stability_limit(Integrator::SemiImplicitEuler, o.zeta);
  o.rk4_limit = stability_limit(Integrator::RK4, o.zeta);
  o.static_penetration = static_penetration(s.solimp, o.K, Ahat, report.load);
  o.impedance_at_rest = mujoco_impedance(s.solimp, -o.static_penetration);
  o.nominal_penetration = report.load / in.k;
  const std::string options = option_line(o);
  o.default_snippet = options + "<default>\n  <default class=\"contact2d\">\n    <geom" +
                      contact_attributes(in, o, false) +
                      " priority=\"1\"/>\n  </default>\n</default>\n";
  o.pair_snippet = options + "<contact>\n  <pair geom1=\"BODY_GEOM\" geom2=\"ground\"" +
                   contact_attributes(in, o, true) + "/>\n</contact>\n";
  return o;
}

std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (char ch : text) {
    if (ch == '"' || ch == '\\') {
      out += '\\';
      out += ch;
    } else if (ch == '\n') {
      out += "\\n";
    } else {
      out += ch;
    }
  }
  return out + "\"";
}

// The shortest text that reads back as the same double; null when not finite.
std::string json_number(double v) { return std::isfinite(v) ? format_exact(v) : "null"; }

}  // namespace

void validate(const SolrefInput& in) {
  auto finite = [](double v) { return std::isfinite(v); };
  require(finite(in.k) && in.k > 0.0, "--k", in.k, "a finite number > 0 (N/m)");
  require(finite(in.c) && in.c >= 0.0, "--c", in.c, "a finite number >= 0 (N·s/m)");
  require(finite(in.dt) && in.dt > 0.0, "--dt", in.dt, "a finite number > 0 (s)");
  require(finite(in.mass) && in.mass > 0.0, "--mass", in.mass, "a finite number > 0 (kg)");
  require(finite(in.inertia) && in.inertia >= 0.0, "--inertia", in.inertia,
          "a finite number >= 0 (kg·m²)");
  require(finite(in.lever) && in.lever >= 0.0, "--lever", in.lever, "a finite number >= 0 (m)");
  if (in.lever > 0.0 && !(in.inertia > 0.0))
    throw InputError("--lever " + g(in.lever) + ": needs --inertia > 0 (the body must rotate)");
  require(finite(in.mu) && in.mu >= 0.0, "--mu", in.mu, "a finite number >= 0");
  require(finite(in.mu_roll) && in.mu_roll >= 0.0, "--mu-roll", in.mu_roll,
          "a finite number >= 0 (m)");
  if (in.mu_roll > 0.0 && !(in.lever > 0.0))
    throw InputError("--mu-roll " + g(in.mu_roll) +
                     ": needs --inertia and --lever > 0 (the rolling radius)");
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

SolrefReport solref_report(const SolrefInput& input, const std::vector<Mapping>& mappings) {
  validate(input);
  SolrefReport report;
  report.input = input;
  report.inv_mass =
      1.0 / input.mass + (input.inertia > 0.0 ? input.lever * input.lever / input.inertia : 0.0);
  report.inv_weight = input.inv_weight > 0.0 ? input.inv_weight : 2.0 / (3.0 * input.mass);
  report.load = input.mass * input.gravity / input.contacts;
  for (Mapping mapping : mappings) report.mappings.push_back(outcome(report, mapping));
  return report;
}

ModelBody read_model_body(const std::string& path, const std::string& body) {
  std::ifstream file(path);
  if (!file) throw InputError("--model " + path + ": cannot open the file");
  std::vector<std::string> warnings;
  WarningCapture capture(warnings);
  char error[1000] = "";
  mjModel* raw = nullptr;
  try {
    raw = mj_loadXML(path.c_str(), nullptr, error, sizeof error);
  } catch (const MujocoError& e) {
    throw InputError("--model " + path + ": MuJoCo cannot load the model: " + e.what());
  }
  if (!raw) {
    std::string text = error;
    std::replace(text.begin(), text.end(), '\n', ' ');
    throw InputError("--model " + path + ": MuJoCo cannot load the model: " + text);
  }
  const ModelPtr model(raw);
  const int id = mj_name2id(model.get(), mjOBJ_BODY, body.c_str());
  if (id <= 0)
    throw InputError("--body " + body + ": " +
                     (id == 0 ? std::string("is the world body, which does not move")
                              : "no body of that name in " + path));
  ModelBody out;
  out.mass = model->body_mass[id];
  out.inv_weight = model->body_invweight0[2 * static_cast<std::ptrdiff_t>(id)];
  std::string warning = error;
  for (const std::string& w : warnings) warning += (warning.empty() ? "" : "; ") + w;
  std::replace(warning.begin(), warning.end(), '\n', ' ');
  out.load_warning = warning;
  if (!(out.mass > 0.0))
    throw InputError("--body " + body + ": has mass " + g(out.mass) + " kg in " + path +
                     "; it must be > 0");
  if (!(out.inv_weight > 0.0))
    throw InputError("--body " + body + ": body_invweight0 is " + g(out.inv_weight) + " in " +
                     path + " (the body has no translational joint)");
  return out;
}

std::string format_report_text(const SolrefReport& r) {
  const SolrefInput& in = r.input;
  std::ostringstream o;
  o << "k = " << g(in.k) << " N/m, c = " << g(in.c) << " N·s/m, Δt = " << g(in.dt)
    << " s; body: " << in.body_source << "\n";
  o << "m = " << g(in.mass) << " kg; A = 1/m" << (in.lever > 0.0 ? " + r²/I" : "") << " = "
    << g(r.inv_mass)
    << " 1/kg (the contact's true inverse mass); Â = body_invweight0 = " << g(r.inv_weight)
    << " 1/kg"
    << (in.inv_weight > 0.0 ? " (read from the compiled model)"
                            : " (2/(3m): slide joints along x and z, as contact2d generates)")
    << "\n";
  o << "at rest each of " << in.contacts << " contact" << (in.contacts > 1 ? "s" : "")
    << " carries f = m·g/" << in.contacts << " = " << g(r.load) << " N; f/k = " << g(r.load / in.k)
    << " m\n";
  for (const MappingOutcome& m : r.mappings) {
    o << "\n"
      << mapping_name(m.mapping) << (m.mapping == kDefaultMapping ? " (the default mapping)" : "")
      << "\n";
    if (!m.unavailable.empty()) {
      o << "  not available: " << m.unavailable << "\n";
      continue;
    }
    const SolverSettings& s = m.settings;
    o << "  solref = \"" << join({s.solref[0], s.solref[1]}) << "\"  solimp = \""
      << join({s.solimp[0], s.solimp[1], s.solimp[2], s.solimp[3], s.solimp[4]})
      << "\"  cone = " << (s.elliptic ? "elliptic" : "pyramidal") << "  impratio = "
      << (m.condim == 1 ? std::string("1 (condim 1: no friction rows)") : g(s.impratio)) << "\n";
    if (s.solref[0] > 0.0) {
      o << "  refsafe: "
        << (s.refsafe_clamped ? "BITES: timeconst " + g(s.solref[0]) + " s < 2Δt; MuJoCo uses " +
                                    g(m.timeconst_used) + " s, a softer contact than k"
                              : "does not bite (timeconst " + g(s.solref[0]) +
                                    " s ≥ 2Δt = " + g(2.0 * in.dt) + " s)")
        << "\n";
    } else {
      o << "  refsafe: does not apply (direct form)\n";
    }
    if (m.normal_weight != r.inv_weight)
      o << "  pyramidal cone with friction: the normal sees Â·μ²(1 + μ²)/((condim − 1)·impratio) "
           "= "
        << g(m.normal_weight) << " 1/kg in place of Â (a stiffer contact)\n";
    o << "  MuJoCo: K = " << g(m.K) << " 1/s², B = " << g(m.B)
      << " 1/s, impedance d = " << g(m.impedance) << " (max), " << g(m.impedance_at_rest)
      << " at rest\n";
    o << "  natural frequency ω = " << g(m.omega) << " rad/s, ζ = " << g(m.zeta)
      << " (the reference: ω = " << g(std::sqrt(in.k * r.inv_mass))
      << ", ζ = " << g(in.c * r.inv_mass / (2.0 * std::sqrt(in.k * r.inv_mass))) << ")\n";
    o << "  ω·Δt = " << g(m.omega_dt) << ": limit " << g(m.euler_limit)
      << " for MuJoCo's Euler and implicit (" << (m.omega_dt < m.euler_limit ? "ok" : "EXCEEDED")
      << "), " << g(m.rk4_limit) << " for RK4 (" << (m.omega_dt < m.rk4_limit ? "ok" : "EXCEEDED")
      << ")\n";
    o << "  static penetration = " << g(m.static_penetration)
      << " m = " << g(m.static_penetration / m.nominal_penetration) << " × f/k\n";
    o << "  MJCF, a default class (put class=\"contact2d\" on the body's contact geoms; "
         "priority 1 makes its values win over the ground's):\n";
    std::istringstream a(m.default_snippet);
    for (std::string line; std::getline(a, line);) o << "    " << line << "\n";
    o << "  or, for a contact with the ground, a pair (replace BODY_GEOM and ground):\n";
    std::istringstream b(m.pair_snippet);
    for (std::string line; std::getline(b, line);) o << "    " << line << "\n";
  }
  return o.str();
}

std::string format_report_json(const SolrefReport& r) {
  const SolrefInput& in = r.input;
  std::ostringstream o;
  o << "{\n  \"k\": " << json_number(in.k) << ",\n  \"c\": " << json_number(in.c)
    << ",\n  \"dt\": " << json_number(in.dt) << ",\n  \"mass\": " << json_number(in.mass)
    << ",\n  \"inertia\": " << json_number(in.inertia)
    << ",\n  \"lever\": " << json_number(in.lever) << ",\n  \"mu\": " << json_number(in.mu)
    << ",\n  \"mu_roll\": " << json_number(in.mu_roll) << ",\n  \"contacts\": " << in.contacts
    << ",\n  \"body\": " << json_string(in.body_source)
    << ",\n  \"inv_mass\": " << json_number(r.inv_mass)
    << ",\n  \"body_invweight0\": " << json_number(r.inv_weight)
    << ",\n  \"load_per_contact\": " << json_number(r.load)
    << ",\n  \"nominal_penetration\": " << json_number(r.load / in.k) << ",\n  \"mappings\": [";
  bool first = true;
  for (const MappingOutcome& m : r.mappings) {
    o << (first ? "\n" : ",\n") << "    {\n      \"mapping\": \"" << mapping_name(m.mapping)
      << "\"";
    first = false;
    if (!m.unavailable.empty()) {
      o << ",\n      \"unavailable\": " << json_string(m.unavailable) << "\n    }";
      continue;
    }
    const SolverSettings& s = m.settings;
    o << ",\n      \"solref\": [" << json_number(s.solref[0]) << ", " << json_number(s.solref[1])
      << "],\n      \"solimp\": [";
    for (size_t i = 0; i < s.solimp.size(); ++i) o << (i ? ", " : "") << json_number(s.solimp[i]);
    o << "],\n      \"cone\": \"" << (s.elliptic ? "elliptic" : "pyramidal")
      << "\",\n      \"impratio\": " << json_number(s.impratio)
      << ",\n      \"condim\": " << m.condim
      << ",\n      \"refsafe_bites\": " << (s.refsafe_clamped ? "true" : "false")
      << ",\n      \"timeconst_used\": "
      << (s.solref[0] > 0.0 ? json_number(m.timeconst_used) : "null")
      << ",\n      \"K\": " << json_number(m.K) << ",\n      \"B\": " << json_number(m.B)
      << ",\n      \"normal_weight\": " << json_number(m.normal_weight)
      << ",\n      \"impedance\": " << json_number(m.impedance)
      << ",\n      \"impedance_at_rest\": " << json_number(m.impedance_at_rest)
      << ",\n      \"omega\": " << json_number(m.omega)
      << ",\n      \"zeta\": " << json_number(m.zeta)
      << ",\n      \"omega_dt\": " << json_number(m.omega_dt)
      << ",\n      \"euler_limit\": " << json_number(m.euler_limit)
      << ",\n      \"rk4_limit\": " << json_number(m.rk4_limit)
      << ",\n      \"static_penetration\": " << json_number(m.static_penetration)
      << ",\n      \"default_snippet\": " << json_string(m.default_snippet)
      << ",\n      \"pair_snippet\": " << json_string(m.pair_snippet) << "\n    }";
  }
  o << "\n  ]\n}\n";
  return o.str();
}

}  // namespace contact2d::mujoco
