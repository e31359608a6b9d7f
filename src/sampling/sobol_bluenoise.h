// `sobol-bluenoise` — Heitz, Belcour, Ostromoukhov, Coeurjolly & Iehl 2019,
// "A Low-Discrepancy Sampler that Distributes Monte Carlo Errors as a Blue
// Noise in Screen Space" (SIGGRAPH Talks).
//
// The leading 2D draws — the position in the pixel (dimensions 0, 1), the
// first vertex's light point (3, 4) and BSDF direction (6, 7) — are an
// Owen-scrambled Sobol' pair whose ranking and scrambling keys come from a
// 128 × 128 tile arranged by our optimiser (sobol_bluenoise_keys.h) so that
// neighbouring pixels' errors cancel at every power-of-two spp up to 256.
// Each of the three pairs reads the tile at its own toroidal offset, drawn
// from the seed, so the pairs of one pixel have unrelated keys. Every other
// dimension is `sobol-owen`'s (the paper likewise falls back to plain
// scrambled Sobol' past its optimised dimensions) — bit for bit, so a
// comparison of the two samplers differs only where the keys act.
//
// Randomisation: besides the tile offsets, the seed draws a digital shift
// (XOR) per optimised dimension, the same for every pixel. A uniform shift
// makes each coordinate exactly uniform, whatever the keys (the estimator is
// unbiased), and it maps every dyadic elementary interval onto one, so the
// nets of a pixel's samples — and how neighbouring pixels' points share out
// the strata — are kept.
//
// Progressive: the ranking is a nested scramble of the index, so sample i
// does not depend on the spp, and every prefix of 2^k samples is a
// (0,k,2)-net.
#pragma once

#include <array>
#include <memory>

#include "sampling/sobol.h"
#include "sampling/sobol_bluenoise_keys.h"

namespace pathlab {

class SobolBlueNoiseSampler {
  public:
    // The optimised pairs start at these dimensions.
    static constexpr std::array<int, 3> kPairStarts = {dims::kPixel,
                                                       dims::kFirstBounce + dims::kLightPoint,
                                                       dims::kFirstBounce + dims::kBsdfDirection};
    static constexpr int kOptimizedEnd = kPairStarts.back() + 2;

    explicit SobolBlueNoiseSampler(const SamplerConfig& c);

    int samplesPerPixel() const { return fallback_.samplesPerPixel(); }
    void startPixelSample(Vec2i p, int index, int dim) {
        pixel_ = p, index_ = index, dimension_ = dim;
    }
    float get1D() {
        const int d = dimension_++;
        if (optimized(d)) return value(d);
        fallback_.startPixelSample(pixel_, index_, d);
        return fallback_.get1D();
    }
    Vec2f get2D() {
        const int d = dimension_;
        dimension_ += 2;
        if (const int pair = pairStartingAt(d); pair >= 0) return point(pair, pixel_, index_);
        if (optimized(d) || optimized(d + 1)) return {value(d), value(d + 1)};
        fallback_.startPixelSample(pixel_, index_, d);
        return fallback_.get2D();
    }
    Vec2f getPixel2D() { return get2D(); }

    // Lane draws: the fallback's side-by-side kernels past the optimised
    // dimensions; within them each lane is drawn by itself (a table read
    // and two scrambles).
    void get1DLanes(Vec2i p, const int* indices, int count, int dim, float* out) {
        if (dim < kOptimizedEnd) return drawEachLane1D(*this, p, indices, count, dim, out);
        fallback_.get1DLanes(p, indices, count, dim, out);
    }
    void get2DLanes(Vec2i p, const int* indices, int count, int dim, Vec2f* out) {
        if (dim < kOptimizedEnd) return drawEachLane2D(*this, p, indices, count, dim, out);
        fallback_.get2DLanes(p, indices, count, dim, out);
    }

    // Optimised pair `pair` of sample `index` at pixel p: the key of the
    // pixel's tile entry, then the seed's digital shift.
    Vec2f point(int pair, Vec2i p, int index) const {
        const int mask = keys_->size - 1;
        const SobolBlueNoiseKey& key = keys_->at((p.x + offset_[size_t(pair)].x) & mask,
                                                 (p.y + offset_[size_t(pair)].y) & mask);
        const uint64_t xy = sobolBlueNoisePair(key, uint32_t(index)) ^ shift_[size_t(pair)];
        return {fixedPointToFloat(uint32_t(xy)), fixedPointToFloat(uint32_t(xy >> 32))};
    }
    const SobolBlueNoiseKeys& keys() const { return *keys_; }

  private:
    static constexpr int pairStartingAt(int d) {
        for (int j = 0; j < int(kPairStarts.size()); ++j)
            if (kPairStarts[size_t(j)] == d) return j;
        return -1;
    }
    static constexpr bool optimized(int d) {
        return pairStartingAt(d) >= 0 || pairStartingAt(d - 1) >= 0;
    }
    // Dimension d of the current sample, d optimised or not, drawn alone.
    float value(int d) {
        if (const int pair = pairStartingAt(d); pair >= 0) return point(pair, pixel_, index_).x;
        if (const int pair = pairStartingAt(d - 1); pair >= 0) return point(pair, pixel_, index_).y;
        fallback_.startPixelSample(pixel_, index_, d);
        return fallback_.get1D();
    }

    OwenSobolSampler fallback_;
    std::shared_ptr<const SobolBlueNoiseKeys> keys_;
    std::array<Vec2i, kPairStarts.size()> offset_{};    // tile offset per pair
    std::array<uint64_t, kPairStarts.size()> shift_{};  // digital shift per pair (y high)
    Vec2i pixel_{0, 0};
    int index_ = 0;
    int dimension_ = 0;
};

}  // namespace pathlab
