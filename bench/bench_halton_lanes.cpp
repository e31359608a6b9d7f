// The Halton lane kernels (sampling/halton_lanes.cpp) per
// instruction set: nanoseconds per value over the dimensions a path of depth 8
// draws (2 … 57), for the first packet's indices (samples 0–7) of each pixel
// of a 512×512 image's first row, with 8, 3 and 2 live lanes (a batch's
// paths die as they bounce). Levels this processor lacks are skipped.
#include <benchmark/benchmark.h>

#include "sampling/halton.h"

namespace pathlab {
namespace {

constexpr int kFirstDimension = 2, kLastDimension = 57;

template <HaltonScrambling kScrambling>
void haltonLanes(benchmark::State& state, SimdLevel level, int count) {
    if (level > bestSimdLevel()) {
        state.SkipWithError("this processor lacks the instruction set");
        return;
    }
    const auto tables = haltonDigitPermutations(1);
    const HaltonImageMapping mapping({512, 512});
    uint64_t a[kCameraPacketSamples];
    Vec2i pixel{0, 0};
    int64_t values = 0;
    for (auto _ : state) {
        for (int j = 0; j < kCameraPacketSamples; ++j) a[j] = mapping.index(pixel, j);
        float out[kCameraPacketSamples];
        for (int d = kFirstDimension; d <= kLastDimension; ++d) {
            if constexpr (kScrambling == HaltonScrambling::Owen)
                owenScrambledLanes(tables->dimensions[size_t(d)], a, count, out, level);
            else if constexpr (kScrambling == HaltonScrambling::RandomDigit)
                randomDigitScrambledLanes(tables->dimensions[size_t(d)], a, count, out, level);
            else
                radicalInverseLanes(primeBases()[d], a, count, out, level);
            benchmark::DoNotOptimize(out);
        }
        values += int64_t(count) * (kLastDimension - kFirstDimension + 1);
        pixel.x = (pixel.x + 1) % 512;
    }
    state.counters["ns/value"] = benchmark::Counter(
        double(values), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

const bool registered = [] {
    const std::pair<const char*, SimdLevel> levels[] = {{"baseline", SimdLevel::Baseline},
                                                        {"avx2", SimdLevel::Avx2},
                                                        {"avx512", SimdLevel::Avx512},
                                                        {"avx512vbmi", SimdLevel::Avx512Vbmi}};
    for (const auto& [name, level] : levels)
        for (int count : {8, 3, 2}) {
            const std::string suffix = std::string(name) + "/lanes:" + std::to_string(count);
            benchmark::RegisterBenchmark(("HaltonLanes/plain/" + suffix).c_str(),
                                         haltonLanes<HaltonScrambling::None>, level, count);
            benchmark::RegisterBenchmark(("HaltonLanes/rd/" + suffix).c_str(),
                                         haltonLanes<HaltonScrambling::RandomDigit>, level, count);
            benchmark::RegisterBenchmark(("HaltonLanes/owen/" + suffix).c_str(),
                                         haltonLanes<HaltonScrambling::Owen>, level, count);
        }
    return true;
}();

}  // namespace
}  // namespace pathlab
