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
    }

    int samplesPerPixel() const { return spp_; }
    void startPixelSample(Vec2i p, int index, int dim) {
        pixel_ = p;
        index_ = static_cast<uint32_t>(index % spp_);
        dimension_ = dim;
        cursor_.seek(hashValues(p.x, p.y, seed_, 0x5354u), index, dim);
    }
    float get1D() {
        const uint32_t stratum = permutationElement(index_, spp_, strataHash());
        ++dimension_;
        return clampSample((stratum + cursor_.nextFloat()) / float(spp_));
    }
    Vec2f get2D() {
        const uint32_t stratum = permutationElement(index_, spp_, strataHash());
        dimension_ += 2;
        const int x = int(stratum) % xStrata_, y = int(stratum) / xStrata_;
        const float dx = cursor_.nextFloat(), dy = cursor_.nextFloat();
        return {clampSample((x + dx) / float(xStrata_)), clampSample((y + dy) / float(yStrata_))};
    }
    Vec2f getPixel2D() { return get2D(); }

    int xStrata() const { return xStrata_; }
    int yStrata() const { return yStrata_; }

  private:
    uint64_t strataHash() const { return hashValues(pixel_.x, pixel_.y, dimension_, seed_); }
    static float clampSample(float v) { return v < kOneMinusEpsilon ? v : kOneMinusEpsilon; }

    int spp_;
    uint64_t seed_;
    int xStrata_ = 1, yStrata_ = 1;
    Vec2i pixel_;
    uint32_t index_ = 0;
    int dimension_ = 0;
    PcgSampleCursor cursor_;
};

}  // namespace pathlab
