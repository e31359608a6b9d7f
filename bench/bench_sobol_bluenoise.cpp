// How long `sobol-bluenoise`'s optimiser takes to arrange its key tile (what
// the first use on a machine pays before the tile is cached), for the
// shipped settings and a few cheaper and dearer ones (docs/samplers.md).
#include <benchmark/benchmark.h>

#include "sampling/sobol_bluenoise_keys.h"

namespace pathlab {
namespace {

void optimise(benchmark::State& state) {
    // The settings defaultSobolBlueNoiseKeys() ships (the struct's defaults),
    // with the swap proposals per pixel varied.
    SobolBlueNoiseOptimizer settings;
    settings.passes = int(state.range(0));
    for (auto _ : state) benchmark::DoNotOptimize(optimizeSobolBlueNoiseKeys(settings).key.data());
}
BENCHMARK(optimise)
    ->Name("SobolBlueNoise/optimise128/passes")
    ->Arg(0)
    ->Arg(40)
    ->Arg(160)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

}  // namespace
}  // namespace pathlab
