// Google Benchmark JSON to report::Bench (report/bench_json.hpp).
#include "report/bench_json.hpp"

#include "io/json_reader.hpp"

#include <map>
#include <stdexcept>
#include <vector>

namespace contact2d::report {
namespace {

using json::Value;

double to_ns(double value, const std::string& unit) {
  if (unit == "ns") return value;
  if (unit == "us") return value * 1e3;
  if (unit == "ms") return value * 1e6;
  if (unit == "s") return value * 1e9;
  throw std::runtime_error("benchmark JSON: unknown time_unit \"" + unit + "\"");
}

struct Times {
  double cpu_ns = 0.0, real_ns = 0.0;
};

}  // namespace

Bench parse_bench_json(const std::string& json) {
  const Value doc = json::parse(json, "benchmark JSON");
  const Value* list = doc.get("benchmarks");
  if (doc.kind != Value::Kind::Object || !list || list->kind != Value::Kind::Array) {
    throw std::runtime_error("benchmark JSON: no \"benchmarks\" array");
  }
  std::vector<std::string> ref_order;  // "SCENE/INTEGRATOR" of the reference runs
  std::map<std::string, Times> times;  // by benchmark name
  for (const Value& b : list->items) {
    const Value* name = b.get("name");
    const Value* cpu = b.get("cpu_time");
    const Value* real = b.get("real_time");
    const Value* unit = b.get("time_unit");
    const Value* error = b.get("error_occurred");
    const Value* run_type = b.get("run_type");
    if (!name || !cpu || !real || !unit) continue;  // an error run has no times
    if (error && error->text == "true") continue;
    if (run_type && run_type->text != "iteration") continue;  // aggregates
    times[name->text] = {to_ns(cpu->number, unit->text), to_ns(real->number, unit->text)};
    if (name->text.rfind("ref/", 0) == 0) ref_order.push_back(name->text.substr(4));
  }
  Bench bench;
  bench.ran = true;
  for (const std::string& c : ref_order) {
    const size_t slash = c.find('/');
    BenchRow row;
    row.scene = c.substr(0, slash);
    row.integrator = slash == std::string::npos ? "" : c.substr(slash + 1);
    row.ref_cpu_ns = times["ref/" + c].cpu_ns;
    row.ref_real_ns = times["ref/" + c].real_ns;
    const auto mj = times.find("mj_step/" + c);
    if (mj != times.end()) {
      row.mj_cpu_ns = mj->second.cpu_ns;
      row.mj_real_ns = mj->second.real_ns;
    }
    bench.rows.push_back(row);
  }
  auto floor = [&](const char* name) {
    const auto it = times.find(std::string("floor/") + name);
    return it == times.end() ? -1.0 : it->second.cpu_ns;
  };
  bench.sincos_ns = floor("libm_sincos");
  // The tanh on the step's chain: the default path's (contact2d's
  // bounded_tanh, core/vector_math.hpp); glibc's in a bench that predates it.
  bench.tanh_ns = floor("bounded_tanh") >= 0.0 ? floor("bounded_tanh") : floor("libm_tanh");
  bench.free_flight_ns = floor("step_free_flight");
  return bench;
}

}  // namespace contact2d::report
