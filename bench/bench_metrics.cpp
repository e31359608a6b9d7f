// Image metrics on a 512×512 pair: FLIP (LDR and HDR) and the pixel metrics,
// with TBB limited to 1 and 2 threads (the benchmark argument).
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <cstdint>

#include "core/hash.h"
#include "core/image.h"
#include "metrics/flip.h"
#include "metrics/image_metrics.h"

namespace {

using pathlab::Image;

// A deterministic, platform-independent value in [0,1) (integer hash only).
float hash01(uint32_t x) {
    return float(pathlab::hash32(x) >> 8) * (1.0f / 16777216.0f);
}

// A render-like pair: smooth shading with a bright light (scaled by
// `light`), and the same with per-pixel noise as from a low sample count.
struct Pair {
    Image reference, test;
};

Pair makePair(int size, float light) {
    Pair p{Image(size, size), Image(size, size)};
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const float u = float(x) / float(size), v = float(y) / float(size);
            const float d2 = (u - 0.7f) * (u - 0.7f) + (v - 0.2f) * (v - 0.2f);
            const float glow = light / (1.0f + 200.0f * d2);
            const pathlab::Vec3f c{0.2f + 0.6f * u + glow, 0.3f + 0.4f * v + glow, 0.25f + glow};
            p.reference.set(x, y, c);
            const size_t i = size_t(y) * size + x;
            const float noise = 0.6f * (2.0f * hash01(uint32_t(i)) - 1.0f);
            p.test.set(x, y, c * (1.0f + noise));
        }
    return p;
}

void runFlip(benchmark::State& state, pathlab::flip::Mode mode, float light) {
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                                size_t(state.range(0)));
    const Pair pair = makePair(512, light);
    pathlab::flip::Options options;
    options.mode = mode;
    int exposures = 1;
    for (auto _ : state) {
        const auto result = pathlab::flip::evaluate(pair.reference, pair.test, options);
        exposures = result.exposures.count;
        benchmark::DoNotOptimize(result.stats.mean);
    }
    state.counters["exposures"] = exposures;
    state.SetItemsProcessed(state.iterations() * 512 * 512);
}

void BM_FlipLdr512(benchmark::State& state) {
    runFlip(state, pathlab::flip::Mode::Ldr, 0.5f);
}
void BM_FlipHdr512(benchmark::State& state) {
    runFlip(state, pathlab::flip::Mode::Hdr, 20.0f);
}

// What a study pays per cell: the reference's half prepared once, outside the loop.
void BM_FlipHdr512PreparedReference(benchmark::State& state) {
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                                size_t(state.range(0)));
    const Pair pair = makePair(512, 20.0f);
    pathlab::flip::Options options;
    options.mode = pathlab::flip::Mode::Hdr;
    const pathlab::flip::PreparedReference prepared(pair.reference, options);
    for (auto _ : state) benchmark::DoNotOptimize(prepared.evaluate(pair.test).stats.mean);
    state.SetItemsProcessed(state.iterations() * 512 * 512);
}

void BM_MseRelMse512(benchmark::State& state) {
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                                size_t(state.range(0)));
    const Pair pair = makePair(512, 20.0f);
    for (auto _ : state) {
        benchmark::DoNotOptimize(pathlab::meanSquaredError(pair.reference, pair.test));
        benchmark::DoNotOptimize(pathlab::relativeMeanSquaredError(pair.reference, pair.test));
    }
}

BENCHMARK(BM_FlipLdr512)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FlipHdr512)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FlipHdr512PreparedReference)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_MseRelMse512)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
