// The error spectrum (metrics/error_spectrum.h) of a W×H pair: square powers
// of two, a 16:9 frame and a size with a large prime factor (FFTW falls back
// to slower codelets there), and the cost of the FFT alone beside the whole.
#include <benchmark/benchmark.h>

#include <cstdint>

#include "core/hash.h"
#include "metrics/error_spectrum.h"

namespace {

using pathlab::Image;

float hash01(uint32_t x) {
    return float(pathlab::hash32(x) >> 8) * (1.0f / 16777216.0f);
}

Image noisy(int w, int h, uint32_t salt) {
    Image img(w, h);
    for (size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = hash01(uint32_t(i) * 3 + salt);
    return img;
}

void BM_ErrorSpectrum(benchmark::State& state) {
    const int w = int(state.range(0)), h = int(state.range(1));
    const Image reference = noisy(w, h, 1), test = noisy(w, h, 2);
    for (auto _ : state) {
        const pathlab::RadialPowerSpectrum s = pathlab::errorSpectrum(reference, test);
        benchmark::DoNotOptimize(s.lowFrequencyPower);
    }
    state.SetItemsProcessed(state.iterations() * int64_t(w) * h);
}
BENCHMARK(BM_ErrorSpectrum)
    ->Args({128, 128})
    ->Args({512, 512})
    ->Args({1024, 1024})
    ->Args({1920, 1080})
    ->Args({1009, 997})
    ->Unit(benchmark::kMillisecond);

// The periodogram alone, from the error field (no image reading or channel mean).
void BM_RadialPeriodogram(benchmark::State& state) {
    const int w = int(state.range(0)), h = int(state.range(1));
    const std::vector<double> field = pathlab::signedErrorField(noisy(w, h, 1), noisy(w, h, 2));
    for (auto _ : state) {
        const pathlab::RadialPowerSpectrum s = pathlab::radialPeriodogram(field, w, h);
        benchmark::DoNotOptimize(s.totalPower);
    }
    state.SetItemsProcessed(state.iterations() * int64_t(w) * h);
}
BENCHMARK(BM_RadialPeriodogram)
    ->Args({512, 512})
    ->Args({1920, 1080})
    ->Unit(benchmark::kMillisecond);

}  // namespace
