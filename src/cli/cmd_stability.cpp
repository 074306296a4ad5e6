// contact2d stability SCENE [--ks LIST] [--integrators LIST] [--engines LIST]
//                           [--zeta Z] [--csv FILE] [--plot FILE.png] [...]
// Largest stable Δt per contact stiffness and integrator, by bisection, next
// to the linear theory.
#include <iostream>
#include <memory>

#include "analysis/plots.hpp"
#include "analysis/stability.hpp"
#include "analysis/tables.hpp"
#include "cli/common.hpp"
#include "io/atomic_file.hpp"
#include "io/scene_file.hpp"

namespace contact2d::cli {

namespace {

struct StabilityOptions : AnalysisOptions {
  std::vector<double> ks;
  std::optional<double> zeta;
  double dt_max = 1e-2;
  double precision = 0.02;
};

int stability(const StabilityOptions& o) {
  o.outputs.check();
  const Scene scene = o.load();
  std::unique_ptr<AtomicFile> csv;
  if (!o.csv.empty()) csv = std::make_unique<AtomicFile>(o.csv);

  analysis::StabilityConfig config;
  analysis::StabilityResult result;
  try {
    if (!o.ks.empty()) config.ks = o.ks;
    if (!o.integrators.empty()) config.integrators = analysis::parse_integrators(o.integrators);
    config.engines = o.engines;
    config.zeta = o.zeta;
    config.dt_max = o.dt_max;
    config.precision = o.precision;
    config.threads = o.threads;
    config.progress =
        progress_reporter("stability " + std::string(shape_name(scene.shape)), o.quiet);
    result = analysis::run_stability(scene, config);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
  analysis::print_stability(std::cout, result);
  if (csv) analysis::write_stability_csv(csv->get(), result);
  if (!o.plot.empty()) analysis::plot_stability(o.plot, result);
  if (csv) csv->commit();  // last: a plot that fails leaves no CSV
  return kExitOk;
}

}  // namespace

Command add_stability(CLI::App& app) {
  auto o = std::make_shared<StabilityOptions>();
  CLI::App* cmd = app.add_subcommand("stability",
                                     "Largest stable dt per contact stiffness and integrator "
                                     "(bisection), against the linear theory");
  o->add_to(*cmd, "Write one row per engine, integrator and k to this CSV file",
            "Write the stability map (PNG, gnuplot)");
  cmd->add_option("--ks", o->ks, "Comma-separated contact stiffnesses (default 1e3,1e4,...,1e9)")
      ->type_name("N/m")
      ->delimiter(',');
  cmd->add_option(
         "--zeta", o->zeta,
         "Damping ratio held at every k: c = 2*zeta*sqrt(k*m_eff) (default: keep the scene's c)")
      ->type_name("ZETA");
  cmd->add_option("--dt-max", o->dt_max, "Largest dt tried (default 1e-2)")
      ->type_name("SECONDS")
      ->check(number_in(0.0, 1e5, true, "(0, 1e5] s"));
  cmd->add_option("--precision", o->precision, "Relative width of the final bracket (default 0.02)")
      ->type_name("FRACTION")
      ->check(number_in(1e-4, 1.0, false, "[1e-4, 1]"));
  return {cmd, [o] { return stability(*o); }};
}

}  // namespace contact2d::cli
