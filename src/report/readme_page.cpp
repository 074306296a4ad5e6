// validation/report/README.md: the reference against MuJoCo on the built-in
// scenes (report/pages.hpp). Prose numbers come from report/numbers.hpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/format.hpp"
#include "io/json_reader.hpp"
#include "io/table.hpp"
#include "report/numbers.hpp"
#include "report/pages.hpp"

namespace contact2d::report {
namespace {

std::string per_step(double seconds, const ComparisonRow& c) {
  return format_significant(micros_per_step(seconds, c.duration, c.dt));
}

// MuJoCo 3.14's cell beside a 2.2.2 figure: its own figure where the
// versions differ by more than rounding, else how close to 2.2.2 it is.
std::string v3_cell(double v3_value, double apart) {
  if (versions_differ(apart))
    return format_significant(v3_value) + " (" + versions_apart_text(apart) + ")";
  return versions_apart_text(apart);
}

// The 2.2.2 table, and a MuJoCo 3.14 column when `v3` holds its runs of the
// same cases (in the same order).
std::string mapping_table(const std::vector<MappingCase>& cases,
                          const std::vector<MappingCase>& v3 = {}) {
  Table t{{"scene / mapping", "max pos (m)", "RMS pos (m)", "max angle (rad)", "max vel (m/s)",
           "end pos (m)", "ref µs/step", "MuJoCo µs/step"},
          {}};
  if (!v3.empty()) t.columns.push_back("MuJoCo 3.14: max pos (m)");
  for (size_t i = 0; i < cases.size(); ++i) {
    const MappingCase& c = cases[i];
    const ComparisonRow& r = c.result;
    std::vector<std::string> row{c.scene + " / " + c.mapping,   format_significant(r.max_pos),
                                 format_significant(r.rms_pos), format_significant(r.max_angle),
                                 format_significant(r.max_vel), format_significant(r.end_pos),
                                 per_step(r.ref_seconds, r),    per_step(r.mujoco_seconds, r)};
    if (!v3.empty()) row.push_back(v3_cell(v3[i].result.max_pos, v3[i].v2_vs_v3));
    add_row(t, row);
  }
  return to_markdown(t);
}

std::string winners(const std::vector<MappingCase>& cases, const ReadmeData& data) {
  std::string out;
  for (const SceneWinner& w : scene_winners(cases, data.scenes, data.mappings)) {
    out += "- " + w.scene + ": **" + w.mapping + "** (" + format_significant(w.error) + " m), " +
           ratio_phrase(w.ratio_to_next, "smaller than", "the next best mapping") + "\n";
  }
  const std::vector<MappingMean> means = mapping_means(cases, data.scenes, data.mappings);
  for (const MappingMean& m : means) {
    out += "- geometric mean over the " + count_words(static_cast<int>(data.scenes.size())) +
           " scenes, " + m.mapping + ": " + format_significant(m.mean) + " m\n";
  }
  const OverallWinner overall = overall_winner(means);
  out += "- overall: **" + overall.mapping + "**, its geometric-mean error " +
         ratio_phrase(overall.ratio_to_next, "below", "the next best mapping's") + "\n";
  return out;
}

std::string goal_table(const std::vector<GoalCase>& goals) {
  Table t{
      {"case", "impratio", "max pos (m)", "goal (m)", "max angle (rad)", "goal (rad)", "reached"},
      {}};
  const bool v3 = std::any_of(goals.begin(), goals.end(),
                              [](const GoalCase& c) { return !std::isnan(c.v2_vs_v3); });
  if (v3) t.columns.push_back("MuJoCo 3.14: max pos (m)");
  for (const GoalCase& c : goals) {
    const ComparisonRow& r = c.result;
    const bool ok = goal_reached(r.max_pos, r.max_angle, c.pos_goal, c.angle_goal);
    std::vector<std::string> row{c.label,
                                 format_significant(r.impratio),
                                 format_significant(r.max_pos),
                                 sci(c.pos_goal),
                                 format_significant(r.max_angle),
                                 c.angle_goal ? sci(*c.angle_goal) : "-",
                                 ok ? "yes" : "**no**"};
    if (v3) row.push_back(v3_cell(c.v3_max_pos, c.v2_vs_v3));
    add_row(t, row);
  }
  return to_markdown(t);
}

std::string geometry_table(const std::vector<GeometryCase>& cases) {
  Table t{{"case", "geometry", "max pos (m)", "max angle (rad)", "MuJoCo µs/step"}, {}};
  for (const GeometryCase& c : cases) {
    const ComparisonRow& r = c.result;
    add_row(t, {c.scene + ", " + (c.friction ? "friction" : "frictionless"), c.geometry,
                format_significant(r.max_pos), format_significant(r.max_angle),
                per_step(r.mujoco_seconds, r)});
  }
  return to_markdown(t);
}

std::string integrator_table(const std::vector<IntegratorCase>& cases) {
  Table t{
      {"scene", "integrator", "max pos (m)", "max angle (rad)", "ref µs/step", "MuJoCo µs/step"},
      {}};
  for (const IntegratorCase& c : cases) {
    const ComparisonRow& r = c.result;
    add_row(t, {c.scene, c.integrator + " / " + r.mujoco_integrator, format_significant(r.max_pos),
                format_significant(r.max_angle), per_step(r.ref_seconds, r),
                per_step(r.mujoco_seconds, r)});
  }
  return to_markdown(t);
}

std::string causes_text(const ThreeWayCase& c, double named_share) {
  if (c.agrees) return "agree (nothing to explain)";
  if (c.causes.empty())
    return "none of the re-runs removes ≥ " + format_text("%.0f %%", 100.0 * named_share);
  std::string out;
  for (const CauseShare& cause : c.causes) {
    out += (out.empty() ? "" : "; ") + cause.cause + " " +
           format_text("%.0f %%", std::round(100.0 * cause.share) + 0.0) +
           (cause.fix.empty() ? "" : " (`" + cause.fix + "`)");
  }
  std::string skipped;
  for (const std::string& cause : c.not_rerun) skipped += (skipped.empty() ? "" : ", ") + cause;
  if (!skipped.empty()) out += "; not re-run: " + skipped + " (`--full-diagnosis`)";
  return out;
}

std::string three_way_table(const std::vector<ThreeWayCase>& cases, double named_share) {
  Table t{{"scene", "law", "ref ↔ converged (m)", "MuJoCo ↔ converged (m)", "ref ↔ MuJoCo (m)",
           "amplification", "named causes (share removed, option)"},
          {}};
  const bool v3 = std::any_of(cases.begin(), cases.end(),
                              [](const ThreeWayCase& c) { return !std::isnan(c.v2_vs_v3); });
  if (v3) t.columns.push_back("MuJoCo 3.14: ref ↔ 3.14 (m)");
  for (const ThreeWayCase& c : cases) {
    std::vector<std::string> row{c.scene,
                                 c.law,
                                 c.converged ? format_significant(c.ref_vs_converged) : "-",
                                 c.converged ? format_significant(c.mujoco_vs_converged) : "-",
                                 format_significant(c.ref_vs_mujoco),
                                 c.converged ? format_significant(c.amplification) : "-",
                                 causes_text(c, named_share)};
    if (v3) row.push_back(v3_cell(c.ref_vs_v3, c.v2_vs_v3));
    add_row(t, row);
  }
  return to_markdown(t);
}

// Each animation, and under it MuJoCo 3.14's: its own where it differs
// from 2.2.2 by more than rounding, else how close to 2.2.2 it stays.
std::string animations(const std::vector<ThreeWayCase>& cases, const std::string& note) {
  std::string out;
  for (const ThreeWayCase& c : cases) {
    if (c.animation.empty()) continue;
    out += "![" + c.scene + ", " + c.law + ": both engines](" + c.animation + ")\n";
    if (!c.animation_v3.empty()) {
      out += "![" + c.scene + ", " + c.law + ": the reference and MuJoCo 3.14](" + c.animation_v3 +
             ")\n";
    } else if (!std::isnan(c.v2_vs_v3)) {
      out += "\n" + c.scene + " on MuJoCo 3.14: " + versions_apart_text(c.v2_vs_v3) + ".\n\n";
    }
  }
  if (out.empty()) return "(No animations: " + note + ".)\n";
  return "\n" + out;
}

std::string random_table(const std::vector<RandomCase>& cases) {
  Table t{{"scene", "shape", "m (kg)", "k (N/m)", "c (N·s/m)", "ζ", "μ", "max pos, μ = 0 (m)",
           "max angle, μ = 0 (rad)", "max pos, with μ (m)"},
          {}};
  for (const RandomCase& c : cases) {
    add_row(t,
            {c.name, c.shape, format_significant(c.mass, 6), format_significant(c.k, 6),
             format_significant(c.c, 6), format_significant(random_zeta(c)),
             format_significant(c.mu), format_significant(c.max_pos_frictionless),
             format_significant(c.max_angle_frictionless), format_significant(c.max_pos_friction)});
  }
  return to_markdown(t);
}

std::string band_name(const ZetaBand& b) {
  if (b.lo <= 0.0) return "ζ < " + format_significant(b.hi);
  if (!std::isfinite(b.hi)) return "ζ ≥ " + format_significant(b.lo);
  return format_significant(b.lo) + " ≤ ζ < " + format_significant(b.hi);
}

// The random scenes under each mapping that ran them: calibrated (the
// default), then compensated when the report ran it.
std::vector<std::pair<std::string, const std::vector<RandomCase>*>> random_runs(
    const ReadmeData& d) {
  std::vector<std::pair<std::string, const std::vector<RandomCase>*>> runs{
      {"calibrated", &d.random}};
  if (!d.random_compensated.empty()) runs.emplace_back("compensated", &d.random_compensated);
  return runs;
}

std::string band_table(const ReadmeData& d) {
  Table t{{"ζ band", "mapping", "scenes", "within goal, μ = 0", "median max pos, μ = 0 (m)",
           "max pos, μ = 0 (m)", "max angle, μ = 0 (rad)", "max pos, with μ (m)"},
          {}};
  const std::vector<std::pair<std::string, const std::vector<RandomCase>*>> runs = random_runs(d);
  std::vector<std::vector<ZetaBand>> bands;
  bands.reserve(runs.size());
  for (const auto& run : runs) bands.push_back(random_bands(*run.second, d.random_config));
  for (size_t b = 0; b < bands[0].size(); ++b) {
    for (size_t m = 0; m < runs.size(); ++m) {
      const ZetaBand& z = bands[m][b];
      add_row(t, {band_name(z), runs[m].first, std::to_string(z.count), std::to_string(z.reached),
                  format_significant(z.median_pos), format_significant(z.max_pos),
                  format_significant(z.max_angle), format_significant(z.max_pos_friction)});
    }
  }
  return to_markdown(t);
}

std::string band_headline(const std::vector<ZetaBand>& bands) {
  std::string out;
  for (size_t i = 0; i < bands.size(); ++i) {
    const ZetaBand& b = bands[i];
    out += (i == 0                  ? ""
            : i + 1 == bands.size() ? " and "
                                    : ", ") +
           std::to_string(b.reached) + " of " + std::to_string(b.count) + " with " + band_name(b);
  }
  return out;
}

std::string plots(const std::vector<std::string>& scenes,
                  const std::vector<std::string>& law_independent) {
  Table t{{"as shipped", "Kelvin–Voigt"}, {}};
  for (const std::string& s : scenes) {
    const bool same =
        std::find(law_independent.begin(), law_independent.end(), s) != law_independent.end();
    add_row(t, {"![" + s + " as shipped](" + s + ".shipped.png)",
                same ? "the same run (the laws differ only while a contact point moves out of the "
                       "ground, which never happens in " +
                           s + ")"
                     : "![" + s + " with Kelvin–Voigt](" + s + ".kelvin_voigt.png)"});
  }
  return to_markdown(t);
}

// One JSON value's fields as "path → text" ("kicks[0].distance"), in order.
void flatten_json(const json::Value& v, const std::string& path,
                  std::vector<std::pair<std::string, std::string>>& out) {
  switch (v.kind) {
    case json::Value::Kind::Object:
      for (const auto& [name, member] : v.members)
        flatten_json(member, path.empty() ? name : path + "." + name, out);
      return;
    case json::Value::Kind::Array:
      for (size_t i = 0; i < v.items.size(); ++i)
        flatten_json(v.items[i], path + "[" + std::to_string(i) + "]", out);
      return;
    case json::Value::Kind::Number: out.emplace_back(path, format_significant(v.number, 9)); return;
    case json::Value::Kind::Null: out.emplace_back(path, "null"); return;
    default: out.emplace_back(path, v.text); return;
  }
}

// What `play --headless --replay` prints on each engine, a field a row and
// an engine a column (a field one engine lacks: "–"); an output that is not
// JSON stays as it is, in one row.
std::string replay_table(const ReplayComparison& r) {
  Table t{{"field"}, {}};
  std::vector<std::string> fields;
  std::vector<std::vector<std::pair<std::string, std::string>>> values;
  for (const ReplayEngine& e : r.engines) {
    t.columns.push_back(e.engine);
    values.emplace_back();
    try {
      flatten_json(json::parse(e.json, "play's output"), "", values.back());
    } catch (const std::exception&) {
      values.back() = {{"output", e.json}};
    }
    for (const auto& field : values.back())
      if (std::find(fields.begin(), fields.end(), field.first) == fields.end())
        fields.push_back(field.first);
  }
  for (const std::string& field : fields) {
    std::vector<std::string> row{"`" + field + "`"};
    for (const auto& of_engine : values) {
      const auto it = std::find_if(of_engine.begin(), of_engine.end(),
                                   [&](const auto& v) { return v.first == field; });
      row.push_back(it == of_engine.end() ? "–" : it->second);
    }
    add_row(t, row);
  }
  return "What `play` prints (its JSON, a field a row):\n\n" + to_markdown(t);
}

std::string replay_section(const ReplayComparison& r) {
  std::string out =
      "## 9. The game's goal replay on both engines\n\n`contact2d play --headless --replay " +
      r.replay + " [--engine mujoco]`: the same key events on both engines.\n\n";
  out += replay_table(r);
  auto when = [](const std::optional<double>& s) {
    return s ? "at t = " + format_significant(*s) + " s" : std::string("never");
  };
  out += "\nThe two balls are 0.01 m apart " + when(r.part_1cm) + " and a ball radius (" +
         format_significant(r.radius) + " m) apart " + when(r.part_radius) +
         ".\n\n![The goal replay on both engines](" + r.plot + ")\n";
  if (!r.gif.empty()) {
    out +=
        "\nThe same goal as the window shows it, the ball chipped over the keeper (recorded on "
        "the reference by `scripts/record-goal`" +
        (r.mp4.empty() ? std::string() : "; the whole video: [" + r.mp4 + "](" + r.mp4 + ")") +
        "):\n\n![A goal against the keeper](" + r.gif + ")\n";
  }
  return out;
}

// "`--mapping compensated`: 1.2× below the next best mapping": the mapping
// whose geometric-mean error over the built-in scenes (Kelvin–Voigt) is the
// smallest on one version, and by how much.
std::string closest_mapping(const ReadmeData& d, const std::vector<MappingCase>& cases) {
  const OverallWinner w = overall_winner(mapping_means(cases, d.scenes, d.mappings));
  return "`--mapping " + w.mapping +
         "`: " + ratio_phrase(w.ratio_to_next, "below", "the next best mapping");
}

// What to do with friction on each version: 2.2.2 has no setting that
// removes the push; MuJoCo 3.14's damper where it helps and where it hurts.
std::string damper_text(const std::vector<DamperCase>& cases, const std::string& verb) {
  std::string out;
  for (const DamperCase& c : cases) {
    out += (out.empty() ? "" : "; ") + verb + " " + c.label + ": " + format_significant(c.without) +
           " → " + format_significant(c.with) + " m";
  }
  return out;
}

// The first screen's advice, per version: one mapping to build on, the one
// that measures closer when it is another, and what to do with friction.
std::string recommendation(const ReadmeData& d) {
  const bool v3 = !d.kelvin_voigt_v3.empty();
  // The runs behind the geometric means: each scene under each mapping.
  std::string scene_list, mapping_list;
  for (const std::string& s : d.scenes) scene_list += (scene_list.empty() ? "" : ", ") + s;
  for (const std::string& m : d.mappings) mapping_list += (mapping_list.empty() ? "" : ", ") + m;
  std::string out =
      "## In short\n\n**Use the `calibrated` mapping** on either version of MuJoCo (the default "
      "of `contact2d generate` and `compare`; `contact2d solref` gives its numbers for your own "
      "model): it sets only `solref`, `solimp` and MuJoCo's options, from k, c and the body's "
      "`body_invweight0`. " +
      std::string(v3 ? "MuJoCo 3.14 is `--engine mujoco3` (the model written for MuJoCo 3: "
                       "`contact2d generate --engine mujoco3`; docs/mujoco3.md)."
                     : "MuJoCo 3.14 did not run here (" + d.mujoco3_not_run + ").") +
      "\n\n";
  Table t{{"advice", "MuJoCo 2.2.2"}, {}};
  if (v3) t.columns.push_back("MuJoCo 3.14");
  auto row = [&](std::vector<std::string> cells) {
    if (!v3) cells.pop_back();
    add_row(t, cells);
  };
  row({"a model to build on", "`calibrated`", "`calibrated`"});
  row({"for comparing with the reference", closest_mapping(d, d.kelvin_voigt),
       v3 ? closest_mapping(d, d.kelvin_voigt_v3) : ""});
  const std::string helps = damper_text(d.damper_helps, "helps most on");
  const std::string hurts = damper_text(d.damper_hurts, "hurts most on");
  row({"with friction", "no setting removes the cone's push (friction.md)",
       "the friction rows' own damper (`--engine " + std::string(kDamperEngines[1]) +
           "`, `--friction damper`) " + helps + (hurts.empty() ? "" : "; " + hurts)});
  out += to_markdown(t);
  out +=
      "\nFor comparing: the geometric-mean error over the built-in scenes with MuJoCo's own "
      "damping law (Kelvin–Voigt; section 2: the geometric mean over SCENE = " +
      scene_list +
      " of the largest position difference of\n`contact2d compare validation/scenes/SCENE.toml "
      "--set contact.damping=kelvin_voigt --mapping MAPPING --allow-nonphysical`, MAPPING = " +
      mapping_list +
      (v3 ? "; on 3.14 `--engine mujoco3:MAPPING` in place of `--mapping MAPPING`" : "") + ").";
  const bool compensated =
      overall_winner(mapping_means(d.kelvin_voigt, d.scenes, d.mappings)).mapping ==
          "compensated" ||
      (v3 && overall_winner(mapping_means(d.kelvin_voigt_v3, d.scenes, d.mappings)).mapping ==
                 "compensated");
  if (compensated)
    out +=
        " `compensated` moves the contact geoms onto a massless body at a long lever "
        "(docs/mujoco.md): a structure for comparing, not for a model to build on.";
  if (v3 && !d.damper_helps.empty() && !d.damper_hurts.empty()) {
    out += " The damper's figures: `" + d.damper_helps.front().command + "` and\n`" +
           d.damper_hurts.front().command + "`, each with `--engine " + kDamperEngines[0] +
           "` (without) and `--engine " + kDamperEngines[1] +
           "` (with; friction.md and versions.md have it on every scene).";
  }
  out += "\n\n";
  return out;
}

// MuJoCo 3.14's runs of the random scenes beside random_runs(d)'s (the
// same order), or nullptr where it did not run.
std::vector<const std::vector<RandomCase>*> random_runs_v3(const ReadmeData& d) {
  std::vector<const std::vector<RandomCase>*> out{d.random_v3.empty() ? nullptr : &d.random_v3};
  if (!d.random_compensated.empty())
    out.push_back(d.random_compensated_v3.empty() ? nullptr : &d.random_compensated_v3);
  return out;
}

// The largest 2.2.2 ↔ 3.14 distance over MuJoCo 3.14's runs of the random
// scenes (NaN when it did not run).
double random_versions_apart(const ReadmeData& d) {
  double apart = std::numeric_limits<double>::quiet_NaN();
  for (const std::vector<RandomCase>* runs : random_runs_v3(d)) {
    if (!runs) continue;
    for (const RandomCase& c : *runs)
      apart = std::isnan(apart) ? c.v2_vs_v3 : std::max(apart, c.v2_vs_v3);
  }
  return apart;
}

// Section 6's MuJoCo 3.14 line: the random scenes where it parts from
// 2.2.2 by more than rounding, under which mapping and by how much.
std::string random_versions_text(const ReadmeData& d) {
  const std::vector<std::pair<std::string, const std::vector<RandomCase>*>> runs = random_runs(d);
  const std::vector<const std::vector<RandomCase>*> runs_v3 = random_runs_v3(d);
  if (!runs_v3.front()) return "";
  std::string differ;
  for (size_t m = 0; m < runs.size(); ++m) {
    if (!runs_v3[m]) continue;
    for (const RandomCase& c : *runs_v3[m]) {
      if (versions_differ(c.v2_vs_v3))
        differ += (differ.empty() ? "" : ", ") + c.name + " " + runs[m].first + " (" +
                  format_significant(c.v2_vs_v3, 2) + " m)";
    }
  }
  return "\nMuJoCo 3.14 on the same scenes (`--engine mujoco3`; its columns in the first "
         "screen's table): " +
         (differ.empty()
              ? versions_apart_text(random_versions_apart(d)) + " on every run"
              : "more than " + sci(kVersionsRounding) +
                    " m from 2.2.2 (the largest distance over both runs) in " + differ +
                    "; every other scene within " + sci(kVersionsRounding) + " m of it") +
         ".\n";
}

// How close MuJoCo then is on the random scenes, by damping band and
// mapping, on each version, with the command behind each row.
std::string closeness_by_band(const ReadmeData& d) {
  const RandomConfig& rc = d.random_config;
  const std::vector<std::pair<std::string, const std::vector<RandomCase>*>> runs = random_runs(d);
  const std::vector<const std::vector<RandomCase>*> runs_v3 = random_runs_v3(d);
  const bool v3 = runs_v3.front() != nullptr;
  std::string out;
  out += "**How close MuJoCo then is** — " + count_words(rc.count) +
         " random scenes (section 6), Δt = 1e-4, semi-implicit Euler against MuJoCo's Euler;\n"
         "each scene of section 6, in the band of its ζ, re-runs with `contact2d compare " +
         d.random_dir +
         "/sNN.toml`\n(add `--set contact.mu=0` for the frictionless columns, `--mapping "
         "compensated` for the compensated rows" +
         (v3 ? ", `--engine mujoco3` for MuJoCo 3.14's columns, `--engine "
               "mujoco3:compensated` in place of `--mapping compensated`"
             : "") +
         "):\n\n";
  const std::string goal = "within " + sci(rc.pos_goal) + " m and " + sci(rc.angle_goal) + " rad";
  Table t{{"damping ratio", "mapping", "scenes", "without friction: " + goal,
           "without friction: median / largest position difference (m)",
           "with friction: largest position difference (m)"},
          {}};
  if (v3) {
    t.columns.push_back("3.14 without friction: " + goal);
    t.columns.emplace_back("3.14 without friction: median / largest (m)");
    t.columns.emplace_back("3.14 with friction: largest (m)");
  }
  std::vector<std::vector<ZetaBand>> by_mapping, by_mapping_v3;
  for (size_t m = 0; m < runs.size(); ++m) {
    by_mapping.push_back(random_bands(*runs[m].second, rc));
    if (v3) by_mapping_v3.push_back(random_bands(*runs_v3[m], rc));
  }
  for (size_t b = 0; b < by_mapping[0].size(); ++b) {
    for (size_t m = 0; m < runs.size(); ++m) {
      const ZetaBand& z = by_mapping[m][b];
      std::vector<std::string> row{
          band_name(z),
          runs[m].first,
          std::to_string(z.count),
          std::to_string(z.reached),
          format_significant(z.median_pos) + " / " + format_significant(z.max_pos),
          format_significant(z.max_pos_friction)};
      if (v3) {
        const ZetaBand& z3 = by_mapping_v3[m][b];
        row.push_back(std::to_string(z3.reached));
        row.push_back(format_significant(z3.median_pos) + " / " + format_significant(z3.max_pos));
        row.push_back(format_significant(z3.max_pos_friction));
      }
      add_row(t, row);
    }
  }
  out += to_markdown(t);
  if (v3) {
    const double apart = random_versions_apart(d);
    out += "\nMuJoCo 3.14 against 2.2.2 on every one of these runs: " +
           std::string(versions_differ(apart) ? "up to " + format_significant(apart, 2) +
                                                    " m apart (more than rounding)"
                                              : versions_apart_text(apart)) +
           ".\n";
  }
  if (runs.size() > 1)
    out +=
        "\n`compensated` (`--mapping compensated`) removes the calibrated force's O(d) term "
        "(section 6); with friction\nboth keep MuJoCo's cone, whose push on a sliding body no "
        "2.2.2 setting removes.\n";
  return out;
}

// With friction: the measured parts (analysis::friction_parts), per mapping
// and version (the cone's shape and its push are two runs of the
// reference, the same for both versions).
std::string friction_parts_table(const ReadmeData& d) {
  const std::vector<std::pair<std::string, const std::vector<RandomCase>*>> runs = random_runs(d);
  const std::vector<const std::vector<RandomCase>*> runs_v3 = random_runs_v3(d);
  std::string out;
  constexpr double kFrictionGoal = 1e-3;
  out +=
      "\n**With friction** the difference is MuJoCo's friction law. Taken apart on the same "
      "random scenes (medians; with friction: the commands above, and the rest: their "
      "diagnosis's\n`friction_law` re-run, the distance it leaves (where they agree and no "
      "diagnosis runs: add `--set contact.friction_law=soft_cone --set contact.cone_ratio=I`, I "
      "the impratio\ncompare prints); `friction.md` has the method, the cone's shape and its push "
      "too, and every 2.2.2 setting tried):\n\n";
  Table parts{{"mapping", "MuJoCo", "with friction", "within " + sci(kFrictionGoal) + " m",
               "the cone's shape", "its push", "the rest: the reference under MuJoCo's law",
               "the rest within " + sci(kFrictionGoal) + " m"},
              {}};
  for (size_t m = 0; m < runs.size(); ++m) {
    for (const std::vector<RandomCase>* cases : {runs[m].second, runs_v3[m]}) {
      if (!cases) continue;
      const FrictionSummary f = friction_summary(*cases, kFrictionGoal);
      add_row(parts, {runs[m].first, cases == runs[m].second ? "2.2.2" : "3.14",
                      format_significant(f.median_total),
                      std::to_string(f.within) + " of " + std::to_string(f.count),
                      format_significant(f.median_shape), format_significant(f.median_push),
                      format_significant(f.median_rest) + " (largest " +
                          format_significant(f.max_rest) + ")",
                      std::to_string(f.rest_within) + " of " + std::to_string(f.count)});
    }
  }
  out += to_markdown(parts);
  return out;
}

// The goal cases on MuJoCo 3.14 (the figures of the 2.2.2 sentence of
// builtin_verdict), empty when it did not run.
std::string builtin_verdict_v3(const ReadmeData& d) {
  const RandomConfig& rc = d.random_config;
  double frictionless = 0.0, friction = 0.0, rest = 0.0;
  double apart = std::numeric_limits<double>::quiet_NaN();
  int reached = 0, count = 0;
  for (const GoalCase& c : d.goals) {
    if (std::isnan(c.v2_vs_v3)) return "";
    apart = std::isnan(apart) ? c.v2_vs_v3 : std::max(apart, c.v2_vs_v3);
    if (c.label.find("frictionless") != std::string::npos) {
      frictionless = std::max(frictionless, c.v3_max_pos);
      ++count;
      reached += goal_reached(c.v3_max_pos, c.v3_max_angle, c.pos_goal, c.angle_goal);
    } else {
      friction = std::max(friction, c.v3_max_pos);
      if (std::isfinite(c.v3_rest)) rest = std::max(rest, c.v3_rest);
    }
  }
  if (std::isnan(apart)) return "";
  return " On MuJoCo 3.14 (the same commands with `--engine mujoco3`): without friction " +
         std::to_string(reached) + " of " + std::to_string(count) + " within " + sci(rc.pos_goal) +
         " m and " + sci(rc.angle_goal) + " rad (largest " + format_significant(frictionless) +
         " m), with friction up to " + format_significant(friction) +
         " m, under MuJoCo's own law at most " + format_significant(rest) +
         " m; 3.14 against 2.2.2 on these runs: " +
         (versions_differ(apart) ? "up to " + format_significant(apart, 2) + " m apart"
                                 : versions_apart_text(apart)) +
         ".";
}

// The built-in scenes with the Kelvin–Voigt law, and why the engines still
// differ.
std::string builtin_verdict(const ReadmeData& d) {
  const RandomConfig& rc = d.random_config;
  std::string out;
  double frictionless = 0.0, friction = 0.0;
  double builtin_shape = 0.0, builtin_push = 0.0, builtin_rest = 0.0;
  int frictionless_reached = 0, frictionless_count = 0;
  // The goal's damping values, from the labels ("box, c = 200, friction").
  std::vector<std::string> dampings;
  for (const GoalCase& c : d.goals) {
    const size_t at = c.label.find(", c = ");
    if (at == std::string::npos) continue;
    const std::string value = c.label.substr(at + 6, c.label.find(',', at + 6) - (at + 6));
    if (std::find(dampings.begin(), dampings.end(), value) == dampings.end())
      dampings.push_back(value);
  }
  const bool no_roll = std::any_of(d.goals.begin(), d.goals.end(), [](const GoalCase& c) {
    return c.label.find("no rolling resistance") != std::string::npos;
  });
  std::string c_values;
  for (size_t i = 0; i < dampings.size(); ++i)
    c_values += (i == 0 ? "" : i + 1 == dampings.size() ? " and " : ", ") + dampings[i];
  for (const GoalCase& c : d.goals) {
    const bool without = c.label.find("frictionless") != std::string::npos;
    (without ? frictionless : friction) =
        std::max(without ? frictionless : friction, c.result.max_pos);
    if (!without && std::isfinite(c.friction_rest)) {
      builtin_shape = std::max(builtin_shape, c.friction_shape);
      builtin_push = std::max(builtin_push, c.friction_push);
      builtin_rest = std::max(builtin_rest, c.friction_rest);
    }
    if (without) {
      ++frictionless_count;
      frictionless_reached +=
          goal_reached(c.result.max_pos, c.result.max_angle, c.pos_goal, c.angle_goal);
    }
  }
  out += "\n**The built-in scenes** with the Kelvin–Voigt law (section 3): without friction " +
         std::to_string(frictionless_reached) + " of " + std::to_string(frictionless_count) +
         " cases within " + sci(rc.pos_goal) + " m and " + sci(rc.angle_goal) + " rad (largest " +
         format_significant(frictionless) + " m), with friction up to " +
         format_significant(friction) +
         " m apart: `contact2d compare validation/scenes/SCENE.toml --dt 1e-4 --set "
         "contact.damping=kelvin_voigt --set contact.c=C`\nfor C = " +
         c_values + " (add `--set contact.mu=0 --set contact.mu_roll=0` for the frictionless line" +
         (no_roll ? ", and\nwith friction the circle also with `--set contact.mu_roll=0`"
                  : std::string()) +
         "); with the reference running MuJoCo's own friction law\n(the same command's diagnosis, "
         "its `friction_law` re-run: `--set "
         "contact.friction_law=soft_cone` at the model's impratio)\nthey are at most " +
         format_significant(builtin_rest) + " m apart." + builtin_verdict_v3(d) +
         "\n\n"
         "**Why they still differ**: with friction, MuJoCo's friction law — measured on the "
         "built-in scenes, the cone's\nshape (viscous inside it, sliding and rolling under one "
         "budget) moves a body by up to " +
         format_significant(builtin_shape) +
         " m and its push (the damper\nlifting a sliding body) by up to " +
         format_significant(builtin_push) +
         " m, while everything else (under calibrated its O(d) term, section 6; MuJoCo's step) "
         "is at most " +
         format_significant(builtin_rest) +
         " m; no setting of\nMuJoCo 2.2.2 removes the push (`friction.md`); MuJoCo 3.14 has "
         "the same law, and its `--friction damper` takes the push out (the advice above). "
         "Without friction: "
         "bounces of an underdamped body (a\nsmall difference of restitution carried from bounce "
         "to bounce) and, in the shipped scenes, the\ncompression-only damper MuJoCo cannot "
         "represent. `contact2d compare` measures each cause by removing\nit (section 1) and "
         "section 7 explains them.\n\n";
  return out;
}

// The first screen: which mapping, and how close MuJoCo then is, by damping
// band, with and without friction, each line with the command behind it.
std::string summary(const ReadmeData& d) {
  return recommendation(d) + closeness_by_band(d) + friction_parts_table(d) + builtin_verdict(d);
}

// Every page `contact2d report` writes beside this one (report/plan.cpp: page_names()),
// linked from the top of the front page.
std::string page_index() {
  Table t{{"page", "what is in it"}, {}};
  for (const auto& [page, what] : std::vector<std::pair<std::string, std::string>>{
           {"README.md",
            "this page: which mapping, how close MuJoCo 2.2.2 and 3.14 get, every case in "
            "detail"},
           {"sweep.md",
            "error against run time of every integrator and Δt, convergence orders, "
            "the cost per step"},
           {"stability.md",
            "the largest stable Δt per contact stiffness against the linear theory"},
           {"extreme.md", "stiff, light, heavy and fast cases"},
           {"closed_forms.md",
            "both engines and the converged solution against closed forms (rest, rebound, "
            "sliding, rolling, a bounce with backspin, a slope)"},
           {"atlas.md", "a small atlas: how close MuJoCo gets over k × ζ for every body"},
           {"friction.md",
            "with friction: how close MuJoCo gets, every 2.2.2 setting tried, and the "
            "difference taken apart (the cone's shape, its push, the rest)"},
           {"versions.md",
            "MuJoCo 3.14 beside 2.2.2: the distance between the versions, each of MuJoCo 3's "
            "changes measured, friction without the push (MuJoCo 3's damper), and which "
            "version and mapping to use for what"},
           {"real_impacts.md",
            "against real impacts: k, c, μ, μ_roll fitted to recorded impacts of an "
            "ellipse, the reference and both MuJoCo versions on held-out impacts beside "
            "impulse models"}}) {
    add_row(t, {page == "README.md" ? page : "[" + page + "](" + page + ")", what});
  }
  return "## The pages of this report\n\n" + to_markdown(t) + "\n";
}

// The title, the index of pages and the first screen.
std::string readme_intro(const ReadmeData& d) {
  const bool v3 = !d.kelvin_voigt_v3.empty();
  std::string out = std::string(v3 ? "# contact2d against MuJoCo 2.2.2 and 3.14\n"
                                   : "# contact2d against MuJoCo 2.2.2\n") +
                    R"md(
Generated by `contact2d report` (`scripts/demo` builds, then runs it): every
number on this page comes from that run; the wall-clock columns vary from
run to run and machine to machine.)md";
  out += v3 ? " MuJoCo 2.2.2 is the native library the distributions ship; MuJoCo\n3.14 "
              "(`--engine mujoco3`, WebAssembly under Node) runs the model written for it\n"
              "beside it in the same cases, its own figures shown where the two versions\n"
              "part by more than rounding (" +
                  sci(kVersionsRounding) + " m).\n\n"
            : "\n\n";
  out += page_index();
  out += summary(d);
  return out;
}

// How errors are taken and what each mapping sets.
std::string how_to_read_section() {
  std::string out = R"md(## How to read this page

Errors are taken over the output samples (every `sim.output_dt`, the same
times for both engines): position error = distance between the two COMs,
angle error = |θ_ref − θ_MuJoCo|, velocity error = |v_ref − v_MuJoCo| of the
COM. Mappings (`src/mujoco/mapping.hpp` and `docs/mujoco.md` have the derivations):

- `seed`: the common rule of thumb timeconst = √(m/k), dampratio ζ = c/(2√(mk)); MuJoCo's
  default impedance and cone. MuJoCo turns it into stiffness (k/m)/ζ² and
  damping (c/m)/ζ per unit mass: right only at ζ = 1.
- `exact`: timeconst = 2m/c with the same ζ, which MuJoCo turns into exactly
  k/m and c/m: the direct form `solref="-k/m -c/m"` (a test steps both and
  finds the same states); MuJoCo's default impedance and cone.
- `calibrated` (the default): direct form `solref="-k·Â -c·Â"` with Â the
  body's `body_invweight0` read from the compiled model, flat minimal
  impedance `solimp="0.0001 0.0001 0.001 0.5 2"`, elliptic cone,
  impratio = 1/(c·Δt·A_t) with A_t = 1/m + r_max²/I, one small sphere per
  2D contact point.
)md";
  return out;
}

// 1. The built-in scenes as shipped, and compare's diagnosis of them.
std::string shipped_section(const ReadmeData& d) {
  std::string out = R"md(
## 1. The built-in scenes as shipped

The scene files use compression-only damping (the damper acts only while a
point moves into the ground). MuJoCo cannot have it (its damper works both
ways, clamped at zero: the Kelvin–Voigt law), so no mapping can match these
runs closely; section 2 removes that difference.

)md";
  out += mapping_table(d.shipped);
  out += "\nSmallest maximum position error per scene:\n\n";
  out += winners(d.shipped, d);
  out += R"md(
### Who is right, and why they differ (`contact2d compare`)

`contact2d compare validation/scenes/SCENE.toml` (calibrated mapping, and
with `--set contact.damping=kelvin_voigt`) measures both engines against the
converged solution — the scene's equations solved by adaptive
Dormand–Prince 5(4) with every contact switch located, at tol = )md" +
         sci(d.converged_tol) + R"md( —
and diagnoses their difference: both engines are re-run with one suspected
cause removed at a time, and a cause is named when that takes away at least
)md" + format_text("%.0f %%", 100.0 * d.named_share) +
         R"md( of the ref ↔ MuJoCo distance (maximum position distances; the
amplification is how many times the scene magnifies a 1e-8 m change of the
initial height).

)md";
  out += three_way_table(d.three_way, d.named_share);
  out += R"md(
Each engine's body on the shipped scene, in real time (`contact2d compare
SCENE --video SCENE.gif`): the reference filled (orange), MuJoCo outlined
(blue), the converged solution as a thin line.
)md";
  out += animations(d.three_way, d.animation_note);
  return out;
}

// 2. The built-in scenes with MuJoCo's damping law.
std::string kelvin_voigt_section(const ReadmeData& d) {
  std::string out = R"md(
## 2. The built-in scenes with the Kelvin–Voigt law

Same scenes, `--set contact.damping=kelvin_voigt`: the law MuJoCo's soft
contact has. What remains is the mapping, friction and contact geometry.

)md";
  out += mapping_table(d.kelvin_voigt, d.kelvin_voigt_v3);
  if (!d.kelvin_voigt_v3.empty())
    out += "\nThe last column is MuJoCo 3.14 on the same case (`--engine mujoco3`).\n";
  out += "\nSmallest maximum position error per scene:\n\n";
  out += winners(d.kelvin_voigt, d);
  out += R"md(
The generator's default mapping is `calibrated`.
)md";
  return out;
}

// 3. The agreement goal, case by case.
std::string goal_section(const ReadmeData& d) {
  std::string out = R"md(
## 3. The agreement goal (calibrated, Δt = 1e-4, Kelvin–Voigt, c ≥ 200)

The built-in scenes with `--dt 1e-4 --set contact.damping=kelvin_voigt
--set contact.c=…`; "frictionless" also sets μ = μ_roll = 0. Goals: 1e-5 m
and 1e-4 rad without friction; with friction 1e-3 m (point mass, circle)
and 3e-3 m (box, T).

)md";
  out += goal_table(d.goals);
  out += R"md(
Without friction the goal holds. With friction it holds where the body
barely slides while loaded; see section 7 for why MuJoCo's friction cannot
follow the reference's closer.
)md";
  return out;
}

// 4. Corner spheres against box geoms.
std::string geometry_section(const ReadmeData& d) {
  std::string out = R"md(
## 4. Contact geometry of the box and the T

`--geometry corners` (default): a sphere of radius 1e-9 m at every 2D
contact point, one MuJoCo contact each. `--geometry boxes`: one box geom per
part; a 2D corner is a 3D edge, and MuJoCo's box–plane test returns both of
its end vertices, so the generator halves k and c per contact (n = 2).
Calibrated, Kelvin–Voigt, c = 200, Δt = 1e-4.

)md";
  out += geometry_table(d.geometry);
  out += R"md(
Both represent the 2D model's contacts; the corner spheres reproduce it one
contact per point (the T's inner vertices included) and measured closer
without friction, so they are the default.
)md";
  return out;
}

// 5. Each reference integrator against its MuJoCo counterpart.
std::string integrator_section(const ReadmeData& d) {
  std::string out = R"md(
## 5. Integrators (calibrated, Kelvin–Voigt, c = 200, Δt = 1e-4, frictionless)

The reference's semi-implicit Euler and RK4 run against MuJoCo's `Euler`
and `RK4`; the reference's implicit Euler against MuJoCo's `implicit`.
Explicit Euler has no MuJoCo 2.2 counterpart (`compare` refuses it).

)md";
  out += integrator_table(d.integrators);
  out += R"md(
MuJoCo's `implicit` integrates joint damping and actuator forces
implicitly, not contact forces, so for these models it is semi-implicit
Euler, and it differs from the reference's fully implicit Euler by the
methods' own O(Δt) difference.
)md";
  return out;
}

// 6. The random scenes, by damping ratio.
std::string random_section(const ReadmeData& d) {
  std::string out = R"md(
## 6. Scenes the mapping was not built on

)md";
  const RandomConfig& rc = d.random_config;
  out += capitalised(count_words(rc.count)) +
         " scenes drawn by `contact2d report`\n(SplitMix64, seed " + std::to_string(rc.seed) +
         R"md(): the four shapes in turn with
m in [0.1, 10] kg, k in [1e3, 3e5] N/m, the damping ratio
ζ = c/(2√(k·m)) log-uniform in [0.1, 5] (m the total mass; c printed),
μ in [0.1, 1], random sizes (T: one to three random parts), heights, tilts,
spins and sideways velocities; Kelvin–Voigt, Δt = 1e-4, 1.5 s, calibrated
mapping, each run without friction (μ = 0) and with it.

)md";
  out += random_table(d.random);
  const std::vector<ZetaBand> bands = random_bands(d.random, rc);
  out += "\nBy damping ratio (goal without friction: " + sci(rc.pos_goal) + " m and " +
         sci(rc.angle_goal) + " rad):\n\n";
  out += band_table(d);
  out += "\nWithout friction, " + std::to_string(random_reached(d.random, rc)) + " of " +
         std::to_string(d.random.size()) + " scenes are within " + sci(rc.pos_goal) + " m and " +
         sci(rc.angle_goal) + " rad under calibrated: " + band_headline(bands) + ".\n";
  if (!d.random_compensated.empty()) {
    const std::vector<ZetaBand> compensated = random_bands(d.random_compensated, rc);
    out += "Under compensated, " + std::to_string(random_reached(d.random_compensated, rc)) +
           " of " + std::to_string(d.random_compensated.size()) + ": " +
           band_headline(compensated) + ".\n";
  }
  out += random_versions_text(d);
  out += R"md(
Why the bands differ: the calibrated force differs from Kelvin–Voigt by a
relative O(d·A/Â) (section 7, impedance d = 1e-4), a slightly different
restitution at every impact. A body that lands and settles (ζ ≥ 1) keeps
that difference small. An underdamped one bounces: each bounce carries the
difference into a longer flight, and arriving a little earlier or later
moves where inside a time step the next contact begins, which changes the
discrete restitution, so the difference grows bounce by bounce as ζ falls
(`tests/mujoco/test_agreement.cpp` measures it for every body at ζ = 0.1,
0.3, 1 and 5 and derives a bound for it).

The compensated mapping (`--mapping compensated`, docs/mujoco.md) scales
solref by MuJoCo's own divisor d/m + (1 − d)·Â and raises Â by placing the
contact geoms on a massless body at a lever, so that term falls by 10⁶
(docs/mujoco.md derives it and traces what remains without friction to
rounding amplified by the scene). With friction both mappings keep MuJoCo's elliptic cone, whose
damper pushes a sliding body up (section 7).
)md";
  return out;
}

// 7. The remaining differences, cause by cause.
std::string differences_section() {
  std::string out = R"md(
## 7. The remaining differences, explained

**Damping law.** The scene files damp only while the point moves into the
ground; MuJoCo's damper acts both ways and its force is clamped at zero
(Kelvin–Voigt). On the built-in scenes this is the largest single
difference (section 1 against section 2), and no solver setting removes
it.

**Impedance.** MuJoCo's contact force for one contact is
f = (aref − a0)/(A + R) with R = (1 − d)/d·Â, aref = −B·v − K·d·pos: with its
default impedance d ≈ 0.9–0.95 the unconstrained acceleration a0 (gravity)
enters with weight d, so at rest k·p = (1 − d)·m·g and the body sits at
5–10 % of the reference's penetration (`seed`, `exact`, without friction;
MuJoCo's pyramidal cone stiffens a contact with friction further). With d at
MuJoCo's minimum 1e-4 and solref = (−k·Â, −c·Â) the force is
k·p − c·v to a relative 1e-4 (the static penetration is (1 − 1e-4)·m·g/k,
asserted in `tests/mujoco/test_contact_laws.cpp`); what is left is the
O(d·A/Â) term, largest in impacts on a corner far from the COM.

**Effective mass.** MuJoCo scales solref by its own inverse-mass estimate
Â (`body_invweight0`, 2/(3m) for slide-x, slide-z and a hinge at the COM:
the mean of 1/m, 0, 1/m). Reading it from the compiled model, instead of
the true contact inverse mass 1/m + r²/I, is what makes the contact law
independent of where on the body the contact is.

**Friction.** MuJoCo's elliptic cone gives a viscous friction
f_t = −impratio·c·v_t capped at μ·f_n; on the cone (sliding) its normal
force becomes (k·p − c·v_n + μ·c·|v_t|)/(1 + μ²/impratio): the damper's slip
term pushes the body up, so a body landing or sliding hops off the ground,
and the normal (and so the friction) impulse of a sliding impact differs.
No solver setting removes the push (B is shared by all rows of a contact).
impratio = 1/(c·Δt·A_t) is the largest value at which MuJoCo's explicit
friction does not reverse a slip within one step (larger values chatter at
rest; smaller ones weaken the normal force through the divisor). The
reference's tanh slope μ·F_n·α only shapes speeds below 1/α.

**Rolling.** Sliding, torsional and rolling friction share one ellipsoid,
|f_t/μ|² + |τ_roll/μ_roll|² ≤ f_n², so while rolling resistance is at its
limit the tangential friction that would keep the disc rolling is not
available and it slips forward; the rolling rows' damping also pushes the
normal force up (μ_roll·c·|ω|), so the disc rides on the surface. And MuJoCo
places a contact midway between the surfaces, p/2 above the 2D contact
point, so the disc rolls on R − p/2. The rolling circle therefore travels
a little farther than v0²/(2·μ_roll·g/(1.5R)) (asserted within 2.5 % in
`tests/mujoco/test_contact_laws.cpp`).

**3D contact geometry.** See section 4: a 3D box geom turns a 2D corner
into two contacts; the corner spheres keep one per 2D point. Their radius
(1e-9 m) moves every corner contact 1e-9 m lower than the 2D corner.

**Cost.** The reference's step is a few dozen floating-point operations per
contact; `mj_step` runs collision detection, builds the constraint Jacobian
and solves the constraint problem every step (RK4 four times).
)md";
  return out;
}

// 8. The plots, and the goal replay when it ran.
std::string plots_section(const ReadmeData& d) {
  std::string out = R"md(
## 8. Plots

x, y, θ of both engines and the errors over time (calibrated): the built-in
scene as shipped (left) and with the Kelvin–Voigt law (right).

)md";
  out += plots(d.scenes, d.law_independent);
  out += "\n";
  if (d.replay.ran) out += replay_section(d.replay);
  return out;
}

}  // namespace

std::string readme_page(const ReadmeData& d) {
  std::string out = readme_intro(d);
  out += how_to_read_section();
  out += shipped_section(d);
  out += kelvin_voigt_section(d);
  out += goal_section(d);
  out += geometry_section(d);
  out += integrator_section(d);
  out += random_section(d);
  out += differences_section();
  out += plots_section(d);
  return out;
}

}  // namespace contact2d::report
