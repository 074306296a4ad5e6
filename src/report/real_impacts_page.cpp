// validation/report/real_impacts.md: both engines against recorded real
// impacts (analysis/real_impacts.hpp): every model's held-out error on both
// splits, the fitted parameters with their spread, k's profile, the engines'
// distance per impact, what no model captures, and the pictures.
#include <cmath>
#include <sstream>
#include <string>

#include "core/format.hpp"
#include "io/table.hpp"
#include "report/pages.hpp"

namespace contact2d::report {
namespace {

std::string impact_fixed(double v, int digits) {
  return format_number(("%." + std::to_string(digits) + "f").c_str(), v);
}
std::string impact_sig(double v) { return format_number("%.3g", v); }

const analysis::ModelFit* find_model(const analysis::SplitFit& s, const std::string& name,
                                     const std::string& engine) {
  for (const analysis::ModelFit& m : s.models)
    if (m.name == name && m.engine == engine) return &m;
  return nullptr;
}

std::string model_description(const analysis::ModelFit& m) {
  if (m.name == "penalty" && m.engine == "ref")
    return "the reference: Kelvin–Voigt k, c, tanh friction μ, rolling resistance μ_roll, fitted";
  if (m.name == "penalty")
    return m.engine + " with the reference's fitted k, c, μ, μ_roll (calibrated mapping)";
  if (m.name == "penalty_no_rolling") return "the reference without rolling resistance, fitted";
  if (m.name == "constant") return "the training impacts' mean velocity after the impact";
  if (m.name == "newton_coulomb")
    return "one impulse: Newton's restitution, Coulomb's bound, fitted";
  if (m.name == "irb_bound")
    return "the best impulse at the lowest point, chosen after the fact for each impact (a bound)";
  return "";
}

}  // namespace

std::string real_impacts_page(const RealImpactsData& d) {
  std::ostringstream o;
  o << "# Against real impacts\n\n";
  if (!d.not_run.empty()) {
    o << "Not run: " << d.not_run << "\n";
    return o.str();
  }
  const analysis::ImpactFit& f = d.fit;
  o << "Every other page measures the engines against their own law or against each other. "
       "This one measures them against real contacts: "
    << f.impacts.size() << " recorded impacts of an elliptical plate (`" << d.recording << "`; "
    << f.flagged_left_out
    << " more carry one of the recording's quality flags and are left out). contact2d fits the "
       "contact law's k, c, μ and μ_roll on half of them and predicts the other half; MuJoCo "
       "2.2.2 and 3.14 get the fitted values through the calibrated mapping. The same numbers: "
       "`contact2d fit "
    << d.recording << "` (docs/real-impacts.md says how it works).\n\n";
  o << "- **Replayed from first touch:** " << f.lifted
    << " pre-impact states already penetrated the ground (median "
    << impact_sig(f.median_lift * 1e3)
    << " mm) and were moved up along the normal until the body just touches; the others fly "
       "freely to first touch. Each replay runs until the body leaves the ground.\n"
    << "- **The error of one impact:** ‖W(v̂ − v)‖ / ‖W v‖ over (vx, vy, ω) just after it, "
       "W = diag(1, 1, √(I/m)) (I/m = "
    << impact_sig(f.inertia / f.mass)
    << " m²). A model's figure: the median over the held-out impacts, and the interquartile "
       "range.\n"
    << "- **Splits:** seeded (shuffled, seed 2026) and chronological (by drop number), 50/50.\n\n";
  for (const std::string& picture : d.pictures) o << "![" << picture << "](" << picture << ")\n\n";

  o << "## Held-out error\n\n";
  Table t{
      {"model", "engine", "what it is", "seeded: median", "IQR", "chronological: median", "IQR"},
      {}};
  if (!f.splits.empty()) {
    for (const analysis::ModelFit& m : f.splits[0].models) {
      std::vector<std::string> row = {m.name, m.engine, model_description(m),
                                      impact_fixed(m.median, 3),
                                      impact_fixed(m.q1, 3) + "–" + impact_fixed(m.q3, 3)};
      const analysis::ModelFit* c =
          f.splits.size() > 1 ? find_model(f.splits[1], m.name, m.engine) : nullptr;
      row.push_back(c ? impact_fixed(c->median, 3) : "—");
      row.push_back(c ? impact_fixed(c->q1, 3) + "–" + impact_fixed(c->q3, 3) : "—");
      add_row(t, row);
    }
  }
  o << to_markdown(t) << "\n";
  for (const analysis::SplitFit& s : f.splits) {
    const analysis::ModelFit* ref = find_model(s, "penalty", "ref");
    const analysis::ModelFit* bound = find_model(s, "irb_bound", "baseline");
    if (ref && bound)
      o << "- " << s.split << ": the reference's median " << impact_fixed(ref->median, 3) << " is "
        << (ref->median < bound->median ? "below" : "not below")
        << " the best impulse chosen after the fact (" << impact_fixed(bound->median, 3) << ").\n";
    for (const analysis::SplitFit::Distance& dist : s.engine_distances)
      o << "- " << s.split << ": " << dist.a << " and " << dist.b
        << " apart per impact (median, same metric): " << impact_sig(dist.median) << "\n";
  }

  o << "\n## The fitted parameters\n\n";
  Table p{{"split", "k (N/m)", "ζ", "c (N·s/m)", "μ", "μ_roll (m)"}, {}};
  for (const analysis::SplitFit& s : f.splits) {
    const analysis::ModelFit* ref = find_model(s, "penalty", "ref");
    if (!ref) continue;
    std::vector<std::string> row = {s.split};
    for (size_t i = 0; i < ref->parameters.size(); ++i) {
      std::string cell = impact_sig(ref->parameters[i].second);
      if (i < ref->spread.size())
        cell +=
            " (" + impact_sig(ref->spread[i].first) + "–" + impact_sig(ref->spread[i].second) + ")";
      row.push_back(cell);
    }
    add_row(p, row);
  }
  o << to_markdown(p)
    << "\nIn parentheses: the 16th–84th percentiles of bootstrap refits on resampled training "
       "sets. k is the parameter the impacts do not pin down: the profile below holds k and "
       "refits the rest.\n\n";
  if (!f.splits.empty() && !f.splits[0].k_profile.empty()) {
    Table k{{"k (N/m)", "training median error"}, {}};
    for (const auto& [kv, e] : f.splits[0].k_profile)
      add_row(k, {impact_sig(kv), impact_fixed(e, 4)});
    o << to_markdown(k) << "\n";
  }

  o << "## What no model here captures\n\n";
  if (!f.splits.empty())
    o << "Measured over the seeded split's held-out impacts, the spin changes by "
      << impact_fixed(f.splits.front().spin_slope, 2)
      << " × what a point impulse at the lowest point (at first touch) with the measured "
      << "change of velocity would give, plus " << impact_sig(f.splits.front().spin_intercept)
      << " rad/s (least squares). ";
  o << "No impulse through that point has that freedom; rolling "
       "resistance, a torque, takes up part of it, which is why the penalty law with μ_roll "
       "beats every impulse model. What remains is not in these laws: the plate's edge is not "
       "a point (it rocks through the contact), the 250 Hz camera's velocities are finite "
       "differences over 4 ms, and the recording's flags show that some impacts bounce "
       "twice.\n";
  return o.str();
}

}  // namespace contact2d::report
