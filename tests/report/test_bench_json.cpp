// The bench's JSON reader (report/bench_json.hpp) on hand-written JSON.
#include <gtest/gtest.h>

#include <stdexcept>

#include "report/bench_json.hpp"

namespace contact2d::report {
namespace {

const char* const kJson = R"({
  "context": {"date": "x", "caches": [{"level": 1}], "load_avg": [1.5, 0.5, 0.25],
              "note": "a \"quoted\" \\ \u00e9 text", "flag": true, "none": null},
  "benchmarks": [
    {"name": "ref/box/rk4", "run_type": "iteration", "iterations": 100,
     "real_time": 2.5e+02, "cpu_time": 2.0e+02, "time_unit": "ns"},
    {"name": "mj_step/box/rk4", "run_type": "iteration", "iterations": 10,
     "real_time": 12.5, "cpu_time": 12.0, "time_unit": "us"},
    {"name": "mj_step/box/rk4_mean", "run_type": "aggregate",
     "real_time": 99, "cpu_time": 99, "time_unit": "us"},
    {"name": "ref/circle/rk4", "run_type": "iteration", "error_occurred": true,
     "error_message": "failed"},
    {"name": "ref/circle/semi_implicit_euler", "run_type": "iteration",
     "real_time": 0.06, "cpu_time": 0.05, "time_unit": "us"},
    {"name": "floor/libm_tanh", "run_type": "iteration", "real_time": 41.6, "cpu_time": 41.5,
     "time_unit": "ns"}
  ]
})";

TEST(BenchJson, RowsFloorsAndUnits) {
  const Bench b = parse_bench_json(kJson);
  EXPECT_TRUE(b.ran);
  ASSERT_EQ(b.rows.size(), 2u);  // the failed run is left out
  EXPECT_EQ(b.rows[0].scene, "box");
  EXPECT_EQ(b.rows[0].integrator, "rk4");
  EXPECT_DOUBLE_EQ(b.rows[0].ref_cpu_ns, 200);
  EXPECT_DOUBLE_EQ(b.rows[0].ref_real_ns, 250);
  ASSERT_TRUE(b.rows[0].mj_cpu_ns);
  EXPECT_DOUBLE_EQ(*b.rows[0].mj_cpu_ns, 12000);  // 12 µs, not the aggregate's 99
  EXPECT_DOUBLE_EQ(*b.rows[0].mj_real_ns, 12500);
  EXPECT_EQ(b.rows[1].scene, "circle");
  EXPECT_DOUBLE_EQ(b.rows[1].ref_cpu_ns, 50);
  EXPECT_FALSE(b.rows[1].mj_cpu_ns);
  EXPECT_DOUBLE_EQ(b.tanh_ns, 41.5);
  EXPECT_EQ(b.sincos_ns, -1.0);  // not in this run
}

// The tanh floor is the default path's (floor/bounded_tanh) when the bench
// timed it, glibc's (floor/libm_tanh) otherwise (above).
TEST(BenchJson, TanhFloorIsTheBoundedOneWhenTimed) {
  const Bench b = parse_bench_json(R"({"benchmarks": [
    {"name": "floor/libm_tanh", "run_type": "iteration", "real_time": 41.6, "cpu_time": 41.5,
     "time_unit": "ns"},
    {"name": "floor/bounded_tanh", "run_type": "iteration", "real_time": 12.6, "cpu_time": 12.5,
     "time_unit": "ns"}]})");
  EXPECT_DOUBLE_EQ(b.tanh_ns, 12.5);
}

TEST(BenchJson, MalformedJsonThrows) {
  EXPECT_THROW(parse_bench_json(""), std::runtime_error);
  EXPECT_THROW(parse_bench_json("{\"benchmarks\": [}"), std::runtime_error);
  EXPECT_THROW(parse_bench_json("{\"benchmarks\": []} x"), std::runtime_error);
  EXPECT_THROW(parse_bench_json("{\"context\": {}}"), std::runtime_error);
  EXPECT_THROW(parse_bench_json("{\"benchmarks\": [{\"name\": \"ref/a/b\", \"cpu_time\": 1, "
                                "\"real_time\": 1, \"time_unit\": \"parsec\"}]}"),
               std::runtime_error);
}

}  // namespace
}  // namespace contact2d::report
