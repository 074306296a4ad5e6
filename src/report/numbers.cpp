// The report's computed prose numbers (report/numbers.hpp).
#include "report/numbers.hpp"

#include "core/format.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

namespace contact2d::report {
namespace {

double find_error(const std::vector<MappingCase>& cases, const std::string& scene,
                  const std::string& mapping) {
  for (const MappingCase& c : cases) {
    if (c.scene == scene && c.mapping == mapping) return c.result.max_pos;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

std::string format_significant(double x, int digits) {
  if (!std::isfinite(x)) return "–";
  return format_number(x, digits);
}

std::string sci(double x) {
  if (!std::isfinite(x)) return "–";
  const std::string text = format_number("%.2e", x);
  const size_t e = text.find('e');
  std::string mantissa = text.substr(0, e);
  while (mantissa.find('.') != std::string::npos &&
         (mantissa.back() == '0' || mantissa.back() == '.')) {
    mantissa.pop_back();
  }
  const long exponent = std::strtol(text.c_str() + e + 1, nullptr, 10);
  return mantissa + "e" + std::to_string(exponent);
}

std::string fixed(double x, int decimals) {
  if (!std::isfinite(x)) return "–";
  return format_text("%.*f", decimals, x);
}

std::string count_words(int n) {
  static const char* const kOnes[] = {"zero",    "one",     "two",       "three",    "four",
                                      "five",    "six",     "seven",     "eight",    "nine",
                                      "ten",     "eleven",  "twelve",    "thirteen", "fourteen",
                                      "fifteen", "sixteen", "seventeen", "eighteen", "nineteen"};
  static const char* const kTens[] = {"",      "",      "twenty",  "thirty", "forty",
                                      "fifty", "sixty", "seventy", "eighty", "ninety"};
  if (n < 0 || n > 99) return std::to_string(n);
  if (n < 20) return kOnes[n];
  return std::string(kTens[n / 10]) + (n % 10 ? std::string("-") + kOnes[n % 10] : "");
}

std::string capitalised(std::string text) {
  if (!text.empty()) text[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(text[0])));
  return text;
}

double geometric_mean(const std::vector<double>& values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  double log_sum = 0.0;
  for (double v : values) {
    if (!(v > 0.0)) return std::numeric_limits<double>::quiet_NaN();
    log_sum += std::log(v);
  }
  return std::exp(log_sum / static_cast<double>(values.size()));
}

std::optional<Range> range_of(const std::vector<double>& values) {
  std::optional<Range> range;
  for (double v : values) {
    if (!std::isfinite(v)) continue;
    if (!range) {
      range = Range{v, v};
    } else {
      range->lo = std::min(range->lo, v);
      range->hi = std::max(range->hi, v);
    }
  }
  return range;
}

std::string range_text(const Range& range, std::string (*format)(double)) {
  const std::string lo = format(range.lo), hi = format(range.hi);
  return lo == hi ? lo : lo + "–" + hi;
}

std::vector<SceneWinner> scene_winners(const std::vector<MappingCase>& cases,
                                       const std::vector<std::string>& scenes,
                                       const std::vector<std::string>& mappings) {
  std::vector<SceneWinner> winners;
  for (const std::string& scene : scenes) {
    size_t best = mappings.size();
    std::vector<double> errors;
    for (size_t i = 0; i < mappings.size(); ++i) {
      errors.push_back(find_error(cases, scene, mappings[i]));
      if (best == mappings.size() || errors[i] < errors[best]) best = i;
    }
    if (best == mappings.size()) continue;
    double next = std::numeric_limits<double>::quiet_NaN();
    for (size_t i = 0; i < mappings.size(); ++i) {
      if (i != best && (std::isnan(next) || errors[i] < next)) next = errors[i];
    }
    winners.push_back({scene, mappings[best], errors[best], next / errors[best]});
  }
  return winners;
}

std::vector<MappingMean> mapping_means(const std::vector<MappingCase>& cases,
                                       const std::vector<std::string>& scenes,
                                       const std::vector<std::string>& mappings) {
  std::vector<MappingMean> means;
  means.reserve(mappings.size());
  for (const std::string& mapping : mappings) {
    std::vector<double> errors;
    errors.reserve(scenes.size());
    for (const std::string& scene : scenes) errors.push_back(find_error(cases, scene, mapping));
    means.push_back({mapping, geometric_mean(errors)});
  }
  return means;
}

OverallWinner overall_winner(const std::vector<MappingMean>& means) {
  std::vector<std::pair<double, std::string>> printed;
  printed.reserve(means.size());
  for (const MappingMean& m : means) {  // a mean that is not a number sorts last
    printed.emplace_back(
        std::isfinite(m.mean) ? std::stod(format_significant(m.mean, 3)) : INFINITY, m.mapping);
  }
  std::stable_sort(printed.begin(), printed.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  if (printed.empty()) return {};
  if (printed.size() == 1) return {printed[0].second, std::numeric_limits<double>::quiet_NaN()};
  return {printed[0].second, printed[1].first / printed[0].first};
}

bool goal_reached(double max_pos, double max_angle, double pos_goal,
                  std::optional<double> angle_goal) {
  return max_pos <= pos_goal && (!angle_goal || max_angle <= *angle_goal);
}

int random_reached(const std::vector<RandomCase>& cases, const RandomConfig& config) {
  return static_cast<int>(std::count_if(cases.begin(), cases.end(), [&](const RandomCase& c) {
    return goal_reached(c.max_pos_frictionless, c.max_angle_frictionless, config.pos_goal,
                        config.angle_goal);
  }));
}

double median_of(std::vector<double> values) {
  values.erase(
      std::remove_if(values.begin(), values.end(), [](double v) { return !std::isfinite(v); }),
      values.end());
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  if (n == 0) return std::numeric_limits<double>::quiet_NaN();
  return n % 2 == 1 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

FrictionSummary friction_summary(const std::vector<RandomCase>& cases, double goal) {
  FrictionSummary s;
  std::vector<double> total, shape, push, rest;
  for (const RandomCase& c : cases) {
    ++s.count;
    s.within += c.max_pos_friction <= goal;
    s.rest_within += c.friction_rest <= goal;
    total.push_back(c.max_pos_friction);
    shape.push_back(c.friction_shape);
    push.push_back(c.friction_push);
    rest.push_back(c.friction_rest);
    if (std::isfinite(c.friction_rest)) s.max_rest = std::max(s.max_rest, c.friction_rest);
  }
  s.median_total = median_of(total);
  s.median_shape = median_of(shape);
  s.median_push = median_of(push);
  s.median_rest = median_of(rest);
  return s;
}

std::string versions_apart_text(double apart) {
  if (std::isnan(apart)) return "–";
  if (versions_differ(apart)) return "2.2.2 ↔ 3.14: " + format_significant(apart, 2) + " m";
  return apart == 0.0 ? "same as 2.2.2 to the bit"
                      : "same as 2.2.2 to " + format_significant(apart, 2) + " m";
}

std::string ratio_phrase(double ratio, const std::string& comparative, const std::string& what) {
  const std::string printed = format_significant(ratio);
  if (printed == "1") return "level with " + what + " (within 0.5 %)";
  return printed + "× " + comparative + " " + what;
}

double random_zeta(const RandomCase& c) { return c.c / (2 * std::sqrt(c.k * c.mass)); }

std::vector<ZetaBand> random_bands(const std::vector<RandomCase>& cases,
                                   const RandomConfig& config) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double edges[] = {0.0, 0.3, 1.0, std::numeric_limits<double>::infinity()};
  auto finite_max = [&](const std::vector<double>& v) {
    const std::optional<Range> r = range_of(v);
    return r ? r->hi : nan;
  };
  std::vector<ZetaBand> out;
  for (int b = 0; b < 3; ++b) {
    ZetaBand band;
    band.lo = edges[b];
    band.hi = edges[b + 1];
    std::vector<double> pos, angle, friction;
    std::vector<RandomCase> members;
    for (const RandomCase& c : cases) {
      const double zeta = random_zeta(c);
      if (zeta < band.lo || zeta >= band.hi) continue;
      members.push_back(c);
      pos.push_back(c.max_pos_frictionless);
      angle.push_back(c.max_angle_frictionless);
      friction.push_back(c.max_pos_friction);
    }
    band.count = static_cast<int>(members.size());
    band.reached = random_reached(members, config);
    band.max_pos = finite_max(pos);
    band.max_angle = finite_max(angle);
    band.max_pos_friction = finite_max(friction);
    band.median_pos = median_of(pos);
    out.push_back(band);
  }
  return out;
}

double micros_per_step(double seconds, double duration, double dt) {
  return seconds / (duration / dt) * 1e6;
}

std::optional<Range> bench_ratio_range(const Bench& bench,
                                       const std::vector<std::string>& integrators) {
  std::vector<double> ratios;
  for (const BenchRow& row : bench.rows) {
    if (!row.mj_cpu_ns) continue;
    if (std::find(integrators.begin(), integrators.end(), row.integrator) == integrators.end())
      continue;
    ratios.push_back(*row.mj_cpu_ns / row.ref_cpu_ns);
  }
  return range_of(ratios);
}

std::optional<std::string> mujoco_cost_ratio(const Bench& bench) {
  const auto range = bench_ratio_range(bench, {"semi_implicit_euler", "rk4"});
  if (!bench.ran || !range) return std::nullopt;
  auto whole = [](double x) { return fixed(x, 0); };
  return range_text({std::round(range->lo), std::round(range->hi)}, whole) + "×";
}

std::vector<double> observed_orders(const SceneSweep& sweep,
                                    const std::vector<std::string>& integrators) {
  std::vector<double> orders;
  for (const OrderRow& row : sweep.orders) {
    if (row.engine != "ref" || row.against != "reference" || !row.observed) continue;
    if (std::find(integrators.begin(), integrators.end(), row.integrator) == integrators.end())
      continue;
    orders.push_back(*row.observed);
  }
  return orders;
}

std::vector<double> bracketed_omega_dt(const std::vector<StabilityMap>& maps,
                                       const std::string& engine, const std::string& integrator) {
  std::vector<double> values;
  for (const StabilityMap& map : maps) {
    for (const StabilityRow& row : map.rows) {
      if (row.engine == engine && row.integrator == integrator && row.verdict == "bracketed")
        values.push_back(row.omega_dt_stable);
    }
  }
  return values;
}

}  // namespace contact2d::report
