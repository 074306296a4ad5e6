// contact2d inspect MODEL.xml [--engine mujoco|mujoco3 | --engines mujoco,mujoco3]
//                  [--key NAME] [--settle S] [--estimate-loads] [--pairs] [--slope DEG]
//                  [--no-rest-search] [--json]
// What the contacts of a user's own MJCF model are in physical units, as
// MuJoCo 2.2.2 or 3.14 resolves and integrates them (mujoco/inspect.hpp);
// with --engines, the model on both versions compared (mujoco/version_compare.hpp).
#include <chrono>
#include <iostream>
#include <memory>
#include <optional>

#include "cli/common.hpp"
#include "core/input_error.hpp"
#include "mujoco/inspect.hpp"
#include "mujoco3/inspect_versions.hpp"
#include "mujoco3/own_model.hpp"

namespace contact2d::cli {
namespace {

struct InspectCliOptions {
  contact2d::mujoco::InspectOptions inspect;
  std::string engine = "mujoco";
  std::string engines;  // "mujoco,mujoco3": both versions compared
  std::optional<double> slope;
  bool rest_search = true;
  bool json = false;
};

int inspect(const InspectCliOptions& options) {
  namespace mj = contact2d::mujoco;
  mj::InspectOptions in = options.inspect;
  in.slope = options.slope;
  // A line on stderr every ~2 s once the pairs take longer than that.
  const auto start = std::chrono::steady_clock::now();
  auto last = start;
  in.progress = [&](size_t done, size_t total) {
    const auto now = std::chrono::steady_clock::now();
    if (now - last < std::chrono::seconds(2)) return;
    last = now;
    std::cerr << "contact2d: inspect: " << done << " of " << total << " geom pairs ("
              << std::chrono::duration_cast<std::chrono::seconds>(now - start).count() << " s)\n";
  };
  if (!options.engines.empty()) {
    if (options.engines != "mujoco,mujoco3" && options.engines != "mujoco3,mujoco")
      throw InputError("--engines " + options.engines +
                       ": compares the two versions, mujoco,mujoco3 (2.2.2 and 3.14)");
    const mj::VersionComparison comparison = contact2d::mujoco3::inspect_versions(in);
    std::cout << (options.json ? mj::format_versions_json(comparison)
                               : mj::format_versions_text(comparison));
    return kExitOk;
  }
  // Throws InputError: exit 2.
  mj::InspectReport report = contact2d::mujoco3::inspect(in, options.engine);
  if (options.rest_search) contact2d::mujoco3::settle_time(report, in, options.engine);
  if (!report.load_warning.empty())
    std::cerr << "contact2d: note: MuJoCo warns while loading " << in.path << ": "
              << report.load_warning << "\n";
  std::cout << (options.json ? mj::format_inspect_json(report) : mj::format_inspect_text(report));
  return kExitOk;
}

}  // namespace

Command add_inspect(CLI::App& app) {
  auto options = std::make_shared<InspectCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "inspect",
      "Your own MJCF model's contacts in physical units: solref/solimp as MuJoCo resolves them, "
      "k, c, ω, ζ, stability, rest depth, restitution, creep");
  cmd->add_option("model", options->inspect.path, "A MuJoCo MJCF file")->required();
  cmd->add_option("--engine", options->engine,
                  "The MuJoCo that reads the model: mujoco (2.2.2) or mujoco3 (3.14)");
  cmd->add_option("--engines", options->engines,
                  "mujoco,mujoco3: the model on both versions, body by body (mass, inertia, "
                  "contacts, loads), each difference with its cause")
      ->excludes("--engine");
  cmd->add_option("--key", options->inspect.key,
                  "Keyframe to inspect the model at (default: qpos0)");
  cmd->add_option("--settle", options->inspect.settle,
                  "Let MuJoCo step the model this many seconds first (from the keyframe or "
                  "qpos0), so it comes to rest on what it touches (>= 0; default 0)");
  cmd->add_flag("--estimate-loads", options->inspect.estimate_loads,
                "Loads from the least-squares split of gravity over the contacts (an "
                "estimate) instead of MuJoCo's own contact forces");
  cmd->add_option("--body", options->inspect.body,
                  "Only the contacts and pairs of this body (the loads still come from all)");
  cmd->add_flag("--pairs", options->inspect.pairs,
                "Also list every geom pair that can collide (explicit <pair>s and default "
                "collisions)");
  cmd->add_option("--slope", options->slope,
                  "Slope in degrees, [0, 90): the speed each contact creeps at under friction");
  cmd->add_flag("!--no-rest-search", options->rest_search,
                "When the model is not at rest, do not re-read it with longer settles to say "
                "how long it takes (up to 120 s of settling, 20 s of reading)");
  cmd->add_flag("--json", options->json, "Print JSON instead of text");
  return {cmd, [options] { return inspect(*options); }};
}

}  // namespace contact2d::cli
