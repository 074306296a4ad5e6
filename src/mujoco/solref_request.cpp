#include "mujoco/solref_request.hpp"

#include "core/format.hpp"
#include "core/input_error.hpp"

namespace contact2d::mujoco {

std::vector<Mapping> chosen_mappings(const std::string& name) {
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

SolrefReport solref_request(const SolrefRequest& options,
                            const std::function<void(const std::string&)>& note) {
  auto tell = [&note](const std::string& line) {
    if (note) note(line);
  };
  const auto mappings = chosen_mappings(options.mapping);
  SolrefInput in;
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
    const auto joint = parse_joint(*options.joint);
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
    validate([&] {  // the numbers first: a bad --k is named before the file is read
      SolrefInput probe = in;
      probe.mass = 1.0;
      probe.joint = in.pivot > 0.0 ? Joint::Hinge : Joint::Free;
      if (probe.joint == Joint::Hinge && !(probe.lever > 0.0)) probe.lever = 1.0;
      return probe;
    }());
    const ModelBody body = read_model_body(options.model, options.body);
    if (!body.load_warning.empty())
      tell("MuJoCo warns while loading " + options.model + ": " + body.load_warning);
    in.mass = body.mass;
    in.inv_weight = body.inv_weight;
    in.body_source = options.model + ", body '" + options.body +
                     "' (joints: " + (body.joints.empty() ? std::string("none") : body.joints) +
                     ")";
    // The joint set gives A; Â is the model's whatever it is.
    in.joint = body.joint.value_or(Joint::Free);
    if (!body.joint)
      tell("body '" + options.body +
           "' is not on one of the joint sets free, planar, slide, hinge; A is taken as 1/m + "
           "r²/I");
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
  const SolrefTargets& t = options.targets;
  if (t.restitution || t.contact_time || t.penetration || !options.k || !options.c)
    solve_targets(in, t, options.k.has_value(), options.c.has_value());
  SolrefReport report = solref_report(in, mappings);
  // One mapping asked for by name and it cannot express k, c: bad input.
  if (report.mappings.size() == 1 && !report.mappings[0].unavailable.empty())
    throw InputError(report.mappings[0].unavailable);
  return report;
}

}  // namespace contact2d::mujoco
