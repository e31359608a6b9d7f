// `stratified`: jittered stratification per pixel (Cook 1986, "Stochastic
// Sampling in Computer Graphics"), padded across dimensions like pbrt-v4's
// StratifiedSampler. The N samples of a pixel are split into an nx × ny grid
// (nx the largest divisor of N not above √N, so N need not be a square); each
// 2D draw puts sample i into stratum π(i) of that grid, jittered uniformly
// inside it, and each 1D draw into one of N intervals. π is a fresh
// pseudo-random permutation per (pixel, dimension, seed), which decorrelates
// the dimensions ("padding", Kollig & Keller 2002) — so the sampler has no
// native dimension limit; only pairs are jointly stratified.
#pragma once

#include "core/hash.h"
#include "sampling/lowdiscrepancy.h"
#include "sampling/pcg_cursor.h"
#include "sampling/pixel_dimension_cache.h"
#include "sampling/sampler.h"

namespace pathlab {

class StratifiedSampler {
  public:
    explicit StratifiedSampler(const SamplerConfig& c)
        : spp_(std::max(1, c.samplesPerPixel)), seed_(c.seed) {
        int nx = 1;
        for (int d = 1; d * d <= spp_; ++d)
            if (spp_ % d == 0) nx = d;
        xStrata_ = nx;
        yStrata_ = spp_ / nx;
        // With N a power of two so are nx and ny: then a stratum's grid
        // position is a mask and a shift, and dividing by the strata counts is
        // multiplying by their exact reciprocals — the same bits without the
        // integer and float divisions.
        powerOfTwo_ = (spp_ & (spp_ - 1)) == 0;
        if (powerOfTwo_) {
            xShift_ = __builtin_ctz(unsigned(xStrata_));
            invSpp_ = 1.0f / float(spp_);
            invX_ = 1.0f / float(xStrata_);
            invY_ = 1.0f / float(yStrata_);
        }
    }

    int samplesPerPixel() const { return spp_; }
    void startPixelSample(Vec2i p, int index, int dim) {
        if (p.x != pixel_.x || p.y != pixel_.y)
            pixel_ = p, pixelHash_ = hashValues(p.x, p.y, seed_, 0x5354u), strataHashes_.clear();
        index_ = sampleInPixel(index);
        dimension_ = dim;
        cursor_.seek(pixelHash_, index, dim);
    }
    float get1D() {
        const uint32_t stratum = permutationElement(index_, spp_, strataHash());
        ++dimension_;
        const float v = float(stratum) + cursor_.nextFloat();
        return clampSample(powerOfTwo_ ? v * invSpp_ : v / float(spp_));
    }
    Vec2f get2D() {
        const uint32_t stratum = permutationElement(index_, spp_, strataHash());
        dimension_ += 2;
        return jitteredStratum(stratum);
    }
    Vec2f getPixel2D() { return get2D(); }

    // Lane draws (sampler.h): the dimension's permutation seed once for all
    // the lanes; each lane's stratum, then its jitter, as get1D / get2D.
    void get1DLanes(Vec2i p, const int* indices, int count, int dim, float* out) {
        startPixelSample(p, indices[0], dim);
        const uint64_t hash = strataHash();
        for (int j = 0; j < count; ++j) {
            const uint32_t stratum = permutationElement(sampleInPixel(indices[j]), spp_, hash);
            cursor_.seek(pixelHash_, indices[j], dim);
            const float v = float(stratum) + cursor_.nextFloat();
            out[j] = clampSample(powerOfTwo_ ? v * invSpp_ : v / float(spp_));
        }
        dimension_ = dim + 1;
    }
    void get2DLanes(Vec2i p, const int* indices, int count, int dim, Vec2f* out) {
        startPixelSample(p, indices[0], dim);
        const uint64_t hash = strataHash();
        for (int j = 0; j < count; ++j) {
            index_ = sampleInPixel(indices[j]);
            cursor_.seek(pixelHash_, indices[j], dim);
            out[j] = jitteredStratum(permutationElement(index_, spp_, hash));
        }
        dimension_ = dim + 2;
    }

    int xStrata() const { return xStrata_; }
    int yStrata() const { return yStrata_; }

  private:
    // A point jittered inside stratum `stratum` of the nx × ny grid.
    Vec2f jitteredStratum(uint32_t stratum) {
        const float dx = cursor_.nextFloat(), dy = cursor_.nextFloat();
        if (powerOfTwo_) {
            const auto x = float(stratum & uint32_t(xStrata_ - 1)), y = float(stratum >> xShift_);
            return {clampSample((x + dx) * invX_), clampSample((y + dy) * invY_)};
        }
        const int x = int(stratum) % xStrata_, y = int(stratum) / xStrata_;
        return {clampSample((x + dx) / float(xStrata_)), clampSample((y + dy) / float(yStrata_))};
    }
    // The permutation's seed for (pixel, dimension): four chained hash rounds,
    // the same for all of a pixel's samples.
    uint64_t strataHash() {
        return strataHashes_.get(dimension_,
                                 [&] { return hashValues(pixel_.x, pixel_.y, dimension_, seed_); });
    }
    // The sample's place among the pixel's spp_ (a mask when spp_ is a power of two).
    uint32_t sampleInPixel(int index) const {
        return powerOfTwo_ ? uint32_t(index) & uint32_t(spp_ - 1) : uint32_t(index % spp_);
    }
    static float clampSample(float v) { return v < kOneMinusEpsilon ? v : kOneMinusEpsilon; }

    int spp_;
    uint64_t seed_;
    int xStrata_ = 1, yStrata_ = 1;
    bool powerOfTwo_ = false;
    int xShift_ = 0;
    float invSpp_ = 1, invX_ = 1, invY_ = 1;
    Vec2i pixel_{-1, -1};
    uint64_t pixelHash_ = 0;  // of pixel_, for the jitter cursor
    PixelDimensionCache<uint64_t> strataHashes_;
    uint32_t index_ = 0;
    int dimension_ = 0;
    PcgSampleCursor cursor_;
};

}  // namespace pathlab
