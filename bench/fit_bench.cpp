// contact2d_fit_bench: the fit's wall time on the shipped ellipse impacts
// (issue target: fitting all 1718 impacts in at most 60 s on 2 cores).
//   BM_FitImpacts/fit     the two penalty fits and the Newton–Coulomb
//                         baseline on both splits (no bootstrap, no k
//                         profile, no engine replays): what "fitting" is
//   BM_FitImpacts/full    what `contact2d fit` does by default with no
//                         engines: the fit, 8 bootstrap refits per split
//                         and the seeded split's k profile
// Each runs once (Iterations(1)): a run is tens of seconds. Threads: one per
// core (analysis::default_threads), as the program.
#include <benchmark/benchmark.h>

#include <string>

#include "analysis/real_impacts.hpp"
#include "io/recording.hpp"

namespace {

using namespace contact2d;

void fit(benchmark::State& state, bool full) {
  const Recording rec =
      read_recording(std::string(CONTACT2D_SOURCE_DIR) + "/validation/real/ellipse/recording.toml");
  analysis::ImpactFitOptions options;
  options.bootstrap = full ? 8 : 0;
  options.k_profile = full;
  for (auto _ : state) {
    const analysis::ImpactFit result = analysis::fit_impacts(rec, options);
    benchmark::DoNotOptimize(result.splits.size());
    state.counters["impacts"] = static_cast<double>(result.impacts.size());
    state.counters["seeded_median"] = result.splits.front().models.front().median;
  }
}

void BM_FitImpacts_fit(benchmark::State& state) { fit(state, false); }
void BM_FitImpacts_full(benchmark::State& state) { fit(state, true); }

BENCHMARK(BM_FitImpacts_fit)
    ->Name("BM_FitImpacts/fit")
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();
BENCHMARK(BM_FitImpacts_full)
    ->Name("BM_FitImpacts/full")
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
