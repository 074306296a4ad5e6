// contact2d solref (--k N/m | --penetration M | --contact-time S) (--c N·s/m | --restitution E)
//                  --dt S (--mass KG [--joint J] [--inertia I --lever R]
//                  [--pivot P] | --model FILE --body NAME) [--mu μ] [--mu-roll M]
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
  std::optional<double> k, c;
  double dt = 0.0;
  contact2d::mujoco::SolrefTargets targets;
  std::optional<double> mass, mu;
  double inertia = 0.0, lever = 0.0, pivot = 0.0, mu_roll = 0.0;
  std::string model, body;
  std::optional<std::string> joint;
  std::string mapping = "all";
  std::optional<int> contacts;
  bool json = false;
};

std::vector<contact2d::mujoco::Mapping> chosen_mappings(const std::string& name) {
  using namespace contact2d::mujoco;
  if (name == "all") {
    std::vector<Mapping> all = offered_mappings();
    all.push_back(Mapping::Compensated);  // printed as not offered, with the reason
    return all;
  }
  const auto parsed = parse_mapping(name);
  if (!parsed || *parsed == Mapping::Compensated)
    throw InputError("--mapping " + name + ": " +
                     (parsed ? "compensated is " + compensated_not_offered() + "; use"
                             : std::string("unknown; use")) +
                     " calibrated, exact, seed or all");
  return {*parsed};
}

int solref(const SolrefOptions& options) {
  namespace mj = contact2d::mujoco;
  const auto mappings = chosen_mappings(options.mapping);
  mj::SolrefInput in;
  in.k = options.k.value_or(1.0);  // a placeholder until solve_targets when a target gives it
  in.c = options.c.value_or(0.0);
  in.dt = options.dt;
  in.inertia = options.inertia;
  in.lever = options.lever;
  in.pivot = options.pivot;
  in.keep_friction = !options.mu;
  in.mu = options.mu.value_or(0.0);
  in.mu_roll = options.mu_roll;
  if (in.keep_friction && in.mu_roll > 0.0)
    throw InputError("--mu-roll " + format_number(in.mu_roll, 6) +
                     ": needs --mu (the snippet writes condim 6 with both)");
  if (options.joint) {
    if (!options.model.empty())
      throw InputError("--joint " + *options.joint +
                       ": not with --model (its joints are read from "
                       "the model)");
    const auto joint = mj::parse_joint(*options.joint);
    if (!joint)
      throw InputError("--joint " + *options.joint + ": unknown; use free, planar, slide or hinge");
    in.joint = *joint;
  }
  in.contacts = options.contacts.value_or(1);
  in.contacts_source = options.contacts ? "--contacts " + std::to_string(in.contacts)
                                        : "the default, 1: give --contacts N when N MuJoCo "
                                          "contacts share the weight (a box on a plane makes 4)";
  if (!options.model.empty()) {
    if (options.body.empty()) throw InputError("--model " + options.model + ": needs --body NAME");
    mj::validate([&] {  // the numbers first: a bad --k is named before the file is read
      mj::SolrefInput probe = in;
      probe.mass = 1.0;
      probe.joint = in.pivot > 0.0 ? mj::Joint::Hinge : mj::Joint::Free;
      if (probe.joint == mj::Joint::Hinge && !(probe.lever > 0.0)) probe.lever = 1.0;
      return probe;
    }());
    const mj::ModelBody body = mj::read_model_body(options.model, options.body);
    if (!body.load_warning.empty())
      std::cerr << "contact2d: note: MuJoCo warns while loading " << options.model << ": "
                << body.load_warning << "\n";
    in.mass = body.mass;
    in.inv_weight = body.inv_weight;
    in.body_source = options.model + ", body '" + options.body +
                     "' (joints: " + (body.joints.empty() ? std::string("none") : body.joints) +
                     ")";
    // The joint set gives A; Â is the model's whatever it is.
    in.joint = body.joint.value_or(mj::Joint::Free);
    if (!body.joint)
      std::cerr << "contact2d: note: body '" << options.body << "' is not on one of the joint "
                << "sets free, planar, slide, hinge; A is taken as 1/m + r²/I\n";
    if (in.keep_friction) in.user_friction = body.friction;
    const std::string settled =
        "after settling " + format_number(body.settle_seconds, 6) + " s with mj_step" +
        (body.rest_speed > 1e-3
             ? " (still moving: |qvel| = " + format_number(body.rest_speed, 3) + ")"
             : std::string());
    if (options.contacts) {
      in.contacts_source = "--contacts " + std::to_string(in.contacts) + "; MuJoCo makes " +
                           std::to_string(body.rest_contacts) + " " + settled;
    } else if (body.rest_contacts > 0) {
      in.contacts = body.rest_contacts;
      in.contacts_source = "counted: MuJoCo makes " + std::to_string(body.rest_contacts) +
                           " for the body " + settled;
    } else {
      in.contacts_source =
          "MuJoCo makes none for the body " + settled + ", so 1 is assumed; give --contacts N";
    }
  } else {
    if (!options.body.empty()) throw InputError("--body " + options.body + ": needs --model FILE");
    if (!options.mass) throw InputError("--mass or --model: one of them is required");
    in.mass = *options.mass;
    in.body_source = "--mass " + format_number(in.mass, 6);
  }
  const mj::SolrefTargets& t = options.targets;
  if (t.restitution || t.contact_time || t.penetration || !options.k || !options.c)
    mj::solve_targets(in, t, options.k.has_value(), options.c.has_value());
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
  cmd->add_option("--k", options->k,
                  "Contact stiffness per MuJoCo contact, N/m (> 0; or --penetration, or "
                  "--contact-time with --restitution)");
  cmd->add_option("--c", options->c,
                  "Contact damping per MuJoCo contact, N·s/m (>= 0; or --restitution)");
  cmd->add_option("--restitution", options->targets.restitution,
                  "Target coefficient of restitution in (0, 1): c from it (the Kelvin–Voigt "
                  "law, force clamped at zero)");
  cmd->add_option("--contact-time", options->targets.contact_time,
                  "Target duration of an impact, s (> 0; with --restitution): k from it");
  cmd->add_option("--penetration", options->targets.penetration,
                  "Target static depth per contact under gravity, m (> 0): k from it (the "
                  "calibrated mapping's rest depth)");
  cmd->add_option("--dt", options->dt, "MuJoCo's timestep, s (> 0)")->required();
  CLI::Option* mass = cmd->add_option("--mass", options->mass, "Body mass, kg (> 0)");
  cmd->add_option("--joint", options->joint,
                  "How the body is jointed: free | planar (slide x, slide z, hinge) | slide (one, "
                  "along the normal) | hinge (default free; --model reads it)");
  cmd->add_option("--inertia", options->inertia,
                  "Moment of inertia about the COM, kg·m² (>= 0; with --lever)");
  cmd->add_option("--lever", options->lever,
                  "Distance of the contact from the COM across the normal, m (>= 0; hinge: the "
                  "normal's moment arm about the axis)");
  cmd->add_option("--pivot", options->pivot,
                  "--joint hinge: distance of the COM from the hinge axis, m (> 0)");
  CLI::Option* model = cmd->add_option(
      "--model", options->model,
      "A MuJoCo MJCF file: read the body's mass, joints, body_invweight0 and friction, and count "
      "its contacts at rest (3 s of mj_step)");
  cmd->add_option("--body", options->body, "The body's name in --model");
  mass->excludes(model);
  cmd->add_option("--mu", options->mu,
                  "Sliding friction coefficient (>= 0; absent: the snippets keep your friction)");
  cmd->add_option(
      "--mu-roll", options->mu_roll,
      "Rolling friction, m (>= 0; needs --mu, --inertia and --lever, the rolling radius)");
  cmd->add_option("--mapping", options->mapping, "calibrated | exact | seed | all (default all)");
  cmd->add_option("--contacts", options->contacts,
                  "MuJoCo contacts sharing the weight at rest, k and c are per contact (>= 1; "
                  "default: counted with --model, else 1)");
  cmd->add_flag("--json", options->json, "Print JSON instead of text");
  return {cmd, [options] { return solref(*options); }};
}

}  // namespace contact2d::cli
