// Golden tests of the report's pages: hand-written result structs
// (fixtures.hpp) through the page writers, compared with the Markdown checked
// in under tests/report/golden/, wall-clock fields masked. A page that
// changes fails here; when the change is meant, regenerate the golden files
// with CONTACT2D_UPDATE_GOLDEN=1 and review their diff.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <limits>
#include <regex>
#include <sstream>

#include "fixtures.hpp"
#include "report/pages.hpp"

namespace contact2d::report {
namespace {

// Wall-clock fields: the per-step columns of README.md and sweep.md's
// "ms at 1e-4", "N ms" anywhere, the run's load and duration, and the bench
// block of sweep.md. The choices made from times (the cheapest run per
// accuracy) stay: on fixed structs they are fixed.
std::string mask_timing(const std::string& page) {
  std::string out;
  std::istringstream in(page);
  std::vector<bool> timing;  // per column of the current table
  bool in_bench = false;
  for (std::string line; std::getline(in, line);) {
    if (line == "```") in_bench = !in_bench;
    if (in_bench && line != "```") {
      out += "BENCH\n";
      continue;
    }
    if (line.rfind("|", 0) == 0) {
      std::vector<std::string> cells;
      size_t start = 2;
      for (size_t at; (at = line.find(" | ", start)) != std::string::npos; start = at + 3)
        cells.push_back(line.substr(start, at - start));
      cells.push_back(line.substr(start, line.size() - start - 2));
      if (timing.empty()) {
        for (const std::string& c : cells) {
          timing.push_back(c.find("µs/step") != std::string::npos ||
                           c.find("ms at 1e-4") != std::string::npos);
        }
      } else if (line.rfind("|---", 0) != 0) {
        line = "|";
        for (size_t i = 0; i < cells.size(); ++i)
          line += " " + (i < timing.size() && timing[i] ? std::string("T") : cells[i]) + " |";
      }
    } else {
      timing.clear();
    }
    out += line + "\n";
  }
  out = std::regex_replace(out, std::regex(R"([0-9.e+-]+ ms\b)"), "T ms");
  out = std::regex_replace(out, std::regex(R"(this run: [^)]*\))"), "this run: RUNINFO)");
  out = std::regex_replace(out, std::regex(R"(took \d+ s\n\(sweeps \d+ s, stability maps \d+ s\))"),
                           "took T s\n(sweeps T s, stability maps T s)");
  return out;
}

void expect_golden(const std::string& name, const std::string& page) {
  const std::string path = std::string(CONTACT2D_REPORT_GOLDEN_DIR) + "/" + name;
  const std::string masked = mask_timing(page);
  if (std::getenv("CONTACT2D_UPDATE_GOLDEN")) {
    std::ofstream(path) << masked;
    GTEST_SKIP() << "wrote " << path;
  }
  std::ifstream in(path);
  ASSERT_TRUE(in) << path << " is missing (CONTACT2D_UPDATE_GOLDEN=1 writes it)";
  // The first line that differs, not two whole pages.
  std::istringstream want(std::string(std::istreambuf_iterator<char>(in), {}));
  std::istringstream got(masked);
  std::string a, b;
  for (int line = 1;; ++line) {
    const bool more_a = static_cast<bool>(std::getline(want, a));
    const bool more_b = static_cast<bool>(std::getline(got, b));
    if (!more_a && !more_b) return;
    if (more_a != more_b || a != b) {
      ADD_FAILURE() << name << " changed at line " << line
                    << ":\n  golden: " << (more_a ? a : "(end)")
                    << "\n  page:   " << (more_b ? b : "(end)");
      return;
    }
  }
}

TEST(ReportPages, ReadmeMatchesGolden) {
  expect_golden("README.md", readme_page(fixtures::readme()));
}

// The first screen's friction lines from the fixture's hand-set parts
// (fixtures.hpp): the random scenes' medians and the built-in box's parts.
TEST(ReportPages, ReadmeTakesTheFrictionDifferenceApart) {
  const std::string page = readme_page(fixtures::readme());
  EXPECT_NE(page.find("| calibrated | 2.2.2 | 0.006 | 1 of 4 | 2.1e-05 | 0.006 | 2e-09 (largest "
                      "2e-06) | 4 of 4 |"),
            std::string::npos);
  EXPECT_NE(page.find("they are at most 9e-10 m apart"), std::string::npos);
  EXPECT_NE(page.find("moves a body by up to 3e-05 m and its push"), std::string::npos);
  EXPECT_NE(page.find("lifting a sliding body) by up to 0.0041 m"), std::string::npos);
}

TEST(ReportPages, SweepMatchesGolden) { expect_golden("sweep.md", sweep_page(fixtures::sweep())); }

TEST(ReportPages, StabilityMatchesGolden) {
  expect_golden("stability.md", stability_page(fixtures::stability(), fixtures::sweep().bench));
}

TEST(ReportPages, ExtremeMatchesGolden) {
  expect_golden("extreme.md", extreme_page(fixtures::extreme()));
}

// The mask hides wall clock and nothing else: a time changes nothing, an
// error does.
// closed_forms.md from a hand-written table: a row inside every tolerance,
// a MuJoCo-only row, and a row without a converged solution where MuJoCo
// misses (it must be listed under "Where MuJoCo misses").
analysis::ClosedFormTable closed_forms_fixture() {
  analysis::ClosedFormTable t;
  t.reference_engine = "ref semi_implicit_euler";
  t.mujoco_engine = "mujoco calibrated Euler";
  t.seconds = 0.61;
  analysis::ClosedFormRow a;
  a.case_id = "static.point_mass";
  a.case_name = "static penetration, point mass";
  a.quantity.name = "depth at rest (m)";
  a.quantity.formula = "m·g/k";
  a.quantity.closed_form = 9.81e-4;
  a.quantity.tolerance = 9.81e-13;
  a.quantity.converged_tolerance = 1e-9;
  a.quantity.why = "rounding";
  a.quantity.mujoco_bound = 9.82e-8;
  a.quantity.mujoco_bound_derived = true;
  a.quantity.mujoco_why = "d·depth";
  a.converged = 9.81e-4 - 2.8e-15;
  a.reference = 9.81e-4 - 7.7e-15;
  a.mujoco = 9.81e-4 - 9.81e-8;
  analysis::ClosedFormRow own = a;
  own.quantity.name = "MuJoCo's own rest depth (m)";
  own.quantity.formula = "m·g·Â·(1−d)/(N·n·s)";
  own.quantity.closed_form = 9.809019e-4;
  own.quantity.reference_applies = false;
  own.quantity.mujoco_bound = 9.81e-13;
  own.quantity.mujoco_why = "its own law at rest";
  own.converged = own.reference = std::numeric_limits<double>::quiet_NaN();
  own.mujoco = 9.809019e-4;
  analysis::ClosedFormRow slope;
  slope.case_id = "slope.slides";
  slope.case_name = "box on a 30° slope";
  slope.quantity.name = "acceleration (m/s²)";
  slope.quantity.formula = "g·(sinθ − μ·cosθ)";
  slope.quantity.closed_form = 2.356;
  slope.quantity.tolerance = 2.4e-9;
  slope.quantity.why = "rounding";
  slope.quantity.mujoco_bound = 1.2e-2;
  slope.quantity.mujoco_why = "MISS: it rattles";
  slope.reference = 2.356;
  slope.mujoco = 2.350;
  slope.converged_note = "no converged solution: obstacles";
  t.rows = {a, own, slope};
  return t;
}

// friction.md from three hand-written rows: one within the goal under
// compensated, one whose pyramidal run diverged, all three within it once
// the reference runs MuJoCo's law (the rest column).
TEST(ReportPages, FrictionMatchesGolden) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<double> knobs{0.0049, 0.0051, inf, 0.005, 0.005, 0.005, 0.005};
  const std::vector<analysis::FrictionRow> rows = {{"box_slide",
                                                    "box sliding to rest, c = 50",
                                                    {0.005, 0, 0.004},
                                                    {0.005, 0, 0.0045},
                                                    {0.001, 0, 1e-5},
                                                    2.8e-5,
                                                    0.0049,
                                                    3e-11,
                                                    1e-10,
                                                    knobs},
                                                   {"tshape",
                                                    "T landing",
                                                    {0.003, 0.01, 0.001},
                                                    {0.0031, 0.01, 0.001},
                                                    {0.39, 1, 0.2},
                                                    0.0069,
                                                    0.0092,
                                                    2e-8,
                                                    1e-7,
                                                    knobs},
                                                   {"slide_roll",
                                                    "disc sliding into rolling",
                                                    {0.002, 0, 0.001},
                                                    {0.0008, 0, 0.0005},
                                                    {0.0002, 0, 1e-6},
                                                    9e-4,
                                                    0.0008,
                                                    1e-13,
                                                    0,
                                                    std::vector<double>(7, nan)}};
  const std::string page = friction_page(rows, 1e-3);
  // 1 of 3 within 1e-3 m (0.0008 under compensated); 3 of 3 conform, the
  // largest rest 2e-8 m.
  EXPECT_NE(page.find("1 of 3 scenes are within 0.001 m"), std::string::npos);
  EXPECT_NE(page.find("3 of 3 are, the largest 2e-08 m"), std::string::npos);
  // push > shape in box_slide and tshape, not in slide_roll's hand-written row.
  EXPECT_NE(page.find("push is the larger part in 2 of 3 scenes"), std::string::npos);
  EXPECT_NE(page.find("| diverged |"), std::string::npos);
  EXPECT_NE(page.find("| — |"), std::string::npos);
  expect_golden("friction.md", page);
}

// versions.md from hand-written rows: each cause named from its columns,
// the damper column "—" where it does not apply, and the not-run line.
TEST(ReportPages, VersionsMatchesGolden) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  analysis::VersionTable table;
  // scene, mapping, friction, for_v3, tolerance, gap, v2_model, ref_v2, ref_v3, ref_v3_damper
  table.rows = {{"point_mass", "calibrated", true, 1e-13, 0, 1e-13, 0.21, 0.028, 0.028, nan},
                {"box", "compensated", true, 2e-13, 4e-13, 2e-8, 2e-8, 0.017, 0.017, 0.016},
                {"circle", "calibrated", false, 7e-13, 5e-11, 7e-13, 5e-11, 1e-7, 1e-7, nan},
                {"tshape", "calibrated", false, 1e-12, 2e-12, 1e-12, 2e-12, 2e-4, 2e-4, nan}};
  const std::string page = versions_page(table);
  EXPECT_NE(page.find("| point_mass | calibrated | 1e-13 | 0 | 1e-13 | 0.21 | 3.0's slide-only "
                      "invweight |"),
            std::string::npos)
      << page;
  EXPECT_NE(page.find("| 3.9's margin/gap |"), std::string::npos);
  EXPECT_NE(page.find("| 3.11's early exits |"), std::string::npos);
  EXPECT_NE(page.find("| none |"), std::string::npos);
  EXPECT_NE(page.find("within 1e-12 m on every row"), std::string::npos);
  EXPECT_NE(page.find("Closest with the damper here: box, 0.016 m"), std::string::npos);
  expect_golden("versions.md", page);
  const std::string skipped =
      versions_page({{}, "mujoco3: Node.js (the command node) is not installed"});
  EXPECT_NE(skipped.find("**Not run here**: mujoco3: Node.js"), std::string::npos);
  EXPECT_EQ(skipped.find("## With friction"), std::string::npos);
}

TEST(ReportPages, ClosedFormsMatchesGolden) {
  expect_golden("closed_forms.md", closed_forms_page(closed_forms_fixture()));
}

TEST(ReportPages, MaskHidesTimesOnly) {
  ReadmeData a = fixtures::readme();
  ReadmeData b = a;
  b.shipped[0].result.mujoco_seconds *= 3;
  b.integrators[0].result.ref_seconds *= 3;
  EXPECT_NE(readme_page(a), readme_page(b));
  EXPECT_EQ(mask_timing(readme_page(a)), mask_timing(readme_page(b)));
  b.shipped[0].result.max_vel *= 3;
  EXPECT_NE(mask_timing(readme_page(a)), mask_timing(readme_page(b)));

  SweepData s = fixtures::sweep();
  SweepData t = s;
  t.info.total_seconds += 5;
  t.sweeps[0].study[1].seconds *= 2;
  EXPECT_EQ(mask_timing(sweep_page(s)), mask_timing(sweep_page(t)));
  t.sweeps[0].study[1].max_pos *= 2;
  EXPECT_NE(mask_timing(sweep_page(s)), mask_timing(sweep_page(t)));
}

// Verdicts and counts in the prose follow the structs.
TEST(ReportPages, ReadmeVerdictsAndCounts) {
  const std::string page = readme_page(fixtures::readme());
  EXPECT_NE(page.find("| box, c = 200, friction | 12.5 | 0.004 | 3e-3 | 0.5 | - | **no** |"),
            std::string::npos);
  EXPECT_NE(
      page.find("| box, c = 200, frictionless | 1e-15 | 3e-06 | 1e-5 | 0.0002 | 1e-4 | **no** |"),
      std::string::npos);
  EXPECT_NE(page.find("Without friction, 1 of 4 scenes are within 1e-5 m and 1e-4 rad under "
                      "calibrated: 1 of 2 with ζ < 0.3, 0 of 1 with 0.3 ≤ ζ < 1 and 0 of 1 with "
                      "ζ ≥ 1.\nUnder compensated, 4 of 4: 2 of 2 with ζ < 0.3, 1 of 1 with "
                      "0.3 ≤ ζ < 1 and 1 of 1 with ζ ≥ 1."),
            std::string::npos);
  EXPECT_NE(page.find("| s00 | point_mass | 0.5 | 20000 | 30 | 0.15 | 0.5 |"), std::string::npos);
  EXPECT_NE(page.find("| ζ < 0.3 | calibrated | 2 | 1 | 0.000151 | 0.0003 | 1e-09 | 0.002 |\n"
                      "| ζ < 0.3 | compensated | 2 | 2 | 6.5e-12 | 1e-11 | 1e-14 | 0.001 |"),
            std::string::npos);
  EXPECT_NE(page.find("Four scenes drawn by `contact2d report`\n(SplitMix64, seed 42)"),
            std::string::npos);
  EXPECT_NE(page.find("- point_mass: **calibrated** (0.1 m), 2.5× smaller than the next best"),
            std::string::npos);
  EXPECT_NE(page.find("- box: **exact** (0.02 m), 1.5× smaller"), std::string::npos);
  // Means as printed: calibrated 0.0548, exact 0.0707: 0.0707 / 0.0548 = 1.29.
  EXPECT_NE(page.find("- overall: **calibrated**, its geometric-mean error 1.29× below"),
            std::string::npos);
}

// The first screen makes one recommendation, calibrated (the model to
// build on), whichever mapping measures closest; when compensated does, it
// is named as the tool for comparing, with why it is not a model to build
// on, and never as "Use the `compensated` mapping".
TEST(ReportPages, ReadmeRecommendsOneMappingToBuildOn) {
  const std::string use = "**Use the `calibrated` mapping**";
  const std::string comparing = "| for comparing with the reference | `--mapping compensated`: ";
  const std::string plain = readme_page(fixtures::readme());
  EXPECT_NE(plain.find(use), std::string::npos);
  EXPECT_EQ(plain.find(comparing), std::string::npos);
  ReadmeData d = fixtures::readme();
  d.mappings.push_back("compensated");
  for (const std::string& scene : d.scenes) {  // ten times below every other mapping
    d.kelvin_voigt.push_back({scene, "compensated", fixtures::comparison(1e-4, 1e-4)});
    d.kelvin_voigt_v3.push_back({scene, "compensated", fixtures::comparison(1e-4, 1e-4), 1e-13});
  }
  const std::string page = readme_page(d);
  EXPECT_NE(page.find(use), std::string::npos);
  EXPECT_EQ(page.find("**Use the `compensated` mapping**"), std::string::npos);
  EXPECT_NE(page.find(comparing), std::string::npos);
  EXPECT_NE(page.find("not for a model to build on"), std::string::npos);
  EXPECT_EQ(plain.find("not for a model to build on"), std::string::npos);
}

// The front page answers for both versions (issue 52): its title, the advice
// per version with MuJoCo 3.14's damper figures, 3.14's columns of the
// damping-band and friction tables from its own runs (the fixture's s01
// differs from 2.2.2), and, case by case, 3.14's figure where the versions
// part by more than rounding and "same as 2.2.2 to X m" where they do not.
TEST(ReportPages, ReadmeAnswersForBothVersions) {
  const std::string page = readme_page(fixtures::readme());
  EXPECT_EQ(page.rfind("# contact2d against MuJoCo 2.2.2 and 3.14\n", 0), 0U);
  EXPECT_NE(page.find("| a model to build on | `calibrated` | `calibrated` |"), std::string::npos);
  // Means as printed (Kelvin–Voigt, a tenth of the shipped errors): 2.2.2
  // calibrated 0.00548, exact 0.00707 (1.29×); 3.14's exact √(0.025·0.03) =
  // 0.0274 and seed 0.0316, so 0.0274 / 0.00548 = 5×.
  EXPECT_NE(page.find("| for comparing with the reference | `--mapping calibrated`: 1.29× below "
                      "the next best mapping | `--mapping calibrated`: 5× below the next best "
                      "mapping |"),
            std::string::npos);
  EXPECT_NE(page.find("helps most on point mass sliding to rest: 0.00165 → 7e-08 m; hurts most "
                      "on the built-in tshape with the Kelvin–Voigt law: 0.018 → 0.338 m"),
            std::string::npos);
  EXPECT_NE(page.find("in s01 calibrated (0.01 m); every other scene within 1e-9 m of it."),
            std::string::npos);
  // ζ < 0.3 (s00, s03): 3.14 with friction 0.002 (s03); 0.3 ≤ ζ < 1 (s01): 0.02.
  EXPECT_NE(page.find("| ζ < 0.3 | calibrated | 2 | 1 | 0.000151 / 0.0003 | 0.002 | 1 | "
                      "0.000151 / 0.0003 | 0.002 |"),
            std::string::npos);
  EXPECT_NE(page.find("| 0.3 ≤ ζ < 1 | calibrated | 1 | 0 | 5e-06 / 5e-06 | 0.01 | 0 | "
                      "5e-06 / 5e-06 | 0.02 |"),
            std::string::npos);
  EXPECT_NE(page.find("MuJoCo 3.14 against 2.2.2 on every one of these runs: up to 0.01 m apart"),
            std::string::npos);
  // Friction medians on 3.14: (0.002 + 0.02)/2 = 0.011.
  EXPECT_NE(page.find("| calibrated | 3.14 | 0.011 | 1 of 4 |"), std::string::npos);
  EXPECT_NE(page.find("| box / exact | 0.002 |"), std::string::npos);
  EXPECT_NE(page.find("| 0.03 (2.2.2 ↔ 3.14: 0.01 m) |\n"), std::string::npos);
  EXPECT_NE(page.find("| box / calibrated | 0.003 |"), std::string::npos);
  EXPECT_NE(page.find("| same as 2.2.2 to 2e-13 m |\n"), std::string::npos);
  EXPECT_NE(page.find("point_mass on MuJoCo 3.14: same as 2.2.2 to 2e-13 m"), std::string::npos);
  EXPECT_NE(page.find("| box, c = 200, friction | 12.5 | 0.004 | 3e-3 | 0.5 | - | **no** | 0.005 "
                      "(2.2.2 ↔ 3.14: 0.001 m) |"),
            std::string::npos);
  EXPECT_NE(page.find("On MuJoCo 3.14 (the same commands with `--engine mujoco3`): without "
                      "friction 1 of 2 within 1e-5 m and 1e-4 rad (largest 3e-06 m), with "
                      "friction up to 0.005 m"),
            std::string::npos);
}

// Without MuJoCo 3.14 the page says why and shows 2.2.2 alone.
TEST(ReportPages, ReadmeWithoutMuJoCo3SaysWhy) {
  const std::string page = readme_page(fixtures::readme_without_mujoco3());
  EXPECT_EQ(page.rfind("# contact2d against MuJoCo 2.2.2\n", 0), 0U);
  EXPECT_NE(page.find("MuJoCo 3.14 did not run here (node not found)."), std::string::npos);
  EXPECT_EQ(page.find("| MuJoCo 3.14 |"), std::string::npos);
  EXPECT_EQ(page.find("3.14 with friction"), std::string::npos);
  EXPECT_EQ(page.find("same as 2.2.2"), std::string::npos);
  EXPECT_EQ(page.find("| 3.14 |"), std::string::npos);
}

// A winner level with the next best to three digits is said so, not "1×".
TEST(ReportPages, ReadmeSaysLevelWhenTheRatioPrintsAsOne) {
  ReadmeData d = fixtures::readme();
  for (MappingCase& c : d.shipped) {
    if (c.scene != "box") continue;  // seed 0.2 m, then 0.2001 m: 1.0005×
    if (c.mapping == "exact") c.result.max_pos = 0.2001;
    if (c.mapping == "calibrated") c.result.max_pos = 0.2002;
  }
  const std::string page = readme_page(d);
  EXPECT_NE(page.find("- box: **seed** (0.2 m), level with the next best mapping (within 0.5 %)"),
            std::string::npos);
  EXPECT_EQ(page.find("1× smaller"), std::string::npos);
}

// The front page is an index of every page the report writes (report/plan.cpp:
// page_names()): each linked by its file name.
TEST(ReportPages, ReadmeLinksEveryPage) {
  const std::string page = readme_page(fixtures::readme());
  const size_t index = page.find("## The pages of this report");
  ASSERT_NE(index, std::string::npos);
  EXPECT_LT(index, page.find("## In short"));
  for (const char* name :
       {"sweep.md", "stability.md", "extreme.md", "closed_forms.md", "atlas.md", "friction.md"})
    EXPECT_NE(page.find(std::string("[") + name + "](" + name + ")"), std::string::npos) << name;
}

// Section 6 sets each 100× (semi-implicit) and 30× (implicit) budget of the
// run against the sincos and tanh links of each scene's chain, from the floors of the
// same run: in the fixture one tanh is 41.6 ns and a sincos 26.1 ns; mj_step
// 1000 ns gives the point mass 10 ns (below one tanh) and 2000 ns implicit
// 66.7 ns (below two tanh, 83.2 ns). A scene whose points turn carries a
// sincos too (67.7 ns; twice: 135.4 ns).
TEST(ReportPages, SweepBudgetsAgainstFloors) {
  const std::string page = sweep_page(fixtures::sweep());
  EXPECT_NE(
      page.find("The sincos and tanh chain of a step whose contact slips slower than 22/α is alone "
                "longer than the whole 100× budget of point_mass "
                "(budget 10 ns, tanh 41.6 ns)."),
      std::string::npos);
  EXPECT_NE(page.find("twice the chain is longer than the 30× budget of point_mass (budget 67 ns, "
                      "2 × (tanh) 83.2 ns)."),
            std::string::npos);
  SweepData turning = fixtures::sweep();
  turning.bench.turning = {"point_mass"};
  const std::string turned = sweep_page(turning);
  EXPECT_NE(turned.find("point_mass (budget 10 ns, sincos + tanh 67.7 ns)"), std::string::npos);
  EXPECT_NE(turned.find("point_mass (budget 67 ns, 2 × (sincos + tanh) 135.4 ns)"),
            std::string::npos);
  SweepData untimed = fixtures::sweep();
  untimed.bench.tanh_ns = -1.0;  // floors not timed: no sentence
  EXPECT_EQ(sweep_page(untimed).find("tanh chain"), std::string::npos);
}

TEST(ReportPages, SweepProseNumbers) {
  const std::string page = sweep_page(fixtures::sweep());
  EXPECT_NE(page.find("its step costs 50–80× more"), std::string::npos);
  // The bench table (wall clock, so masked in the golden file) as aligned text.
  EXPECT_NE(
      page.find("scene       integrator           ref cpu  mj cpu  ratio  ref wall  mj wall\n"
                "point_mass  semi_implicit_euler  20.0ns   1000ns  50x    20.5ns    1001ns\n"),
      std::string::npos);
  EXPECT_NE(page.find("circle      semi_implicit_euler  30.0ns   -       -      30.5ns    -\n"),
            std::string::npos);
  EXPECT_NE(page.find("sincos 26.1ns, tanh 41.6ns, a step with no contact points 10.1ns\n```"),
            std::string::npos);
  EXPECT_NE(page.find("(1.00 for the Euler methods, ≈ 4.6 for RK4 between 1e-3\n  and 2e-4 s,"),
            std::string::npos);
  EXPECT_NE(page.find("semi-implicit Euler against MuJoCo Euler 50–50× (CPU time), all "
                      "integrators 10–80× — not met on every scene (section 6)."),
            std::string::npos);
  EXPECT_NE(page.find("floor drops to 0.001 m (its errors at 1e-4 s are 0.001 m)"),
            std::string::npos);
  // ref orders of the bouncing point mass: ± 0.012 and ± 0.14 (the circle's left out)
  EXPECT_NE(page.find("standard errors of ±0.01…0.1 on the slopes"), std::string::npos);
}

TEST(ReportPages, StabilityProseRanges) {
  const std::string page = stability_page(fixtures::stability(), fixtures::sweep().bench);
  // explicit Euler bracketed: 316·0.0016 = 0.506, 3162·0.00017 = 0.538, 700·0.0011 = 0.77
  EXPECT_NE(page.find("fails at ω·Δt ≈ 0.51–0.77 (the table)"), std::string::npos);
  // implicit Euler bracketed: 31623·0.00024 = 7.59 only
  EXPECT_NE(page.find("(≳ 7.6, the table)"), std::string::npos);
  EXPECT_NE(page.find("= 0.83 at ζ = 1,\nRK4 2.79 at ζ = 1"), std::string::npos);
  EXPECT_NE(page.find("own c = 20 N·s/m at every k\n\nHolding c fixed makes ζ = c/(2√(k·m)) "
                      "fall from 0.32 to 0.00032 as k grows."),
            std::string::npos);
}

}  // namespace
}  // namespace contact2d::report

namespace contact2d::report {
namespace {

// Section 9 shows the window's video of the goal when scripts/record-goal
// has made it (ReplayComparison::gif, mp4), and says nothing of it otherwise.
TEST(ReportPages, TheGoalReplaySectionShowsTheRecordedGoal) {
  ReadmeData d = fixtures::readme();
  EXPECT_EQ(readme_page(d).find("goal.gif"), std::string::npos);
  d.replay.gif = "goal.gif";
  d.replay.mp4 = "goal.mp4";
  const std::string page = readme_page(d);
  EXPECT_NE(page.find("![A goal against the keeper](goal.gif)"), std::string::npos);
  EXPECT_NE(page.find("[goal.mp4](goal.mp4)"), std::string::npos);
}

// Section 9 shows what `play` prints as a table, a field a row and an
// engine a column (issue 51 §3: not raw JSON lines); a field one engine
// lacks is "–", an output that is not JSON stays whole.
TEST(ReportPages, TheGoalReplayOutputIsATable) {
  ReadmeData d = fixtures::readme();
  d.replay.engines = {
      {"ref", "goal", R"({"goal":true,"kicks":[{"distance":2.92822625}],"ball":{"x":10.1}})"},
      {"mujoco", "goal", R"({"goal":true,"kicks":[{"distance":2.13383313}]})"}};
  std::string page = readme_page(d);
  EXPECT_NE(page.find("| field | ref | mujoco |"), std::string::npos);
  EXPECT_NE(page.find("| `goal` | true | true |"), std::string::npos);
  EXPECT_NE(page.find("| `kicks[0].distance` | 2.92822625 | 2.13383313 |"), std::string::npos);
  EXPECT_NE(page.find("| `ball.x` | 10.1 | – |"), std::string::npos);
  EXPECT_EQ(page.find("{\"goal\""), std::string::npos);
  d.replay.engines[1].json = "not json";
  page = readme_page(d);
  EXPECT_NE(page.find("| `output` | – | not json |"), std::string::npos);
}

}  // namespace
}  // namespace contact2d::report

namespace contact2d::report {
namespace {

// real_impacts.md from a hand-written fit: every model of both splits in
// one table, the reference against the bound, the parameters with their
// spread, the spin's slope; and one line when the fit did not run.
TEST(ReportPages, RealImpactsShowsEveryModelAndSplit) {
  RealImpactsData d;
  d.recording = "validation/real/ellipse/recording.toml";
  d.fit.impacts.resize(10);
  d.fit.flagged_left_out = 3;
  d.fit.mass = 2.0;
  d.fit.inertia = 0.5;
  for (const char* split : {"seeded", "chronological"}) {
    analysis::SplitFit s;
    s.split = split;
    analysis::ModelFit ref;
    ref.name = "penalty";
    ref.engine = "ref";
    ref.median = std::string(split) == "seeded" ? 0.3701 : 0.3662;
    ref.q1 = 0.25;
    ref.q3 = 0.6;
    ref.parameters = {{"k", 2e7}, {"zeta", 0.23}, {"c", 409}, {"mu", 0.0}, {"mu_roll", 0.003}};
    ref.spread = {{1e7, 3e7}, {0.22, 0.24}, {300, 500}, {0, 0.001}, {0.0029, 0.0031}};
    analysis::ModelFit bound;
    bound.name = "irb_bound";
    bound.engine = "baseline";
    bound.median = 0.442;
    s.models = {ref, bound};
    s.engine_distances = {{"ref", "mujoco", 0.0136}};
    d.fit.splits.push_back(s);
  }
  d.fit.splits.front().spin_slope = 0.35;
  d.fit.splits.front().spin_intercept = 18.0;
  const std::string page = real_impacts_page(d);
  EXPECT_NE(page.find("| penalty | ref |"), std::string::npos) << page;
  EXPECT_NE(page.find("| 0.370 | 0.250–0.600 | 0.366 | 0.250–0.600 |"), std::string::npos) << page;
  EXPECT_NE(page.find("seeded: the reference's median 0.370 is below the best impulse chosen "
                      "after the fact (0.442)"),
            std::string::npos);
  EXPECT_NE(page.find("| seeded | 2e+07 (1e+07–3e+07) | 0.23 (0.22–0.24) |"), std::string::npos)
      << page;
  EXPECT_NE(page.find("ref and mujoco apart per impact (median, same metric): 0.0136"),
            std::string::npos);
  EXPECT_NE(page.find("0.35 × what a point impulse"), std::string::npos);
  EXPECT_NE(page.find("10 recorded impacts"), std::string::npos);
  RealImpactsData none;
  none.not_run = "no recording";
  EXPECT_EQ(real_impacts_page(none), "# Against real impacts\n\nNot run: no recording\n");
}

}  // namespace
}  // namespace contact2d::report
