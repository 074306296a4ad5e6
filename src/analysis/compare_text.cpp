// compare's text (analysis/compare_run.hpp): the table of distances, the
// energies, the versions and the diagnosis, wrapped for a terminal.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/compare_run.hpp"
#include "core/format.hpp"
#include "engines/engines.hpp"
#include "io/table.hpp"

namespace contact2d::analysis {
namespace {

// Words wrapped at `width` columns after an indent.
std::string wrapped(const std::string& text, const std::string& indent, size_t width = 78) {
  std::string out, line = indent;
  std::istringstream words(text);
  std::string word;
  size_t length = indent.size();  // in characters (UTF-8 sequences count as one)
  auto chars = [](const std::string& w) {
    size_t n = 0;
    for (unsigned char ch : w) n += (ch & 0xC0) != 0x80;
    return n;
  };
  while (words >> word) {
    if (length > indent.size() && length + 1 + chars(word) > width) {
      out += line + "\n";
      line = indent;
      length = indent.size();
    }
    if (length > indent.size()) {
      line += " ";
      ++length;
    }
    line += word;
    length += chars(word);
  }
  return out + line + "\n";
}

}  // namespace

std::string run_options_text(const ComparedRun& r, bool name_first) {
  const engines::EngineInfo* info = engines::find_engine(r.spec.kind);
  std::string out;
  for (const engines::EngineOption& option : info->options) {
    const std::string value = engines::option_value(r.spec, option.name);
    if (!name_first) return value + " " + std::string(option.name);
    out += (out.empty() ? "" : ", ") + std::string(option.name) + " " + value;
  }
  return out;
}

namespace {

// "ref vs MuJoCo, semi_implicit_euler (MuJoCo Euler), mapping calibrated,
// geometry corners"; with more than one engine after the first, each one's
// integrator and options after its label.
std::string engines_text(const Comparison& c) {
  std::string who = c.runs[0].label + " vs ", what;
  for (size_t i = 1; i < c.runs.size(); ++i) {
    const ComparedRun& r = c.runs[i];
    who += (i > 1 ? " and " : "") + r.label;
    std::string one = engines::integrator_label(r.spec.kind, c.scene.sim.integrator);
    if (const std::string options = run_options_text(r, true); !options.empty())
      one += ", " + options;
    what += (i > 1 ? "; " : "") + (c.runs.size() > 2 ? r.label + ": " : "") + one;
  }
  return who + ", " + what;
}

// The diagnosis: its summary, each named cause with its fix, what was
// ruled out and what was not re-run.
void diagnosis_text(std::ostringstream& out, const Comparison& c) {
  const Diagnosis& d = c.diagnosis;
  if (!d.damper_notes.empty()) out << "\nFriction damper:\n";
  for (const std::string& note : d.damper_notes) out << wrapped(note, "  ");
  if (!d.ran) {
    if (!d.summary.empty()) out << "\nDiagnosis:\n" << wrapped(d.summary, "  ");
    return;
  }
  out << "\nDiagnosis"
      << (c.runs.size() > 2 ? " of " + c.runs[0].label + " <-> " + c.runs[c.diagnosed].label : "")
      << " (each cause removed alone, both engines re-run):\n"
      << wrapped(d.summary, "  ");
  int n = 0;
  for (const Finding& finding : d.findings) {
    if (!finding.named) continue;
    out << "\n"
        << wrapped(std::to_string(++n) + ". " + finding.cause + ": " + finding.explanation, "  ");
    if (!finding.fix.empty()) out << "     fix: " << finding.fix << "\n";
  }
  std::string ruled_out;
  for (const Finding& finding : d.findings) {
    if (finding.named) continue;
    ruled_out += (ruled_out.empty() ? "" : "; ") + finding.cause + " (" +
                 (std::isfinite(finding.share)
                      ? format_text("%.0f %%", std::round(100.0 * finding.share) + 0.0) + ", " +
                            format_number(finding.after, 3) +
                            (finding.cause == "dt_dependent_model" ? " m with the model held"
                                                                   : " m without it")
                      : std::string("not measured")) +
                 ")";
  }
  if (!ruled_out.empty())
    out << "\n" << wrapped("Measured and ruled out: " + ruled_out + ".", "  ");
  if (!d.not_rerun.empty()) {
    std::string causes;
    for (const std::string& cause : d.not_rerun) causes += (causes.empty() ? "" : ", ") + cause;
    out << "\n" << wrapped("Not re-run: " + causes + ". " + d.not_rerun_why, "  ");
  }
}

}  // namespace

std::string comparison_text(const Comparison& c) {
  std::ostringstream out;
  const ConvergedSolution& conv = c.converged;
  out << shape_name(c.scene.shape) << ": " << engines_text(c) << ", "
      << std::string(damping_law_title(c.scene.contact.damping))
      << " damping, dt = " << format_number(c.scene.sim.dt, 4) << " s, "
      << c.runs[1].vs_first.samples << " samples over " << format_number(c.scene.sim.duration, 4)
      << " s\n";
  if (c.scene.contact.friction != FrictionLaw::Tanh) {
    // A cone law is a conformance law, not physics; it matches MuJoCo only
    // at MuJoCo's own impratio: that of the first engine whose model has one.
    size_t with = 1;
    while (with + 1 < c.runs.size() && !std::isfinite(c.runs[with].run.impratio)) ++with;
    const double impratio = c.runs[with].run.impratio;
    std::string note = "friction law: " + std::string(friction_law_name(c.scene.contact.friction)) +
                       " (MuJoCo's cone, not physics), cone ratio " +
                       format_shortest(c.scene.contact.cone_ratio, 6);
    if (std::isfinite(impratio) && impratio != c.scene.contact.cone_ratio)
      note += "; " + c.runs[with].label + "'s model has impratio " + format_shortest(impratio, 6) +
              ": --set contact.cone_ratio=" + format_shortest(impratio, 6) +
              " to compare like with like";
    out << wrapped(note, "") << "\n";
  }
  if (conv.available) {
    out << "converged solution: Dormand-Prince 5(4) with every contact switch located, tol "
        << format_shortest(conv.tol) << " (its own error <= " << format_number(conv.own_error, 2)
        << " m: the distance to tol " << format_shortest(10 * conv.tol)
        << ");\nthe scene magnifies a 1e-8 m change of the initial height "
        << format_number(conv.amplification, 3) << "-fold\n\n";
  } else {
    std::string pairs;
    for (size_t i = 1; i < c.runs.size(); ++i)
      pairs += (i > 1 ? ", " : "") + c.runs[0].label + " <-> " + c.runs[i].label;
    out << wrapped("converged solution: not available (" + conv.why_not + "); only " + pairs + " " +
                       (c.runs.size() > 2 ? "are" : "is") + " measured.",
                   "")
        << "\n";
  }
  Table t;
  t.columns = {"", c.runs[0].label + " <-> converged"};
  for (size_t i = 1; i < c.runs.size(); ++i) {
    t.columns.push_back(c.runs[i].label + " <-> converged");
    t.columns.push_back(c.runs[0].label + " <-> " + c.runs[i].label);
  }
  auto row = [&](const std::string& name, auto field) {
    auto converged = [&](const ComparedRun& r) {
      return conv.available ? format_number(field(r.vs_converged), 4) : std::string("-");
    };
    std::vector<std::string> cells{name, converged(c.runs[0])};
    for (size_t i = 1; i < c.runs.size(); ++i) {
      cells.push_back(converged(c.runs[i]));
      cells.push_back(format_number(field(c.runs[i].vs_first), 4));
    }
    add_row(t, cells);
  };
  using E = TrajectoryError;
  row("max position (m)", [](const E& e) { return e.max_pos; });
  row("RMS position (m)", [](const E& e) { return e.rms_pos; });
  row("end position (m)", [](const E& e) { return e.end_pos; });
  row("max angle (rad)", [](const E& e) { return e.max_angle; });
  row("end angle (rad)", [](const E& e) { return e.end_angle; });
  row("max velocity (m/s)", [](const E& e) { return e.max_vel; });
  row("max omega (rad/s)", [](const E& e) { return e.max_omega; });
  row("time of max position (s)", [](const E& e) { return e.time_of_max_pos; });
  out << to_text(t) << "\n";
  size_t width = 6;  // "energy ref     ": the labels in one column
  for (const ComparedRun& r : c.runs) width = std::max(width, r.label.size());
  for (const ComparedRun& r : c.runs) {
    const Energies en = energies(c.scene, r.run.trajectory);
    out << "energy " << r.label << std::string(width + 2 - r.label.size(), ' ')
        << format_number(en.initial, 4) << " -> " << format_number(en.final, 4) << " J\n";
  }
  out << "wall clock" << std::string(width - 1, ' ');
  for (size_t i = 0; i < c.runs.size(); ++i)
    out << (i ? ", " : "") << c.runs[i].label << " " << format_number(c.runs[i].run.seconds, 4)
        << " s";
  if (conv.available) out << ", converged " << format_number(conv.seconds, 4) << " s";
  out << "\n";
  const std::vector<std::string> versions = version_notes(c);
  if (!versions.empty()) out << "\nVersions:\n";
  for (const std::string& note : versions) out << wrapped(note, "  ");
  diagnosis_text(out, c);
  return out.str();
}

}  // namespace contact2d::analysis
