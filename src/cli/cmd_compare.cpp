// contact2d compare SCENE [--mapping NAME] [--geometry NAME] [--csv FILE] [--json] [--plot
// FILE.png] [--video FILE.mp4|.gif] [--converged-tol TOL] [--no-diagnosis] [overrides]
//
// Runs the reference solver and MuJoCo on the same scene (same Δt, same
// sample times), measures both against the converged solution and against
// each other, and diagnoses their difference by re-running without each
// suspected cause (analysis/comparison.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <sstream>
#include <utility>

#include "analysis/compare_run.hpp"
#include "analysis/trajectory_error.hpp"
#include "cli/common.hpp"
#include "core/input_error.hpp"
#include "engines/engines.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/json.hpp"
#include "io/plot.hpp"
#include "io/table.hpp"
#include "mujoco/mjcf.hpp"
#ifdef CONTACT2D_WITH_WINDOW
#include "game/comparison_video.hpp"
#endif

namespace contact2d::cli {
namespace {

namespace mj = contact2d::mujoco;

struct CompareOptions {
  SceneOptions scene;
  MujocoOptions mujoco;
  std::string csv;
  std::string plot;
  std::string video;
  bool json = false;
  double converged_tol = 1e-12;
  bool no_diagnosis = false;
  OutputOptions outputs;  // --csv, --plot, --video
  bool allow_nonphysical = false;
};

using analysis::Comparison;
using analysis::energies;
using analysis::Energies;

// Words wrapped at `width` columns after an indent.
std::string wrapped(const std::string& text, const std::string& indent, size_t width = 78) {
  std::string out, line = indent;
  std::istringstream words(text);
  std::string word;
  size_t length = indent.size();  // in characters (UTF-8 sequences count as one)
  auto chars = [](const std::string& w) {
    size_t n = 0;
    for (unsigned char ch : w) n += (ch & 0xC0) != 0x80;
    return n;
  };
  while (words >> word) {
    if (length > indent.size() && length + 1 + chars(word) > width) {
      out += line + "\n";
      line = indent;
      length = indent.size();
    }
    if (length > indent.size()) {
      line += " ";
      ++length;
    }
    line += word;
    length += chars(word);
  }
  return out + line + "\n";
}

void print_table(const Comparison& c) {
  const Energies er = energies(c.scene, c.ref.trajectory);
  const Energies em = energies(c.scene, c.mujoco.trajectory);
  const analysis::ConvergedSolution& conv = c.three.converged;
  std::cout << shape_name(c.scene.shape) << ": ref vs MuJoCo, "
            << engines::integrator_label("mujoco", c.scene.sim.integrator) << ", mapping "
            << mj::mapping_name(c.mjcf.mapping) << ", geometry "
            << mj::geometry_name(c.mjcf.geometry) << ", "
            << (c.scene.contact.damping == DampingLaw::Compression ? "compression" : "Kelvin-Voigt")
            << " damping, dt = " << format_number(c.scene.sim.dt, 4) << " s, " << c.errors.samples
            << " samples over " << format_number(c.scene.sim.duration, 4) << " s\n";
  if (c.scene.contact.friction != FrictionLaw::Tanh) {
    // A cone law is a conformance law, not physics; it matches MuJoCo only
    // at MuJoCo's own impratio.
    const double impratio = c.mujoco.impratio;
    std::string note = "friction law: " + std::string(friction_law_name(c.scene.contact.friction)) +
                       " (MuJoCo's cone, not physics), cone ratio " +
                       format_shortest(c.scene.contact.cone_ratio, 6);
    if (std::isfinite(impratio) && impratio != c.scene.contact.cone_ratio)
      note += "; MuJoCo's model has impratio " + format_shortest(impratio, 6) +
              ": --set contact.cone_ratio=" + format_shortest(impratio, 6) +
              " to compare like with like";
    std::cout << wrapped(note, "") << "\n";
  }
  if (conv.available) {
    std::cout << "converged solution: Dormand-Prince 5(4) with every contact switch located, tol "
              << format_shortest(conv.tol)
              << " (its own error <= " << format_number(conv.own_error, 2)
              << " m: the distance to tol " << format_shortest(10 * conv.tol)
              << ");\nthe scene magnifies a 1e-8 m change of the initial height "
              << format_number(conv.amplification, 3) << "-fold\n\n";
  } else {
    std::cout << wrapped("converged solution: not available (" + conv.why_not +
                             "); only ref <-> MuJoCo is measured.",
                         "")
              << "\n";
  }
  Table t;
  t.columns = {"", "ref <-> converged", "MuJoCo <-> converged", "ref <-> MuJoCo"};
  auto row = [&](const std::string& name, auto field) {
    add_row(t, {name, conv.available ? format_number(field(c.three.ref_vs_converged), 4) : "-",
                conv.available ? format_number(field(c.three.mujoco_vs_converged), 4) : "-",
                format_number(field(c.three.ref_vs_mujoco), 4)});
  };
  using E = analysis::TrajectoryError;
  row("max position (m)", [](const E& e) { return e.max_pos; });
  row("RMS position (m)", [](const E& e) { return e.rms_pos; });
  row("end position (m)", [](const E& e) { return e.end_pos; });
  row("max angle (rad)", [](const E& e) { return e.max_angle; });
  row("end angle (rad)", [](const E& e) { return e.end_angle; });
  row("max velocity (m/s)", [](const E& e) { return e.max_vel; });
  row("max omega (rad/s)", [](const E& e) { return e.max_omega; });
  row("time of max position (s)", [](const E& e) { return e.time_of_max_pos; });
  std::cout << to_text(t) << "\n"
            << "energy ref     " << format_number(er.initial, 4) << " -> "
            << format_number(er.final, 4) << " J\n"
            << "energy MuJoCo  " << format_number(em.initial, 4) << " -> "
            << format_number(em.final, 4) << " J\n"
            << "wall clock     ref " << format_number(c.ref.seconds, 4) << " s, MuJoCo "
            << format_number(c.mujoco.seconds, 4) << " s";
  if (conv.available) std::cout << ", converged " << format_number(conv.seconds, 4) << " s";
  std::cout << "\n";
  const analysis::Diagnosis& d = c.diagnosis;
  if (!d.ran) return;
  std::cout << "\nDiagnosis (each cause removed alone, both engines re-run):\n"
            << wrapped(d.summary, "  ");
  int n = 0;
  for (const analysis::Finding& finding : d.findings) {
    if (!finding.named) continue;
    std::cout << "\n"
              << wrapped(std::to_string(++n) + ". " + finding.cause + ": " + finding.explanation,
                         "  ")
              << "     fix: " << finding.fix << "\n";
  }
  std::string ruled_out;
  for (const analysis::Finding& finding : d.findings) {
    if (finding.named) continue;
    ruled_out += (ruled_out.empty() ? "" : "; ") + finding.cause + " (" +
                 (std::isfinite(finding.share)
                      ? format_text("%.0f %%", std::round(100.0 * finding.share) + 0.0) + ", " +
                            format_number(finding.after, 3) +
                            (finding.cause == "dt_dependent_model" ? " m with the model held"
                                                                   : " m without it")
                      : std::string("not measured")) +
                 ")";
  }
  if (!ruled_out.empty())
    std::cout << "\n" << wrapped("Measured and ruled out: " + ruled_out + ".", "  ");
}

void write_csv(AtomicFile& out, const Comparison& c) {
  const bool conv = c.three.converged.available;
  std::fprintf(out.get(), "%s%s\n",
               "t,x_ref,y_ref,theta_ref,vx_ref,vy_ref,omega_ref,"
               "x_mujoco,y_mujoco,theta_mujoco,vx_mujoco,vy_mujoco,omega_mujoco",
               conv ? ",x_converged,y_converged,theta_converged,vx_converged,vy_converged,"
                      "omega_converged"
                    : "");
  const auto& a = c.ref.trajectory.samples;
  const auto& b = c.mujoco.trajectory.samples;
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    const State& r = a[i].state;
    const State& m = b[i].state;
    std::fprintf(out.get(),
                 "%.10g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g",
                 a[i].t, r.q.x(), r.q.y(), r.q.z(), r.v.x(), r.v.y(), r.v.z(), m.q.x(), m.q.y(),
                 m.q.z(), m.v.x(), m.v.y(), m.v.z());
    if (conv) {
      const State g = c.three.converged.trajectory.at(a[i].t);
      std::fprintf(out.get(), ",%.12g,%.12g,%.12g,%.12g,%.12g,%.12g", g.q.x(), g.q.y(), g.q.z(),
                   g.v.x(), g.v.y(), g.v.z());
    }
    std::fputc('\n', out.get());
  }
}

int compare(const CompareOptions& options) {
  options.outputs.check();
  const engines::EngineSpec spec = options.mujoco.spec(options.scene.path);
  Comparison c = analysis::prepare_comparison(options.scene.load(), spec);
  if (!options.video.empty()) {
#ifdef CONTACT2D_WITH_WINDOW
    game::check_video_path(options.video);
#else
    throw InputError("--video " + options.video +
                     ": this contact2d was built without the game's window (GLFW, OpenGL, "
                     "stb_easy_font), which draws the video");
#endif
  }
  std::unique_ptr<AtomicFile> csv;
  if (!options.csv.empty()) csv = std::make_unique<AtomicFile>(options.csv);
  analysis::run_engines(c);
  for (const std::string& w : c.mujoco.warnings)
    std::cerr << "contact2d: MuJoCo warning: " << w << "\n";
  const std::vector<analysis::RunProblem> problems = analysis::run_problems(c);
  bool stop = false;
  for (const analysis::RunProblem& p : problems) {
    if (p.diverged) {
      std::cerr << "contact2d: " << options.scene.path << ": " << p.engine << ": " << p.message
                << "\n";
      stop = true;
    } else {
      stop |=
          reject_nonphysical(p.message, options.allow_nonphysical, options.scene.path, p.engine);
    }
  }
  if (stop) return kExitDiverged;
  analysis::measure(c, options.converged_tol, !options.no_diagnosis);
  if (csv) write_csv(*csv, c);  // committed last: a plot or video that fails leaves no CSV
  if (!options.plot.empty()) {
    const std::string title =
        std::string(shape_name(c.scene.shape)) + ": ref vs MuJoCo, " +
        engines::integrator_label("mujoco", c.scene.sim.integrator) +
        ", Δt = " + format_number(c.scene.sim.dt) + " s, " +
        std::string(mj::mapping_name(c.mjcf.mapping)) + " mapping, " +
        (c.scene.contact.damping == DampingLaw::Compression ? "compression" : "Kelvin-Voigt") +
        " damping";
    plot_comparison(options.plot, title, c.ref.trajectory, c.mujoco.trajectory);
  }
#ifdef CONTACT2D_WITH_WINDOW
  if (!options.video.empty()) {
    game::ComparisonVideoInput in;
    in.scene = &c.scene;
    in.reference = &c.ref.trajectory;
    in.mujoco = &c.mujoco.trajectory;
    in.converged = c.three.converged.available ? &c.three.converged.trajectory : nullptr;
    in.title = std::string(shape_name(c.scene.shape)) + ": ref vs MuJoCo, " +
               engines::integrator_label("mujoco", c.scene.sim.integrator) + ", " +
               std::string(mj::mapping_name(c.mjcf.mapping)) + " mapping";
    in.reference_label = "ref";
    game::write_comparison_video(options.video, in);
  }
#endif
  if (csv) csv->commit();
  if (options.json) {
    std::cout << analysis::comparison_json(c, options.scene.path);
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
  options->outputs.file(*cmd, "--csv", options->csv,
                        "Write both trajectories side by side to this file", "FILE.csv");
  cmd->add_flag("--json", options->json, "Print one JSON object instead of the table");
  options->outputs.file(
      *cmd, "--plot", options->plot,
      "Draw x, y, theta of both engines and their distance into this PNG (gnuplot)", "FILE.png");
  options->outputs.file(*cmd, "--video", options->video,
                        "Draw both engines overlaid in real time into this .mp4 or .gif "
                        "(reference filled, MuJoCo outlined, the converged solution as a thin "
                        "line)",
                        "FILE.mp4|.gif");
  cmd->add_option("--converged-tol", options->converged_tol,
                  "Tolerance of the converged solution (rtol = atol; default 1e-12)")
      ->type_name("TOL")
      ->check(number_in(1e-14, 1e-6, false, "[1e-14, 1e-6]"));
  add_allow_nonphysical(*cmd, options->allow_nonphysical);
  cmd->add_flag("--no-diagnosis", options->no_diagnosis,
                "Skip the diagnosis (the re-runs that remove each cause of the difference)");
  return {cmd, [options] { return compare(*options); }};
}

}  // namespace contact2d::cli
