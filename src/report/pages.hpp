// The pages of validation/report/: Markdown text from the report's result
// structs (report/results.hpp). Every number a page states is computed from
// those structs (report/numbers.hpp); nothing here runs an engine, so the
// pages are tested on hand-written results (tests/report).
#pragma once

#include <string>

#include "analysis/atlas.hpp"
#include "analysis/closed_forms.hpp"
#include "analysis/friction_table.hpp"
#include "analysis/real_impacts.hpp"
#include "analysis/version_table.hpp"
#include "report/results.hpp"

namespace contact2d::report {

std::string readme_page(const ReadmeData& data);  // README.md
std::string sweep_page(const SweepData& data);    // sweep.md
std::string stability_page(const StabilityData& data,
                           const Bench& bench);     // stability.md (bench: the cost ratio)
std::string extreme_page(const ExtremeData& data);  // extreme.md
std::string closed_forms_page(const analysis::ClosedFormTable& table);  // closed_forms.md
// friction.md: MuJoCo with friction, both mappings, the push's share; goal
// in m (the 1e-3).
std::string friction_page(const std::vector<analysis::FrictionRow>& rows, double goal);

// versions.md: MuJoCo 3.14 beside 2.2.2 (its not_run says why when it did
// not run here).
std::string versions_page(const analysis::VersionTable& table);

// real_impacts.md: the fit against recorded impacts (analysis/real_impacts.hpp)
// and its pictures, or why it did not run.
struct RealImpactsData {
  std::string recording;  // the manifest's path
  analysis::ImpactFit fit;
  std::string not_run;                // why there is no fit (empty when there is one)
  std::vector<std::string> pictures;  // file names, beside the page
};
std::string real_impacts_page(const RealImpactsData& data);

// atlas.md: the default atlas (validation/atlas/default.toml), its summary
// and how it ran (src/report/atlas_page.cpp).
struct AtlasRunInfo {
  std::string spec;  // the spec's path
  long long points = 0;
  unsigned threads = 0;
  double wall_seconds = 0.0, cpu_per_point = 0.0, points_per_core = 0.0;
};
std::string atlas_page(const analysis::AtlasSummary& summary, const AtlasRunInfo& info);

// The atlas summary's Markdown, the body of atlas.md and of `contact2d atlas
// merge`'s summary.md (src/report/atlas_page.cpp): counts, the fraction of
// points meeting the goals per group, the converged solution's own error
// against what it measures, the worst points and the heat maps (as images at
// image_dir + file name).
std::string atlas_summary_markdown(const analysis::AtlasSummary& summary,
                                   const std::string& image_dir = "");

}  // namespace contact2d::report
