// contact2d solref --k N/m --c N·s/m --dt S (--mass KG [--inertia I --lever R] |
//                  --model FILE --body NAME) [--mu μ] [--mu-roll M]
//                  [--mapping NAME|all] [--contacts N] [--json]
// MuJoCo's solref, solimp, impratio and cone for a user's own model, and
// what MuJoCo then does (mujoco/solref_tool.hpp).
#include <iostream>
#include <memory>
#include <optional>

#include "cli/common.hpp"
#include "core/input_error.hpp"
#include "mujoco/solref_tool.hpp"

namespace contact2d::cli {
namespace {

struct SolrefOptions {
  double k = 0.0, c = 0.0, dt = 0.0;
  std::optional<double> mass;
  double inertia = 0.0, lever = 0.0, mu = 0.0, mu_roll = 0.0;
  std::string model, body;
  std::string mapping = "all";
  int contacts = 1;
  bool json = false;
};

std::vector<contact2d::mujoco::Mapping> chosen_mappings(const std::string& name) {
  using namespace contact2d::mujoco;
  if (name == "all") return {std::begin(kAllMappings), std::end(kAllMappings)};
  const auto parsed = parse_mapping(name);
  if (!parsed)
    throw InputError("--mapping " + name + ": unknown (seed, exact, calibrated, compensated, all)");
  return {*parsed};
}

int solref(const SolrefOptions& options) {
  namespace mj = contact2d::mujoco;
  const auto mappings = chosen_mappings(options.mapping);
  mj::SolrefInput in;
  in.k = options.k;
  in.c = options.c;
  in.dt = options.dt;
  in.inertia = options.inertia;
  in.lever = options.lever;
  in.mu = options.mu;
  in.mu_roll = options.mu_roll;
  in.contacts = options.contacts;
  if (!options.model.empty()) {
    if (options.body.empty()) throw InputError("--model " + options.model + ": needs --body NAME");
    mj::validate([&] {  // the numbers first: a bad --k is named before the file is read
      mj::SolrefInput probe = in;
      probe.mass = 1.0;
      return probe;
    }());
    const mj::ModelBody body = mj::read_model_body(options.model, options.body);
    if (!body.load_warning.empty())
      std::cerr << "contact2d: note: MuJoCo warns while loading " << options.model << ": "
                << body.load_warning << "\n";
    in.mass = body.mass;
    in.inv_weight = body.inv_weight;
    in.body_source = options.model + ", body '" + options.body + "'";
  } else {
    if (!options.body.empty()) throw InputError("--body " + options.body + ": needs --model FILE");
    if (!options.mass) throw InputError("--mass or --model: one of them is required");
    in.mass = *options.mass;
    in.body_source = "--mass " + format_number(in.mass, 6);
  }
  const mj::SolrefReport report = mj::solref_report(in, mappings);
  // One mapping asked for by name and it cannot express k, c: bad input.
  if (report.mappings.size() == 1 && !report.mappings[0].unavailable.empty())
    throw InputError(report.mappings[0].unavailable);
  std::cout << (options.json ? mj::format_report_json(report) : mj::format_report_text(report));
  return kExitOk;
}

}  // namespace

Command add_solref(CLI::App& app) {
  auto options = std::make_shared<SolrefOptions>();
  CLI::App* cmd = app.add_subcommand(
      "solref", "MuJoCo solref, solimp, impratio and cone for your own model, per mapping");
  cmd->add_option("--k", options->k, "Contact stiffness, N/m (> 0)")->required();
  cmd->add_option("--c", options->c, "Contact damping, N·s/m (>= 0)")->required();
  cmd->add_option("--dt", options->dt, "MuJoCo's timestep, s (> 0)")->required();
  CLI::Option* mass = cmd->add_option("--mass", options->mass, "Body mass, kg (> 0)");
  cmd->add_option("--inertia", options->inertia,
                  "Moment of inertia about the COM, kg·m² (>= 0; with --lever)");
  cmd->add_option("--lever", options->lever,
                  "Distance of the contact from the COM across the normal, m (>= 0)");
  CLI::Option* model = cmd->add_option(
      "--model", options->model, "A MuJoCo MJCF file: read the body's mass and body_invweight0");
  cmd->add_option("--body", options->body, "The body's name in --model");
  mass->excludes(model);
  cmd->add_option("--mu", options->mu, "Sliding friction coefficient (>= 0; default 0)");
  cmd->add_option("--mu-roll", options->mu_roll,
                  "Rolling friction, m (>= 0; needs --inertia and --lever, the rolling radius)");
  cmd->add_option("--mapping", options->mapping,
                  "seed | exact | calibrated | compensated | all (default all)");
  cmd->add_option("--contacts", options->contacts,
                  "MuJoCo contacts sharing the weight at rest (>= 1; default 1)");
  cmd->add_flag("--json", options->json, "Print JSON instead of text");
  return {cmd, [options] { return solref(*options); }};
}

}  // namespace contact2d::cli
