// contact2d solref (--k N/m | --penetration M | --contact-time S) (--c N·s/m | --restitution E)
//                  [--dt S] (--mass KG [--joint J] [--inertia I --lever R]
//                  [--pivot P] | --model FILE --body NAME) [--mu μ] [--mu-roll M]
//                  [--mapping NAME|all] [--contacts N] [--json]
// MuJoCo's solref, solimp, impratio and cone for a user's own model, and
// what MuJoCo then does (mujoco/solref_request.hpp, mujoco/solref_tool.hpp).
#include <iostream>
#include <memory>
#include <optional>

#include "cli/common.hpp"
#include "core/input_error.hpp"
#include "mujoco/solref_request.hpp"
#include "mujoco3/own_model.hpp"

namespace contact2d::cli {
namespace {

struct SolrefOptions {
  contact2d::mujoco::SolrefRequest request;
  bool json = false;
  const CLI::Option* apply = nullptr;  // given empty: an error, as for every output
};

int solref(const SolrefOptions& options) {
  namespace mj = contact2d::mujoco;
  if (options.apply->count() > 0 && options.request.apply.empty())
    throw InputError("--apply: empty; name the file to write");
  const mj::SolrefReport report = contact2d::mujoco3::solref(
      options.request,
      [](const std::string& line) { std::cerr << "contact2d: note: " << line << "\n"; });
  std::cout << (options.json ? mj::format_report_json(report) : mj::format_report_text(report));
  // --apply refused after the report (no mapping fits): the report says why.
  if (!report.apply_refused.empty()) throw InputError(report.apply_refused);
  return kExitOk;
}

}  // namespace

Command add_solref(CLI::App& app) {
  auto options = std::make_shared<SolrefOptions>();
  CLI::App* cmd = app.add_subcommand(
      "solref", "MuJoCo solref, solimp, impratio and cone for your own model, per mapping");
  cmd->add_option("--k", options->request.k,
                  "Contact stiffness per MuJoCo contact, N/m (> 0; or --penetration, or "
                  "--contact-time with --restitution)");
  cmd->add_option("--c", options->request.c,
                  "Contact damping per MuJoCo contact, N·s/m (>= 0; or --restitution)");
  cmd->add_option("--restitution", options->request.targets.restitution,
                  "Target coefficient of restitution in (0, 1): c from it (the Kelvin–Voigt "
                  "law, force clamped at zero)");
  cmd->add_option("--contact-time", options->request.targets.contact_time,
                  "Target duration of an impact, s (> 0; with --restitution): k from it");
  cmd->add_option("--penetration", options->request.targets.penetration,
                  "Target static depth per contact under gravity, m (> 0): k from it (the "
                  "calibrated mapping's rest depth)");
  cmd->add_option("--dt", options->request.dt,
                  "MuJoCo's timestep, s (> 0; with --model default: the model's timestep)");
  CLI::Option* mass = cmd->add_option("--mass", options->request.mass, "Body mass, kg (> 0)");
  cmd->add_option("--joint", options->request.joint,
                  "How the body is jointed: free | planar (slide x, slide z, hinge) | slide (one, "
                  "along the normal) | hinge (default free; --model reads it)");
  cmd->add_option("--inertia", options->request.inertia,
                  "Moment of inertia about the COM, kg·m² (>= 0; with --lever)");
  cmd->add_option("--lever", options->request.lever,
                  "Distance of the contact from the COM across the normal, m (>= 0; hinge: the "
                  "normal's moment arm about the axis)");
  cmd->add_option("--pivot", options->request.pivot,
                  "--joint hinge: distance of the COM from the hinge axis, m (> 0)");
  CLI::Option* model = cmd->add_option(
      "--model", options->request.model,
      "A MuJoCo MJCF file: read the body's mass, joints, body_invweight0 and friction, and count "
      "its contacts at rest (3 s of mj_step)");
  cmd->add_option("--body", options->request.body, "The body's name in --model");
  cmd->add_option("--engine", options->request.engine,
                  "The MuJoCo whose numbers to give: mujoco (2.2.2) or mujoco3 (3.14): Â and, "
                  "with --model, the settled contacts as that version compiles and steps it");
  cmd->add_option("--settle", options->request.settle,
                  "--model: seconds of mj_step before reading the body's contacts (>= 0; "
                  "default 3)");
  cmd->add_option("--slope", options->request.slope,
                  "Slope in degrees, [0, 90): each mapping's creep speed under friction");
  options->apply = cmd->add_option(
      "--apply", options->request.apply,
      "--model: write the model with the recommended mapping on the body's geoms to "
      "this file (in the model's folder), settle it and list the body's contacts "
      "there");
  cmd->add_option("--key", options->request.key,
                  "--model: the keyframe the settling starts from (default qpos0)");
  mass->excludes(model);
  cmd->add_option("--mu", options->request.mu,
                  "Sliding friction coefficient (>= 0; absent: the snippets keep your friction)");
  cmd->add_option(
      "--mu-roll", options->request.mu_roll,
      "Rolling friction, m (>= 0; needs --mu, --inertia and --lever, the rolling radius)");
  cmd->add_option("--mapping", options->request.mapping,
                  "calibrated | exact | seed | all (default all)");
  cmd->add_option("--contacts", options->request.contacts,
                  "MuJoCo contacts sharing the weight at rest, k and c are per contact (>= 1; "
                  "default: counted with --model, else 1)");
  cmd->add_flag("--json", options->json, "Print JSON instead of text");
  return {cmd, [options] { return solref(*options); }};
}

}  // namespace contact2d::cli
