// contact2d sweep SCENE [--integrators LIST] [--dts LIST] [--engines ref,mujoco]
//                       [--csv FILE] [--plot FILE.png] [...]
// Error against run time for every engine × integrator × Δt, against the
// scene's converged reference; table on stdout, progress on stderr.
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <memory>
#include <mutex>

#include "analysis/plots.hpp"
#include "analysis/sweep.hpp"
#include "analysis/tables.hpp"
#include "cli/common.hpp"
#include "io/atomic_file.hpp"
#include "io/scene_file.hpp"

namespace contact2d::cli {

namespace {

struct SweepOptions : AnalysisOptions {
  std::vector<double> dts;
  std::vector<double> other_dts;               // --mujoco-dts: every engine but the reference
  std::vector<std::string> other_integrators;  // --mujoco-integrators: the same
  std::string orders_csv;
  int repeats = 3;
  double tol = 1e-12;
  bool reference_study = false;
  std::string study_csv;
};

int sweep(const SweepOptions& o) {
  o.outputs.check();
  const Scene scene = o.load();
  if (!scene.obstacles.empty()) {
    throw InputError(o.path +
                     ": sweep measures errors against the converged reference, which handles "
                     "ground contact only; this scene has static obstacles");
  }
  // Outputs are opened first and committed together at the end: a run that
  // fails halfway leaves none of them.
  std::unique_ptr<AtomicFile> csv, orders_csv, study_csv;
  if (!o.csv.empty()) csv = std::make_unique<AtomicFile>(o.csv);
  if (!o.orders_csv.empty()) orders_csv = std::make_unique<AtomicFile>(o.orders_csv);
  if (!o.study_csv.empty()) study_csv = std::make_unique<AtomicFile>(o.study_csv);

  analysis::SweepConfig config;
  try {
    if (!o.integrators.empty()) config.integrators = analysis::parse_integrators(o.integrators);
    if (!o.dts.empty()) config.dts = o.dts;
    if (!o.other_dts.empty()) config.other_dts = o.other_dts;
    if (!o.other_integrators.empty())
      config.other_integrators = analysis::parse_integrators(o.other_integrators);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
  config.engines = o.engines;
  config.repeats = o.repeats;
  config.reference_tol = o.tol;
  config.threads = o.threads;
  config.progress = progress_reporter("sweep " + std::string(shape_name(scene.shape)), o.quiet);

  if (o.reference_study || study_csv) {
    const std::vector<double> tols{1e-3, 1e-4,  1e-5,  1e-6,  1e-7, 1e-8,
                                   1e-9, 1e-10, 1e-11, 1e-12, 1e-13};
    // One thread: the study times every run, and two side by side would
    // disturb each other's timing more than they save.
    const analysis::ReferenceStudy study = analysis::study_reference(scene, tols, 1e-14, 1);
    analysis::print_reference_study(std::cout, std::string(shape_name(scene.shape)), study);
    std::cout << "\n";
    if (study_csv) {
      analysis::write_reference_study_csv(study_csv->get(), std::string(shape_name(scene.shape)),
                                          study);
    }
  }

  analysis::SweepResult result;
  try {
    result = analysis::run_sweep(scene, config);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  } catch (const std::runtime_error& e) {
    std::cerr << "contact2d: " << o.path << ": " << e.what() << "\n";
    return kExitDiverged;
  }
  analysis::print_sweep(std::cout, result);
  for (const analysis::SweepRow& row : result.rows) {
    for (const std::string& w : row.warnings) {
      std::cerr << "contact2d: " << row.engine << " " << integrator_name(row.integrator) << " dt "
                << format_number(row.dt) << " warning: " << w << "\n";
    }
  }
  if (csv) analysis::write_sweep_csv(csv->get(), result);
  if (orders_csv) analysis::write_orders_csv(orders_csv->get(), result);
  if (!o.plot.empty()) analysis::plot_sweep(o.plot, result);
  for (AtomicFile* file : {study_csv.get(), csv.get(), orders_csv.get()})
    if (file) file->commit();
  return kExitOk;
}

}  // namespace

Command add_sweep(CLI::App& app) {
  auto o = std::make_shared<SweepOptions>();
  CLI::App* cmd = app.add_subcommand("sweep",
                                     "Error against run time: every engine x integrator x dt "
                                     "against the scene's converged reference");
  o->add_to(*cmd, "Write one row per run to this CSV file",
            "Write the work-precision diagram (PNG, gnuplot)");
  cmd->add_option("--dts", o->dts,
                  "Comma-separated time steps (default: 1e-3,5e-4,2e-4,1e-4,5e-5,2e-5,1e-5)")
      ->type_name("SECONDS")
      ->delimiter(',');
  cmd->add_option("--mujoco-dts", o->other_dts,
                  "Comma-separated time steps for every engine but the reference: MuJoCo "
                  "(default: --dts; a MuJoCo step costs ~100x a reference step)")
      ->type_name("SECONDS")
      ->delimiter(',');
  cmd->add_option("--mujoco-integrators", o->other_integrators,
                  "Comma-separated integrators for every engine but the reference: MuJoCo "
                  "(default: --integrators; MuJoCo has no explicit_euler)")
      ->type_name("NAME")
      ->delimiter(',');
  o->outputs.file(*cmd, "--orders-csv", o->orders_csv, "Write the observed orders to this CSV file",
                  "FILE.csv");
  cmd->add_option(
         "--repeats", o->repeats,
         "Time each run as the best of N repeats (default 3; 1 when a run takes over 0.25 s)")
      ->type_name("N")
      ->check(CLI::Range(1, 100));
  cmd->add_option("--tol", o->tol, "Tolerance of the converged reference (default 1e-12)")
      ->type_name("TOL")
      ->check(number_in(1e-15, 1e-3, false, "[1e-15, 1e-3]"));
  cmd->add_flag(
      "--reference-study", o->reference_study,
      "First show the reference's self-consistency error at tolerances 1e-3..1e-13 against 1e-14");
  o->outputs.file(*cmd, "--study-csv", o->study_csv,
                  "Write the reference study to this CSV file (implies --reference-study)",
                  "FILE.csv");
  return {cmd, [o] { return sweep(*o); }};
}

}  // namespace contact2d::cli
