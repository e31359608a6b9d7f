// Nanoseconds per sample for every sampler, drawn the way the renderer draws
// them on the Cornell box (sampling/sampler_cost.h): a batch's camera samples,
// then its paths' vertex draws, for paths of depth 4 — so startPixelSample is
// amortised over a typical path. Reported per drawn dimension, and separately
// for 1D and 2D.
#include <benchmark/benchmark.h>

#include "sampling/sampler_cost.h"

namespace pathlab {
namespace {

constexpr int kSpp = 64;
constexpr int kDepth = 4;
constexpr Vec2i kResolution{256, 256};

void pathDimensions(benchmark::State& state, const std::string& name) {
    AnySampler sampler = makeSampler(name, SamplerConfig{kSpp, 1, kResolution});
    int64_t paths = 0;
    std::visit(
        [&](auto& s) {
            BatchWalk walk{kSpp, kResolution};
            for (auto _ : state) {
                benchmark::DoNotOptimize(
                    drawBatchDimensions(s, walk.pixel, walk.index, walk.count(), kDepth));
                paths += walk.count();
                walk.advance();
            }
        },
        sampler);
    const double dimsPerPath = dimensionsPerPath(kDepth);
    state.counters["ns/dim"] = benchmark::Counter(
        double(paths) * dimsPerPath, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// Only 1D (or only 2D) draws after one startPixelSample per 8 draws.
template <bool kTwoD>
void draws(benchmark::State& state, const std::string& name) {
    AnySampler sampler = makeSampler(name, SamplerConfig{kSpp, 1, kResolution});
    int64_t count = 0;
    std::visit(
        [&](auto& s) {
            int index = 0, x = 0;
            for (auto _ : state) {
                s.startPixelSample(Vec2i{x, 7}, index, dims::kFirstBounce);
                float acc = 0;
                for (int k = 0; k < 8; ++k) {
                    if constexpr (kTwoD) {
                        const Vec2f u = s.get2D();
                        acc += u.x + u.y;
                    } else {
                        acc += s.get1D();
                    }
                }
                benchmark::DoNotOptimize(acc);
                count += 8;
                if (++index == kSpp) index = 0, x = (x + 1) % kResolution.x;
            }
        },
        sampler);
    state.counters[kTwoD ? "ns/2D" : "ns/1D"] = benchmark::Counter(
        double(count), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

const bool registered = [] {
    for (const SamplerInfo& info : samplerInfos()) {
        benchmark::RegisterBenchmark(("Sampler/path/" + info.name).c_str(), pathDimensions,
                                     info.name);
        benchmark::RegisterBenchmark(("Sampler/1D/" + info.name).c_str(), draws<false>, info.name);
        benchmark::RegisterBenchmark(("Sampler/2D/" + info.name).c_str(), draws<true>, info.name);
    }
    return true;
}();

}  // namespace
}  // namespace pathlab
