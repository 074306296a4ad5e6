// Reads the JSON that Google Benchmark writes with --benchmark_out_format=json
// into the report's Bench struct. A small hand parser (the project has no
// JSON library, and this needs only the "benchmarks" array's names, times and
// time units): a JSON value is parsed in full and checked, anything that is
// not JSON throws std::runtime_error with the offset.
//
// Benchmarks named "ref/SCENE/INTEGRATOR" and "mj_step/SCENE/INTEGRATOR"
// become one row per scene and integrator (in the order the reference runs
// appear); "floor/libm_sincos", "floor/bounded_tanh" (or "floor/libm_tanh"
// when the bench has no bounded_tanh), "floor/step_free_flight" the floors.
// Times are per iteration, converted to ns.
#pragma once

#include <string>

#include "report/results.hpp"

namespace contact2d::report {

Bench parse_bench_json(const std::string& json);

}  // namespace contact2d::report
