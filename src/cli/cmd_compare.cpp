// contact2d compare SCENE [--mapping NAME] [--geometry NAME] [--csv FILE] [--json] [--plot
// FILE.png] [overrides]
//
// Runs the reference solver and MuJoCo on the same scene (same Δt, same
// sample times) and reports their differences (analysis/trajectory_error.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <utility>

#include "analysis/trajectory_error.hpp"
#include "cli/common.hpp"
#include "core/input_error.hpp"
#include "io/csv.hpp"
#include "io/plot.hpp"
#include "mujoco/mjcf.hpp"

namespace contact2d::cli {
namespace {

namespace mj = contact2d::mujoco;

struct CompareOptions {
  SceneOptions scene;
  MujocoOptions mujoco;
  std::string csv;
  std::string plot;
  bool json = false;
};

struct Comparison {
  Scene scene;
  mj::MjcfOptions mjcf;
  engines::EngineRun ref;
  engines::EngineRun mujoco;
  analysis::TrajectoryError errors;
};

struct Energies {
  double initial = 0.0;
  double final = 0.0;
};

Energies energies(const Scene& scene, const Trajectory& t) {
  const Model model = make_model(scene);
  return {energy(model, t.samples.front().state), energy(model, t.samples.back().state)};
}

std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (char ch : text) {
    if (ch == '"' || ch == '\\') out += '\\';
    if (static_cast<unsigned char>(ch) < 0x20) {
      out += ' ';
      continue;
    }
    out += ch;
  }
  return out + "\"";
}

std::string json_number(double v) { return std::isfinite(v) ? format_number(v, 10) : "null"; }

void print_json(const Comparison& c, const std::string& path) {
  const Energies er = energies(c.scene, c.ref.trajectory);
  const Energies em = energies(c.scene, c.mujoco.trajectory);
  const analysis::TrajectoryError& e = c.errors;
  std::ostringstream o;
  o << "{\"scene\": " << json_string(path) << ", \"shape\": \"" << shape_name(c.scene.shape) << "\""
    << ", \"mapping\": \"" << mj::mapping_name(c.mjcf.mapping) << "\", \"geometry\": \""
    << mj::geometry_name(c.mjcf.geometry) << "\", \"damping\": \""
    << (c.scene.contact.damping == DampingLaw::Compression ? "compression" : "kelvin_voigt") << "\""
    << ", \"integrators\": {\"ref\": \"" << integrator_name(c.scene.sim.integrator)
    << "\", \"mujoco\": \"" << mj::mujoco_integrator(c.scene.sim.integrator) << "\"}"
    << ", \"dt\": " << json_number(c.scene.sim.dt)
    << ", \"duration\": " << json_number(c.scene.sim.duration) << ", \"samples\": " << e.samples
    << ", \"max_pos_err\": " << json_number(e.max_pos)
    << ", \"rms_pos_err\": " << json_number(e.rms_pos)
    << ", \"max_angle_err\": " << json_number(e.max_angle)
    << ", \"max_vel_err\": " << json_number(e.max_vel)
    << ", \"max_omega_err\": " << json_number(e.max_omega)
    << ", \"end_pos_err\": " << json_number(e.end_pos)
    << ", \"end_angle_err\": " << json_number(e.end_angle)
    << ", \"time_of_max_pos_err\": " << json_number(e.time_of_max_pos) << ", \"ref_energy\": ["
    << json_number(er.initial) << ", " << json_number(er.final) << "]"
    << ", \"mujoco_energy\": [" << json_number(em.initial) << ", " << json_number(em.final) << "]"
    << ", \"ref_seconds\": " << json_number(c.ref.seconds)
    << ", \"mujoco_seconds\": " << json_number(c.mujoco.seconds) << ", \"solref\": ["
    << json_number(c.mujoco.solref[0]) << ", " << json_number(c.mujoco.solref[1]) << "]"
    << ", \"impratio\": " << json_number(c.mujoco.impratio) << ", \"mujoco_warnings\": [";
  for (size_t i = 0; i < c.mujoco.warnings.size(); ++i)
    o << (i ? ", " : "") << json_string(c.mujoco.warnings[i]);
  o << "]}\n";
  std::cout << o.str();
}

void print_table(const Comparison& c) {
  const Energies er = energies(c.scene, c.ref.trajectory);
  const Energies em = energies(c.scene, c.mujoco.trajectory);
  const analysis::TrajectoryError& e = c.errors;
  auto f = [](double v) { return format_number(v, 4); };
  std::cout << shape_name(c.scene.shape) << ": ref " << integrator_name(c.scene.sim.integrator)
            << " vs MuJoCo " << mj::mujoco_integrator(c.scene.sim.integrator) << ", mapping "
            << mj::mapping_name(c.mjcf.mapping) << ", geometry "
            << mj::geometry_name(c.mjcf.geometry) << ", dt = " << f(c.scene.sim.dt) << " s, "
            << e.samples << " samples over " << f(c.scene.sim.duration) << " s\n"
            << "  max position error   " << f(e.max_pos) << " m (at t = " << f(e.time_of_max_pos)
            << " s)\n"
            << "  RMS position error   " << f(e.rms_pos) << " m\n"
            << "  max angle error      " << f(e.max_angle) << " rad\n"
            << "  max velocity error   " << f(e.max_vel) << " m/s, omega " << f(e.max_omega)
            << " rad/s\n"
            << "  end error            " << f(e.end_pos) << " m, " << f(e.end_angle) << " rad\n"
            << "  energy ref           " << f(er.initial) << " -> " << f(er.final) << " J\n"
            << "  energy MuJoCo        " << f(em.initial) << " -> " << f(em.final) << " J\n"
            << "  wall clock           ref " << f(c.ref.seconds) << " s, MuJoCo "
            << f(c.mujoco.seconds) << " s\n";
}

void write_csv(AtomicFile& out, const Comparison& c) {
  std::fprintf(out.get(),
               "t,x_ref,y_ref,theta_ref,vx_ref,vy_ref,omega_ref,"
               "x_mujoco,y_mujoco,theta_mujoco,vx_mujoco,vy_mujoco,omega_mujoco\n");
  const auto& a = c.ref.trajectory.samples;
  const auto& b = c.mujoco.trajectory.samples;
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    const State& r = a[i].state;
    const State& m = b[i].state;
    std::fprintf(out.get(),
                 "%.10g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g\n",
                 a[i].t, r.q.x(), r.q.y(), r.q.z(), r.v.x(), r.v.y(), r.v.z(), m.q.x(), m.q.y(),
                 m.q.z(), m.v.x(), m.v.y(), m.v.z());
  }
  out.commit();
}

// Reports a divergence of either engine; true when one diverged.
bool report_divergence(const Comparison& c, const std::string& path) {
  bool diverged = false;
  for (const auto& [name, run] : {std::pair{"ref", &c.ref}, std::pair{"MuJoCo", &c.mujoco}}) {
    if (!run->trajectory.divergence) continue;
    std::cerr << "contact2d: " << path << ": " << name << ": "
              << describe(*run->trajectory.divergence, c.scene) << "\n";
    diverged = true;
  }
  return diverged;
}

int compare(const CompareOptions& options) {
  Comparison c;
  c.scene = options.scene.load();
  const engines::EngineSpec spec = options.mujoco.spec(options.scene.path);
  c.mjcf = mj::mjcf_options(spec.mapping, spec.geometry, spec.source);
  mj::mujoco_integrator(c.scene.sim.integrator);  // explicit Euler: fail before any work
  std::unique_ptr<AtomicFile> csv;
  if (!options.csv.empty()) csv = std::make_unique<AtomicFile>(options.csv);
  c.mujoco = engines::run_engine(spec, c.scene);
  c.ref = engines::run_engine(engines::parse_engine("ref"), c.scene);
  for (const std::string& w : c.mujoco.warnings)
    std::cerr << "contact2d: MuJoCo warning: " << w << "\n";
  if (report_divergence(c, options.scene.path)) return kExitDiverged;
  for (const auto& [name, run] : {std::pair{"ref", &c.ref}, std::pair{"MuJoCo", &c.mujoco}}) {
    if (!run->trajectory.energy.exceeded()) continue;
    std::cerr << "contact2d: " << options.scene.path << ": " << name << " warning: "
              << describe_energy_rise(run->trajectory.energy, run->trajectory.available_energy,
                                      c.scene)
              << "\n";
  }
  c.errors = analysis::error_between(c.ref.trajectory, c.mujoco.trajectory);
  if (csv) write_csv(*csv, c);
  if (!options.plot.empty()) {
    const std::string title =
        std::string(shape_name(c.scene.shape)) + ": ref vs MuJoCo (" +
        std::string(mj::mapping_name(c.mjcf.mapping)) + " mapping, " +
        (c.scene.contact.damping == DampingLaw::Compression ? "compression" : "Kelvin-Voigt") +
        " damping)";
    plot_comparison(options.plot, title, c.ref.trajectory, c.mujoco.trajectory);
  }
  if (options.json) {
    print_json(c, options.scene.path);
  } else {
    print_table(c);
  }
  return kExitOk;
}

}  // namespace

Command add_compare(CLI::App& app) {
  auto options = std::make_shared<CompareOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare", "Run the reference solver and MuJoCo on a scene and compare them");
  options->scene.add_to(*cmd);
  options->mujoco.add_to(*cmd);
  cmd->add_option("--csv", options->csv, "Write both trajectories side by side to this file");
  cmd->add_flag("--json", options->json, "Print one JSON object instead of the table");
  cmd->add_option("--plot", options->plot,
                  "Draw x, y, theta of both engines and the errors into this PNG (gnuplot)");
  return {cmd, [options] { return compare(*options); }};
}

}  // namespace contact2d::cli
