#include "mujoco/solref_request.hpp"

#include <algorithm>
#include <tuple>

#include "core/format.hpp"
#include "core/input_error.hpp"
#include "io/atomic_file.hpp"
#include "mujoco/inspect.hpp"
#include "mujoco/solref_apply.hpp"

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

namespace {

// --model's body, settled by `read` (2.2.2 when empty), into `in`: its
// mass, Â, joints, friction and the contacts MuJoCo rests it on.
void read_body_into(const SolrefRequest& options, SolrefInput& in,
                    const std::function<void(const std::string&)>& tell, const StateReader& read) {
  StateRequest request;
  request.path = options.model;
  request.key = options.key;
  request.settle = options.settle;
  request.option = "--model";
  const ModelBody body = read_model_body(read ? read(request) : read_model_state(request),
                                         options.model, options.body);
  if (!body.load_warning.empty())
    tell("MuJoCo warns while loading " + options.model + ": " + body.load_warning);
  in.mass = body.mass;
  in.inv_weight = body.inv_weight;
  in.body_source = options.model + ", body '" + printable_name(options.body) +
                   "' (joints: " + (body.joints.empty() ? std::string("none") : body.joints) +
                   "), MuJoCo " + body.version;
  in.joint = body.joint.value_or(Joint::Free);
  if (in.keep_friction) in.user_friction = body.friction;
  // The model's noslip pass stays whatever the snippets write (they leave it).
  in.user_friction.noslip_iterations = body.friction.noslip_iterations;
  in.settled_contacts = body.contacts;
  // The class each contact's geom of the body has in the file, which the
  // default class snippet would replace (solref_tool.hpp's ClassCaveat).
  std::vector<GeomRef> own;
  own.reserve(in.settled_contacts.size());
  for (const SettledContact& c : in.settled_contacts) own.push_back(c.own == 0 ? c.ref1 : c.ref2);
  const auto classes = geom_classes_in_file(options.model, own);
  for (size_t i = 0; i < classes.size(); ++i)
    std::tie(in.settled_contacts[i].own_class, in.settled_contacts[i].own_class_from) = classes[i];
  in.model_version = body.version;
  if (!options.dt) {
    in.dt = body.timestep;
    in.dt_source = "the model's timestep";
  }
  in.tangential_inv_mass = body.tangential_inv_mass;
  const std::string settled =
      "after settling " + format_number(body.settle_seconds, 6) + " s with mj_step" +
      (body.at_rest ? std::string()
                    : " (not at rest: |qvel| up to " + format_number(body.rest_speed, 3) +
                          "; a longer --settle)");
  if (!body.contacts.empty()) {
    // The contact that carries the most: its A and MuJoCo's load at it.
    const SettledContact* most = &body.contacts.front();
    for (const SettledContact& c : body.contacts)
      if (c.load > most->load) most = &c;
    in.measured = ContactMechanics{most->A, most->load};
    in.measured_source = "measured in the model " + settled + ": contact " + most->geom1 + " – " +
                         most->geom2 + ", the most loaded of the body's " +
                         std::to_string(body.contacts.size());
    if (!(most->A > kNoMotion * std::max(most->inv_weight, 1.0 / body.mass)))  // inspect.hpp
      throw InputError(
          "--body " + printable_name(options.body) +
          ": its joints cannot move its contact along the normal (A = " +
          (most->A > 0.0 ? "round-off of 0, below 1e-12 of Â or 1/m" : std::string("0")) + ")");
  } else if (!body.joint) {
    tell("body '" + printable_name(options.body) + "' has no contacts " + settled +
         " and is not on one of the joint sets free, planar, slide, hinge; A is taken as 1/m + "
         "r²/I");
  }
  if (options.contacts) {
    in.contacts_source = "--contacts " + std::to_string(in.contacts) + "; MuJoCo makes " +
                         std::to_string(body.rest_contacts) + " " + settled;
  } else if (body.rest_contacts > 0) {
    in.contacts = body.rest_contacts;
    in.contacts_source =
        "counted: MuJoCo makes " + std::to_string(body.rest_contacts) + " for the body " + settled;
  } else {
    in.contacts_source =
        "MuJoCo makes none for the body " + settled + ", so 1 is assumed; give --contacts N";
  }
}

}  // namespace

namespace {

// Every option the request lacks, in one message: k, c, Δt and the body
// each need one of their options.
void require_options(const SolrefRequest& options) {
  std::vector<std::string> missing;
  const SolrefTargets& t = options.targets;
  if (!options.k && !t.penetration && !t.contact_time)
    missing.push_back("--k (or --penetration, or --contact-time with --restitution)");
  if (!options.c && !t.restitution) missing.push_back("--c (or --restitution)");
  if (!options.dt && options.model.empty())
    missing.push_back("--dt (with --model: the model's timestep)");
  if (!options.mass && options.model.empty())
    missing.push_back("--mass, or --model FILE --body NAME");
  if (!options.model.empty() && options.body.empty()) missing.push_back("--body NAME");
  if (missing.empty()) return;
  std::string text;
  for (size_t i = 0; i < missing.size(); ++i)
    text += (i == 0 ? "" : i + 1 == missing.size() ? " and " : ", ") + missing[i];
  throw InputError("missing " + text);
}

}  // namespace

SolrefReport solref_request(const SolrefRequest& options,
                            const std::function<void(const std::string&)>& note,
                            const StateReader& read) {
  auto tell = [&note](const std::string& line) {
    if (note) note(line);
  };
  require_options(options);
  const auto mappings = chosen_mappings(options.mapping);
  if (options.engine != "mujoco" && options.engine != "mujoco3")
    throw InputError("--engine " + options.engine +
                     ": solref is for mujoco (2.2.2) or mujoco3 (3.14)");
  if (options.engine == "mujoco3" && !read)
    throw InputError("--engine mujoco3: MuJoCo 3 is not available in this build");
  SolrefInput in;
  in.mujoco3 = options.engine == "mujoco3";
  in.slope = options.slope;
  in.k = options.k.value_or(1.0);  // a placeholder until solve_targets when a target gives it
  in.c = options.c.value_or(0.0);
  in.dt = options.dt.value_or(0.0);  // --model without --dt: its timestep (read_body_into)
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
  if (!options.apply.empty()) {
    if (options.model.empty())
      throw InputError("--apply " + options.apply + ": needs --model FILE --body NAME");
    check_output_file("--apply", options.apply);
  }
  if (!options.model.empty()) {
    if (options.mass)
      throw InputError("--mass " + format_number(*options.mass) +
                       ": not with --model (the body's mass is read from the model)");
    if (options.body.empty()) throw InputError("--model " + options.model + ": needs --body NAME");
    validate([&] {  // the numbers first: a bad --k is named before the file is read
      SolrefInput probe = in;
      probe.mass = 1.0;
      if (!options.dt) probe.dt = 1e-3;  // the model's, read next
      probe.joint = in.pivot > 0.0 ? Joint::Hinge : Joint::Free;
      if (probe.joint == Joint::Hinge && !(probe.lever > 0.0)) probe.lever = 1.0;
      return probe;
    }());
    read_body_into(options, in, tell, read);
  } else {
    if (!options.body.empty())
      throw InputError("--body " + printable_name(options.body) + ": needs --model FILE");
    if (!options.mass) throw InputError("--mass or --model: one of them is required");
    in.mass = *options.mass;
    in.body_source = "--mass " + format_number(in.mass, 6);
  }
  const SolrefTargets& t = options.targets;
  if (t.restitution || t.contact_time || t.penetration || !options.k || !options.c)
    solve_targets(in, t, options.k.has_value(), options.c.has_value());
  if (in.mujoco3 && (in.mu > 0.0 || (in.keep_friction && in.user_friction.condim > 1)))
    tell(
        "MuJoCo 3's friction damper (solreffriction on <pair>s, which removes the sliding "
        "push) is not in these snippets: it needs a friction-row damper ratio φ of 1e-4 or "
        "less of the normal one, which breaks over calibrated's d = 1e-4 (measured 1.8 cm to "
        "1.95 m off on contact2d's scenes) and works over compensated, which only `contact2d "
        "generate --engine mujoco3 --mapping compensated --friction damper` builds "
        "(docs/mujoco3.md)");
  SolrefReport report = solref_report(in, mappings);
  report.fit_hint = fit_hint(report);
  // One mapping asked for by name and it cannot express k, c: bad input.
  if (report.mappings.size() == 1 && !report.mappings[0].unavailable.empty())
    throw InputError(report.mappings[0].unavailable);
  if (!options.apply.empty()) {
    // The recommendation is printed first; --mapping NAME applies that one.
    const MappingOutcome& chosen = report.mappings.front();
    if (!chosen.unavailable.empty() ||
        (options.mapping == "all" && report.recommendation.empty())) {
      report.apply_refused = "--apply " + options.apply +
                             ": not written: no mapping is fit for a model to build on here "
                             "(the report above says why)" +
                             (report.fit_hint.empty() ? "" : "; t" + report.fit_hint.substr(1));
      return report;
    }
    StateRequest settle;
    settle.key = options.key;
    settle.settle = options.settle;
    report.applied = apply_solref(report, chosen, options.model, options.body, options.apply,
                                  settle, read ? read : StateReader(read_model_state));
  }
  return report;
}

}  // namespace contact2d::mujoco
