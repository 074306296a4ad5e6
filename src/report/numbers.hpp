// The numbers the report's prose states, computed from result structs:
// number formatting ("%.3g"), the winning mapping per scene and overall, the
// geometric mean, ranges ("50–80×"), goal verdicts and counts. Pure
// functions over plain data, unit-tested against hand-computed values.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "report/results.hpp"

namespace contact2d::report {

// "%.*g" of x ("–" when x is not finite).
std::string format_significant(double x, int digits = 3);
// x in scientific notation as people write it ("1e-5", "3e-3", "2.5e-4"; not
// "1e-05" or "0.001"): goals stated on the pages. Three digits at most.
std::string sci(double x);
// "%.*f" of x.
std::string fixed(double x, int decimals);
// English words for 0…99 ("twenty-four"); digits beyond that.
std::string count_words(int n);
// A string with its first letter upper-case (ASCII).
std::string capitalised(std::string text);

// Two MuJoCo versions' runs of one case that part by at most this (m) are
// one run up to rounding (versions.md measures ≤ 1e-10 m on every built-in
// scene); farther apart, the front page shows MuJoCo 3.14 beside 2.2.2.
inline constexpr double kVersionsRounding = 1e-9;
// Whether `apart` (m, 2.2.2 ↔ 3.14) is more than rounding; NaN (not run): no.
inline bool versions_differ(double apart) { return apart > kVersionsRounding; }
// "same as 2.2.2 to 1.3e-13 m" (or "to the bit" at 0) within rounding,
// else "2.2.2 ↔ 3.14: X m"; "–" for NaN.
std::string versions_apart_text(double apart);

// "1.2× smaller than" … : `ratio`× followed by `than`, or, when the ratio
// prints as 1 (below 1.005), "level with" instead: how many times the
// winner's error is below the next best's, said properly either way.
std::string ratio_phrase(double ratio, const std::string& comparative, const std::string& what);

// Geometric mean exp(Σ log xᵢ / n); NaN for an empty list or a value ≤ 0.
double geometric_mean(const std::vector<double>& values);

struct Range {
  double lo = 0.0;
  double hi = 0.0;
};
// Smallest and largest of the finite values; none when there is none.
std::optional<Range> range_of(const std::vector<double>& values);
// "lo–hi" with each end formatted by `format`, or one value when both ends
// format the same.
std::string range_text(const Range& range, std::string (*format)(double));

// The mapping with the smallest maximum position error of one scene, and
// how many times smaller it is than the next best (ties: the first listed).
struct SceneWinner {
  std::string scene, mapping;
  double error = 0.0;
  double ratio_to_next = 0.0;
};
std::vector<SceneWinner> scene_winners(const std::vector<MappingCase>& cases,
                                       const std::vector<std::string>& scenes,
                                       const std::vector<std::string>& mappings);

// Each mapping's geometric mean of the maximum position error over the
// scenes, in mapping order.
struct MappingMean {
  std::string mapping;
  double mean = 0.0;
};
std::vector<MappingMean> mapping_means(const std::vector<MappingCase>& cases,
                                       const std::vector<std::string>& scenes,
                                       const std::vector<std::string>& mappings);

// The mapping with the smallest geometric mean and its ratio to the next
// best. The ratio is that of the means as the page prints them (3 digits),
// so a reader can check it from the page.
struct OverallWinner {
  std::string mapping;
  double ratio_to_next = 0.0;
};
OverallWinner overall_winner(const std::vector<MappingMean>& means);

// The agreement goal: the position goal, and the angle goal when there is one.
bool goal_reached(double max_pos, double max_angle, double pos_goal,
                  std::optional<double> angle_goal);

// Random scenes within the frictionless goal.
int random_reached(const std::vector<RandomCase>& cases, const RandomConfig& config);

// A random scene's damping ratio ζ = c/(2√(k·m)), m its total mass (the ζ
// report/random_scenes.hpp draws).
double random_zeta(const RandomCase& c);

// The random scenes with lo ≤ ζ < hi: how many, how many within the
// frictionless goal, the median and largest frictionless position error,
// the largest angle error and the largest position error with friction
// (maxima and median over the finite values; NaN when there is none).
struct ZetaBand {
  double lo = 0.0, hi = 0.0;  // hi = +inf for the last band
  int count = 0, reached = 0;
  double median_pos = 0.0, max_pos = 0.0, max_angle = 0.0, max_pos_friction = 0.0;
};
// The median of the finite values (NaN when there is none).
double median_of(std::vector<double> values);

// All random scenes with friction: the medians of the difference and of its
// three parts (RandomCase), the largest rest, and how many scenes are within
// `goal` as they are and with the reference under MuJoCo's law.
struct FrictionSummary {
  int count = 0, within = 0, rest_within = 0;
  double median_total = 0.0, median_shape = 0.0, median_push = 0.0, median_rest = 0.0;
  double max_rest = 0.0;
};
FrictionSummary friction_summary(const std::vector<RandomCase>& cases, double goal);

// The bands ζ < 0.3, 0.3 ≤ ζ < 1 and ζ ≥ 1, in that order.
std::vector<ZetaBand> random_bands(const std::vector<RandomCase>& cases,
                                   const RandomConfig& config);

// Per-step cost in µs of `seconds` of stepping over duration/dt steps.
double micros_per_step(double seconds, double duration, double dt);

// The range of mj_step / reference step (CPU time) over the bench rows of
// the given integrators; none without MuJoCo rows.
std::optional<Range> bench_ratio_range(const Bench& bench,
                                       const std::vector<std::string>& integrators);

// "51–81×": the cost of an mj_step over a reference step (CPU time, as the
// bench table prints the ratio) for the integrators MuJoCo runs in the
// sweeps, Euler and RK4; none when the bench did not run MuJoCo.
std::optional<std::string> mujoco_cost_ratio(const Bench& bench);

// The observed orders of the reference against the converged reference in
// one sweep, for the given integrators (rows without an order are skipped).
std::vector<double> observed_orders(const SceneSweep& sweep,
                                    const std::vector<std::string>& integrators);

// Measured ω·Δt of the bracketed rows of an integrator over maps.
std::vector<double> bracketed_omega_dt(const std::vector<StabilityMap>& maps,
                                       const std::string& engine, const std::string& integrator);

}  // namespace contact2d::report
