#include "analysis/compare_run.hpp"

#include <sstream>

#include "io/json.hpp"

namespace contact2d::analysis {

namespace mj = contact2d::mujoco;

Comparison prepare_comparison(const Scene& scene, const engines::EngineSpec& spec) {
  Comparison c;
  c.scene = scene;
  c.spec = spec;
  c.mjcf = mj::mjcf_options(spec.mapping, spec.geometry, spec.source);
  c.mjcf.model_dt = spec.model_dt;
  mj::mujoco_integrator(c.scene.sim.integrator);  // explicit Euler: fail before any work
  return c;
}

void run_engines(Comparison& c) {
  c.mujoco = engines::run_engine(c.spec, c.scene);
  c.ref = engines::run_engine(engines::parse_engine("ref"), c.scene);
}

std::vector<RunProblem> run_problems(const Comparison& c) {
  const std::pair<const char*, const engines::EngineRun*> runs[] = {{"ref", &c.ref},
                                                                    {"MuJoCo", &c.mujoco}};
  std::vector<RunProblem> problems;
  for (const auto& [name, run] : runs)
    if (run->trajectory.divergence) problems.push_back({name, true, run->divergence_message});
  if (!problems.empty()) return problems;
  for (const auto& [name, run] : runs) {
    std::string reason = nonphysical(run->trajectory, c.scene);
    if (!reason.empty()) problems.push_back({name, false, std::move(reason)});
  }
  return problems;
}

void measure(Comparison& c, double converged_tol, bool diagnosis) {
  c.three = three_way(c.scene, c.ref.trajectory, c.mujoco.trajectory, converged_tol);
  c.errors = c.three.ref_vs_mujoco;
  if (diagnosis) c.diagnosis = diagnose(c.scene, c.spec, c.ref, c.mujoco, c.three);
}

Energies energies(const Scene& scene, const Trajectory& t) {
  const Model model = make_model(scene);
  return {energy(model, t.samples.front().state), energy(model, t.samples.back().state)};
}

namespace {

// `prefix`_max_pos_err, …: one pair's distances (null when not measured).
void json_errors(std::ostringstream& o, const std::string& prefix, const TrajectoryError& e,
                 bool measured) {
  auto n = [measured](double v) { return measured ? json::number(v, 10) : std::string("null"); };
  o << ", \"" << prefix << "_max_pos_err\": " << n(e.max_pos) << ", \"" << prefix
    << "_rms_pos_err\": " << n(e.rms_pos) << ", \"" << prefix << "_end_pos_err\": " << n(e.end_pos)
    << ", \"" << prefix << "_max_angle_err\": " << n(e.max_angle) << ", \"" << prefix
    << "_end_angle_err\": " << n(e.end_angle) << ", \"" << prefix
    << "_max_vel_err\": " << n(e.max_vel) << ", \"" << prefix
    << "_max_omega_err\": " << n(e.max_omega);
}

void json_diagnosis(std::ostringstream& o, const Diagnosis& d) {
  o << ", \"diagnosis_ran\": " << (d.ran ? "true" : "false")
    << ", \"agrees\": " << (d.agrees ? "true" : "false")
    << ", \"diagnosis_summary\": " << json::string(d.summary) << ", \"diagnosis\": [";
  bool first = true;
  for (const Finding& f : d.findings) {
    if (!f.named) continue;
    o << (first ? "" : ", ");
    first = false;
    o << "{\"cause\": " << json::string(f.cause) << ", \"share\": " << json::number(f.share, 10)
      << ", \"before\": " << json::number(f.before, 10)
      << ", \"after\": " << json::number(f.after, 10) << ", \"fix\": " << json::string(f.fix)
      << ", \"explanation\": " << json::string(f.explanation);
    if (f.cause == "friction") {
      o << ", \"sliding_phases\": [";
      for (size_t i = 0; i < f.phases.size(); ++i)
        o << (i ? ", " : "") << "{\"t0\": " << json::number(f.phases[i].t0, 10)
          << ", \"t1\": " << json::number(f.phases[i].t1, 10)
          << ", \"distance0\": " << json::number(f.phases[i].distance0, 10)
          << ", \"distance1\": " << json::number(f.phases[i].distance1, 10) << "}";
      o << "]";
    }
    o << "}";
  }
  o << "], \"ruled_out\": [";
  first = true;
  for (const Finding& f : d.findings) {
    if (f.named) continue;
    o << (first ? "" : ", ") << "{\"cause\": " << json::string(f.cause)
      << ", \"share\": " << json::number(f.share, 10)
      << ", \"after\": " << json::number(f.after, 10) << "}";
    first = false;
  }
  o << "]";
}

}  // namespace

std::string comparison_json(const Comparison& c, const std::string& scene_label) {
  const Energies er = energies(c.scene, c.ref.trajectory);
  const Energies em = energies(c.scene, c.mujoco.trajectory);
  const TrajectoryError& e = c.errors;
  const ConvergedSolution& conv = c.three.converged;
  std::ostringstream o;
  o << "{\"scene\": " << json::string(scene_label) << ", \"shape\": \"" << shape_name(c.scene.shape)
    << "\""
    << ", \"mapping\": \"" << mj::mapping_name(c.mjcf.mapping) << "\", \"geometry\": \""
    << mj::geometry_name(c.mjcf.geometry) << "\", \"damping\": \""
    << (c.scene.contact.damping == DampingLaw::Compression ? "compression" : "kelvin_voigt") << "\""
    << ", \"friction_law\": \"" << friction_law_name(c.scene.contact.friction) << "\""
    << ", \"integrators\": {\"ref\": \"" << integrator_name(c.scene.sim.integrator)
    << "\", \"mujoco\": \"" << mj::mujoco_integrator(c.scene.sim.integrator) << "\"}"
    << ", \"dt\": " << json::number(c.scene.sim.dt, 10)
    << ", \"duration\": " << json::number(c.scene.sim.duration, 10)
    << ", \"samples\": " << e.samples << ", \"max_pos_err\": " << json::number(e.max_pos, 10)
    << ", \"rms_pos_err\": " << json::number(e.rms_pos, 10)
    << ", \"max_angle_err\": " << json::number(e.max_angle, 10)
    << ", \"max_vel_err\": " << json::number(e.max_vel, 10)
    << ", \"max_omega_err\": " << json::number(e.max_omega, 10)
    << ", \"end_pos_err\": " << json::number(e.end_pos, 10)
    << ", \"end_angle_err\": " << json::number(e.end_angle, 10)
    << ", \"time_of_max_pos_err\": " << json::number(e.time_of_max_pos, 10) << ", \"ref_energy\": ["
    << json::number(er.initial, 10) << ", " << json::number(er.final, 10) << "]"
    << ", \"mujoco_energy\": [" << json::number(em.initial, 10) << ", "
    << json::number(em.final, 10) << "]"
    << ", \"ref_seconds\": " << json::number(c.ref.seconds, 10)
    << ", \"mujoco_seconds\": " << json::number(c.mujoco.seconds, 10) << ", \"solref\": ["
    << json::number(c.mujoco.solref[0], 10) << ", " << json::number(c.mujoco.solref[1], 10) << "]"
    << ", \"impratio\": " << json::number(c.mujoco.impratio, 10) << ", \"mujoco_warnings\": [";
  for (size_t i = 0; i < c.mujoco.warnings.size(); ++i)
    o << (i ? ", " : "") << json::string(c.mujoco.warnings[i]);
  o << "], \"converged_tol\": " << json::number(conv.tol, 10)
    << ", \"converged_available\": " << (conv.available ? "true" : "false")
    << ", \"converged_why_not\": " << (conv.available ? "null" : json::string(conv.why_not))
    << ", \"converged_own_error\": "
    << (conv.available ? json::number(conv.own_error, 10) : std::string("null"))
    << ", \"converged_seconds\": " << json::number(conv.seconds, 10) << ", \"amplification\": "
    << (conv.available ? json::number(conv.amplification, 10) : std::string("null"));
  json_errors(o, "ref_vs_converged", c.three.ref_vs_converged, conv.available);
  json_errors(o, "mujoco_vs_converged", c.three.mujoco_vs_converged, conv.available);
  json_errors(o, "ref_vs_mujoco", c.three.ref_vs_mujoco, true);
  json_diagnosis(o, c.diagnosis);
  o << "}\n";
  return o.str();
}

}  // namespace contact2d::analysis
