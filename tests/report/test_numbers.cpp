// The report's computed prose numbers against hand-computed values.
#include <gtest/gtest.h>

#include <cmath>

#include "fixtures.hpp"
#include "report/numbers.hpp"

namespace contact2d::report {
namespace {

TEST(ReportNumbers, Formatting) {
  EXPECT_EQ(format_significant(0.000123456), "0.000123");
  EXPECT_EQ(format_significant(1234567.0), "1.23e+06");
  EXPECT_EQ(format_significant(std::nan("")), "–");
  EXPECT_EQ(sci(1e-5), "1e-5");
  EXPECT_EQ(sci(3e-3), "3e-3");
  EXPECT_EQ(sci(2.5e-4), "2.5e-4");
  EXPECT_EQ(sci(1000), "1e3");
  EXPECT_EQ(fixed(4.6149, 1), "4.6");
  EXPECT_EQ(count_words(24), "twenty-four");
  EXPECT_EQ(count_words(4), "four");
  EXPECT_EQ(count_words(30), "thirty");
  EXPECT_EQ(count_words(100), "100");
  EXPECT_EQ(capitalised("twenty-four"), "Twenty-four");
}

TEST(ReportNumbers, GeometricMean) {
  EXPECT_NEAR(geometric_mean({1e-3, 1e-1}), 1e-2, 1e-15);
  EXPECT_NEAR(geometric_mean({2, 4, 8}), 4, 1e-12);
  EXPECT_TRUE(std::isnan(geometric_mean({})));
  EXPECT_TRUE(std::isnan(geometric_mean({1, 0})));
}

TEST(ReportNumbers, Ranges) {
  const auto r = range_of({3, std::nan(""), 1.5, 2});
  ASSERT_TRUE(r);
  EXPECT_EQ(r->lo, 1.5);
  EXPECT_EQ(r->hi, 3);
  EXPECT_FALSE(range_of({std::nan("")}));
  auto two = [](double x) { return format_significant(x, 2); };
  EXPECT_EQ(range_text({0.43, 1.2}, two), "0.43–1.2");
  EXPECT_EQ(range_text({7.51, 7.54}, two), "7.5");  // equal as printed: one value
}

TEST(ReportNumbers, WinnersPerSceneAndOverall) {
  const ReadmeData d = fixtures::readme();
  const auto winners = scene_winners(d.shipped, d.scenes, d.mappings);
  ASSERT_EQ(winners.size(), 2u);
  EXPECT_EQ(winners[0].mapping, "calibrated");
  EXPECT_EQ(winners[0].error, 0.1);
  EXPECT_NEAR(winners[0].ratio_to_next, 2.5, 1e-12);
  EXPECT_EQ(winners[1].mapping, "exact");
  EXPECT_NEAR(winners[1].ratio_to_next, 1.5, 1e-12);

  const auto means = mapping_means(d.shipped, d.scenes, d.mappings);
  ASSERT_EQ(means.size(), 3u);
  EXPECT_NEAR(means[0].mean, std::sqrt(0.5 * 0.2), 1e-12);
  EXPECT_NEAR(means[1].mean, std::sqrt(0.25 * 0.02), 1e-12);
  EXPECT_NEAR(means[2].mean, std::sqrt(0.1 * 0.03), 1e-12);
  const OverallWinner overall = overall_winner(means);
  EXPECT_EQ(overall.mapping, "calibrated");
  EXPECT_NEAR(overall.ratio_to_next, 0.0707 / 0.0548, 1e-12);  // the means as printed
}

TEST(ReportNumbers, MeanThatIsNotANumberSortsLast) {
  const OverallWinner w =
      overall_winner({{"seed", std::nan("")}, {"exact", 0.2}, {"calibrated", 0.4}});
  EXPECT_EQ(w.mapping, "exact");
  EXPECT_NEAR(w.ratio_to_next, 2.0, 1e-12);
}

TEST(ReportNumbers, TiesGoToTheFirstMapping) {
  std::vector<MappingCase> cases;
  for (const char* m : {"seed", "exact", "calibrated"})
    cases.push_back({"circle", m, fixtures::comparison(0.5, 0)});
  cases[2].result.max_pos = 0.6;
  const auto w = scene_winners(cases, {"circle"}, {"seed", "exact", "calibrated"});
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].mapping, "seed");
  EXPECT_EQ(w[0].ratio_to_next, 1.0);
}

TEST(ReportNumbers, Goals) {
  EXPECT_TRUE(goal_reached(1e-5, 1e-4, 1e-5, 1e-4));  // at the goal counts
  EXPECT_FALSE(goal_reached(1.01e-5, 0, 1e-5, 1e-4));
  EXPECT_FALSE(goal_reached(1e-6, 2e-4, 1e-5, 1e-4));
  EXPECT_TRUE(goal_reached(1e-3, 7.0, 3e-3, std::nullopt));
  const ReadmeData d = fixtures::readme();
  EXPECT_EQ(random_reached(d.random, d.random_config), 1);
}

// The fixture's four scenes (fixtures.hpp has the hand computation).
TEST(ReportNumbers, ZetaBands) {
  const ReadmeData d = fixtures::readme();
  EXPECT_NEAR(random_zeta(d.random[0]), 0.15, 1e-12);
  EXPECT_NEAR(random_zeta(d.random[2]), 1500 / (2 * std::sqrt(1.25 * 3e5)), 1e-12);
  const std::vector<ZetaBand> b = random_bands(d.random, d.random_config);
  ASSERT_EQ(b.size(), 3u);
  EXPECT_EQ(b[0].count, 2);
  EXPECT_EQ(b[0].reached, 1);
  EXPECT_NEAR(b[0].median_pos, 1.51e-4, 1e-15);
  EXPECT_EQ(b[0].max_pos, 3e-4);
  EXPECT_EQ(b[0].max_angle, 1e-9);
  EXPECT_EQ(b[0].max_pos_friction, 0.002);
  EXPECT_EQ(b[1].count, 1);
  EXPECT_EQ(b[1].reached, 0);
  EXPECT_EQ(b[1].max_angle, 2e-4);
  EXPECT_EQ(b[2].count, 1);
  EXPECT_EQ(b[2].reached, 0);
  EXPECT_EQ(b[2].max_pos, 2e-5);
  EXPECT_EQ(b[2].lo, 1.0);
  EXPECT_TRUE(std::isinf(b[2].hi));
  // An empty band has no errors.
  const std::vector<ZetaBand> none = random_bands({}, d.random_config);
  EXPECT_EQ(none[1].count, 0);
  EXPECT_TRUE(std::isnan(none[1].max_pos));
  EXPECT_TRUE(std::isnan(none[1].median_pos));
}

TEST(ReportNumbers, PerStepCost) {
  EXPECT_NEAR(micros_per_step(0.05, 2.0, 1e-4), 2.5, 1e-12);  // 0.05 s over 2e4 steps
}

TEST(ReportNumbers, BenchRatios) {
  const Bench b = fixtures::sweep().bench;
  const auto euler_rk4 = bench_ratio_range(b, {"semi_implicit_euler", "rk4"});
  ASSERT_TRUE(euler_rk4);
  EXPECT_NEAR(euler_rk4->lo, 50, 1e-12);  // 1000 / 20
  EXPECT_NEAR(euler_rk4->hi, 80, 1e-12);  // 4000 / 50
  EXPECT_EQ(mujoco_cost_ratio(b), "50–80×");
  Bench none = b;
  for (BenchRow& r : none.rows) r.mj_cpu_ns.reset();
  EXPECT_FALSE(mujoco_cost_ratio(none));
  none.ran = false;
  EXPECT_FALSE(mujoco_cost_ratio(b.ran ? none : b));
}

TEST(ReportNumbers, OrdersAndStability) {
  const SceneSweep s = fixtures::scene_sweep("circle", 1);
  EXPECT_EQ(observed_orders(s, {"semi_implicit_euler"}), std::vector<double>{1.004});
  EXPECT_EQ(observed_orders(s, {"rk4"}), std::vector<double>{4.61});  // MuJoCo's has none
  const StabilityData d = fixtures::stability();
  const auto w = bracketed_omega_dt(d.reference, "ref", "explicit_euler");
  ASSERT_EQ(w.size(), 3u);
  EXPECT_NEAR(w[0], 316 * 0.0016, 1e-12);
  EXPECT_NEAR(w[2], 700 * 0.0011, 1e-12);
}

// MuJoCo 3.14 beside 2.2.2: within kVersionsRounding (1e-9 m) a case is
// "the same" to its distance, beyond it the distance is named; NaN (not
// run) is neither.
TEST(ReportNumbers, VersionsApart) {
  EXPECT_EQ(versions_apart_text(0.0), "same as 2.2.2 to the bit");
  EXPECT_EQ(versions_apart_text(2.34e-13), "same as 2.2.2 to 2.3e-13 m");
  EXPECT_EQ(versions_apart_text(1e-9), "same as 2.2.2 to 1e-09 m");
  EXPECT_EQ(versions_apart_text(1.1e-9), "2.2.2 ↔ 3.14: 1.1e-09 m");
  EXPECT_EQ(versions_apart_text(std::nan("")), "–");
  EXPECT_FALSE(versions_differ(std::nan("")));
  EXPECT_TRUE(versions_differ(0.02));
}

// A ratio that prints as 1 is "level with", never "1× smaller".
TEST(ReportNumbers, RatioPhrase) {
  EXPECT_EQ(ratio_phrase(2.07, "smaller than", "the next best"),
            "2.07× smaller than the next best");
  EXPECT_EQ(ratio_phrase(1.006, "smaller than", "the next best"),
            "1.01× smaller than the next best");
  EXPECT_EQ(ratio_phrase(1.004, "smaller than", "the next best"),
            "level with the next best (within 0.5 %)");
  EXPECT_EQ(ratio_phrase(1.0, "below", "the next best"), "level with the next best (within 0.5 %)");
}

}  // namespace
}  // namespace contact2d::report
