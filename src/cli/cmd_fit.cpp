// contact2d fit RECORDING [--json] [--seed N] [--bootstrap B] [--threads N]
//                         [--engines LIST] [--all-impacts] [--omega-dt X] [--quiet]
// A recording of real impacts or trajectories in (docs/recordings.md), the
// contact law's k, c (ζ), μ (and μ_roll for impacts) out, and every model
// measured on held-out impacts (analysis/real_impacts.hpp,
// docs/real-impacts.md) or trajectories (analysis/real_trajectories.hpp,
// docs/real-trajectories.md).
#include <algorithm>
#include <iostream>
#include <memory>

#include "analysis/real_impacts.hpp"
#include "analysis/real_trajectories.hpp"
#include "cli/common.hpp"
#include "core/input_error.hpp"
#include "io/recording.hpp"

namespace contact2d::cli {

namespace {

struct FitOptions {
  std::string recording;
  bool json = false;
  long long seed = 2026;
  int bootstrap = 8;
  unsigned threads = 0;
  std::vector<std::string> engines;
  bool engines_given = false;
  bool all_impacts = false;
  bool bootstrap_given = false;
  double omega_dt = 0.0;  // 0: the fit's default
  bool quiet = false;
};

int fit_trajectories(const FitOptions& o, const Recording& rec) {
  if (o.bootstrap_given || o.all_impacts)
    throw InputError(std::string(o.all_impacts ? "--all-impacts" : "--bootstrap") +
                     ": applies to impacts recordings; " + o.recording +
                     " holds trajectories (kind = \"trajectories\")");
  analysis::TrajectoryFitOptions options;
  options.seed = static_cast<std::uint64_t>(o.seed);
  options.threads = o.threads;
  options.engines = o.engines;
  if (o.omega_dt > 0.0) options.omega_dt = o.omega_dt;
  if (!o.quiet) options.progress = [](const std::string& line) { std::cerr << line << "\n"; };
  const analysis::TrajectoryFit result = analysis::fit_trajectories(rec, options);
  std::cout << (o.json ? analysis::trajectory_fit_json(result)
                       : analysis::trajectory_fit_text(result));
  return kExitOk;
}

int fit(FitOptions o) {
  const Recording rec = read_recording(o.recording);
  if (!o.engines_given) o.engines = analysis::default_fit_engines();
  o.engines.erase(std::remove(o.engines.begin(), o.engines.end(), ""), o.engines.end());
  // Each engine once: the reference replays the fit always (so "ref" adds
  // nothing), and an engine named twice printed its rows twice.
  for (size_t i = 0; i < o.engines.size(); ++i) {
    if (o.engines[i] == "ref")
      throw InputError(
          "--engines ref: the reference always replays the fit; list the other engines");
    for (size_t j = 0; j < i; ++j)
      if (o.engines[j] == o.engines[i])
        throw InputError("--engines: " + o.engines[i] + " is named twice; name each engine once");
  }
  if (rec.kind == "trajectories") return fit_trajectories(o, rec);
  analysis::ImpactFitOptions options;
  options.seed = static_cast<std::uint64_t>(o.seed);
  options.bootstrap = o.bootstrap;
  options.threads = o.threads;
  options.engines = o.engines;
  options.all_impacts = o.all_impacts;
  if (o.omega_dt > 0.0) options.omega_dt = o.omega_dt;
  if (!o.quiet) options.progress = [](const std::string& line) { std::cerr << line << "\n"; };
  const analysis::ImpactFit result = analysis::fit_impacts(rec, options);
  std::cout << (o.json ? analysis::impact_fit_json(result) : analysis::impact_fit_text(result));
  return kExitOk;
}

}  // namespace

Command add_fit(CLI::App& app) {
  auto o = std::make_shared<FitOptions>();
  CLI::App* cmd = app.add_subcommand(
      "fit",
      "Fit k, c, mu (and mu_roll for impacts) to a recording of real impacts or trajectories and "
      "measure every model (the reference, MuJoCo 2.2.2 and 3.14, impulse baselines or the "
      "recording's peer engine) on held-out impacts or trajectories");
  cmd->add_option("recording", o->recording,
                  "The recording's manifest (TOML; docs/recordings.md), e.g. "
                  "validation/real/ellipse/recording.toml")
      ->required();
  cmd->add_flag("--json", o->json, "Print one JSON object instead of the table");
  cmd->add_option("--seed", o->seed, "Seed of the 50/50 split's shuffle (default 2026)")
      ->check(CLI::Range(0LL, 1LL << 53));
  cmd->add_option("--bootstrap", o->bootstrap,
                  "Refits on resampled training sets for the parameters' spread (default 8; 0: "
                  "none)")
      ->check(CLI::Range(0, 1000))
      ->check(CLI::Validator(
          [](const std::string& v) {
            // One refit has no spread: 0 (none) or at least 2.
            return v == "1" ? std::string("1 refit gives no spread: 0 (none) or 2 to 1000")
                            : std::string();
          },
          "", "bootstrap"))
      ->each([o](const std::string&) { o->bootstrap_given = true; });
  cmd->add_option("--threads", o->threads, "Threads (default: one per core)")
      ->check(CLI::Range(0u, 256u));
  cmd->add_option("--engines", o->engines,
                  "Comma-separated engines that replay the held-out impacts with the fitted "
                  "parameters besides the reference (default: every built-in engine with soft "
                  "constraints; \"\": none)")
      ->delimiter(',')
      ->each([o](const std::string&) { o->engines_given = true; });
  cmd->add_flag("--all-impacts", o->all_impacts,
                "Also the impacts the recording flags (its flags column)");
  cmd->add_option("--omega-dt", o->omega_dt,
                  "omega dt of the replays, omega = sqrt(k/m_eff): impacts 0.02 by default; "
                  "trajectories the largest, 0.05 by default (dt then divides the frame period)")
      ->check(CLI::Range(1e-4, 0.5));
  cmd->add_flag("--quiet", o->quiet, "No progress lines on stderr");
  return {cmd, [o] { return fit(*o); }};
}

}  // namespace contact2d::cli
