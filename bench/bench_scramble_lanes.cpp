// The Owen-scramble lane kernels of `zsobol`'s lane draws
// (sampling/scramble_lanes.cpp) per instruction set: nanoseconds per value,
// one dimension (eight lanes) and a pair of dimensions (sixteen values).
// Levels this processor lacks are skipped.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <string>

#include "sampling/sampler.h"
#include "sampling/scramble_lanes.h"

namespace pathlab {
namespace {

void scrambleLanes(benchmark::State& state, SimdLevel level, bool paired) {
    if (level > bestSimdLevel()) {
        state.SkipWithError("this processor lacks the instruction set");
        return;
    }
    uint32_t x[kCameraPacketSamples], y[kCameraPacketSamples];
    for (int j = 0; j < kCameraPacketSamples; ++j)
        x[j] = uint32_t(j) * 0x9e3779b9u, y[j] = uint32_t(j) * 0x85ebca6bu;
    uint32_t seed = 1;
    int64_t values = 0;
    for (auto _ : state) {
        float out[2 * kCameraPacketSamples];
        if (paired) {
            owenScrambleReversedLanes2D(x, y, seed, seed ^ 0x5bd1e995u, out, level);
        } else {
            owenScrambleReversedLanes(x, seed, out, level);
            owenScrambleReversedLanes(y, seed ^ 0x5bd1e995u, out + kCameraPacketSamples, level);
        }
        benchmark::DoNotOptimize(out);
        seed += 0x632be5abu;
        values += 2 * kCameraPacketSamples;
    }
    state.counters["ns/value"] = benchmark::Counter(
        double(values), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

const bool registered = [] {
    const std::pair<const char*, SimdLevel> levels[] = {{"baseline", SimdLevel::Baseline},
                                                        {"avx2", SimdLevel::Avx2},
                                                        {"avx512vbmi", SimdLevel::Avx512Vbmi}};
    for (const auto& [name, level] : levels) {
        benchmark::RegisterBenchmark(("ScrambleLanes/two-calls/" + std::string(name)).c_str(),
                                     scrambleLanes, level, false);
        benchmark::RegisterBenchmark(("ScrambleLanes/paired/" + std::string(name)).c_str(),
                                     scrambleLanes, level, true);
    }
    return true;
}();

}  // namespace
}  // namespace pathlab
