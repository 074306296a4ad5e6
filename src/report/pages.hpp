// The pages of validation/report/: Markdown text from the report's result
// structs (report/results.hpp). Every number a page states is computed from
// those structs (report/numbers.hpp); nothing here runs an engine, so the
// pages are tested on hand-written results (tests/report).
#pragma once

#include <string>

#include "analysis/closed_forms.hpp"
#include "report/results.hpp"

namespace contact2d::report {

std::string readme_page(const ReadmeData& data);  // README.md
std::string sweep_page(const SweepData& data);    // sweep.md
std::string stability_page(const StabilityData& data,
                           const Bench& bench);     // stability.md (bench: the cost ratio)
std::string extreme_page(const ExtremeData& data);  // extreme.md
std::string closed_forms_page(const analysis::ClosedFormTable& table);  // closed_forms.md

}  // namespace contact2d::report
