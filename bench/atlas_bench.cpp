// Google Benchmark: the atlas's cost per point (docs/atlas.md), on the points
// of validation/atlas/throughput.toml (2-s scenes at Δt = 1e-4 s: the
// reference, MuJoCo with its model built, and the converged solution at
// 1e-12 with its 10× run), one benchmark per body, each iteration the next
// point of that body. CPU time per point and points per CPU second
// ("points_per_s", the throughput per core).
#include <benchmark/benchmark.h>

#include "analysis/atlas.hpp"
#include "io/atlas_spec.hpp"

namespace {

using namespace contact2d;

const AtlasSpec& spec() {
  static const AtlasSpec s =
      load_atlas_spec(CONTACT2D_SOURCE_DIR "/validation/atlas/throughput.toml");
  return s;
}

void BM_AtlasPoint(benchmark::State& state) {
  const AtlasSpec& s = spec();
  const long long per_body = atlas_point_count(s) / static_cast<long long>(s.bodies.size());
  const long long first = state.range(0) * per_body;
  long long i = 0;
  for (auto _ : state) {
    const analysis::AtlasPoint point = analysis::atlas_point(s, first + i);
    const analysis::AtlasResult result = analysis::run_atlas_point(point, s.converged_tol);
    benchmark::DoNotOptimize(result.mujoco_conv_pos);
    if (result.status != "ok") state.SkipWithError(result.message.c_str());
    i = (i + 1) % per_body;
  }
  state.SetLabel(s.bodies[static_cast<size_t>(state.range(0))].label);
  state.counters["points_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_AtlasPoint)->DenseRange(0, 3)->Unit(benchmark::kMillisecond)->MinTime(1.0);

}  // namespace

BENCHMARK_MAIN();
