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

#include <vector>

#include "core/hash.h"
#include "sampling/lowdiscrepancy.h"
#include "sampling/pcg_cursor.h"
#include "sampling/pixel_dimension_cache.h"
#include "sampling/sampler.h"
#include "sampling/scramble_lanes.h"

namespace pathlab {

class StratifiedSampler {
  public:
    explicit StratifiedSampler(const SamplerConfig& c)
        : spp_(std::max(1, c.samplesPerPixel)), seed_(c.seed), strata_(uint32_t(spp_)) {
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
        if (spp_ <= kMaxTabulatedSpp) tables_.resize(size_t(kTabulatedDimensions) * size_t(spp_));
    }

    int samplesPerPixel() const { return spp_; }
    void startPixelSample(Vec2i p, int index, int dim) {
        setPixel(p);
        index_ = sampleInPixel(index);
        dimension_ = dim;
        cursor_.seek(pixelHash_, index, dim);
    }
    float get1D() {
        const uint32_t stratum = stratumOf(index_, dimension_);
        ++dimension_;
        return jittered1D(stratum, cursor_.nextFloat());
    }
    Vec2f get2D() {
        const uint32_t stratum = stratumOf(index_, dimension_);
        dimension_ += 2;
        const float dx = cursor_.nextFloat(), dy = cursor_.nextFloat();
        return jittered2D(stratum, dx, dy);
    }
    // Lane draws (sampler.h): each lane's stratum (lanesStrata), then its
    // jitter. They leave the sampler where the last lane's per-sample draw
    // would (sampler.h asks for no position: the Halton and Owen-scrambled
    // samplers' leave it at the first lane's).
    void get1DLanes(Vec2i p, const int* indices, int count, int dim, float* out) {
        uint32_t strata[kCameraPacketSamples];
        lanesStrata(p, indices, count, dim, strata);
        for (int j = 0; j < count; ++j) {
            cursor_.seek(pixelHash_, indices[j], dim);
            out[j] = jittered1D(strata[j], cursor_.nextFloat());
        }
        finishLanes(indices, count, dim + 1);
    }
    void get2DLanes(Vec2i p, const int* indices, int count, int dim, Vec2f* out) {
        uint32_t strata[kCameraPacketSamples];
        lanesStrata(p, indices, count, dim, strata);
        for (int j = 0; j < count; ++j) {
            cursor_.seek(pixelHash_, indices[j], dim);
            const float dx = cursor_.nextFloat(), dy = cursor_.nextFloat();
            out[j] = jittered2D(strata[j], dx, dy);
        }
        finishLanes(indices, count, dim + 2);
    }
    Vec2f getPixel2D() { return get2D(); }
    void getPixel2DLanes(Vec2i p, const int* indices, int count, Vec2f* out) {
        get2DLanes(p, indices, count, dims::kPixel, out);
    }

    int xStrata() const { return xStrata_; }
    int yStrata() const { return yStrata_; }

  private:
    void setPixel(Vec2i p) {
        if (p.x != pixel_.x || p.y != pixel_.y)
            pixel_ = p, pixelHash_ = hashValues(p.x, p.y, seed_, 0x5354u), strataHashes_.clear(),
            tableValid_ = 0;
    }
    // The renderer's indices are below spp already; the division is for others.
    uint32_t sampleInPixel(int index) const {
        if (unsigned(index) < unsigned(spp_)) return uint32_t(index);
        const int r = index % spp_;
        return uint32_t(r < 0 ? r + spp_ : r);
    }
    void finishLanes(const int* indices, int count, int nextDimension) {
        if (count > 0) index_ = sampleInPixel(indices[count - 1]), dimension_ = nextDimension;
    }
    // The permutation's seed for (pixel, dimension): four chained hash rounds,
    // the same for all of a pixel's samples.
    uint64_t strataHash(int dim) const { return hashValues(pixel_.x, pixel_.y, dim, seed_); }
    // strataHash for the untabulated dimensions, once per pixel and dimension.
    uint64_t cachedStrataHash(int dim) {
        return strataHashes_.get(dim, [&] { return strataHash(dim); });
    }
    // Sample `index`'s stratum in dimension `dim` of the current pixel. One
    // permutation element is a chain of four dependent multiplies, which a
    // draw would wait for; the first kTabulatedDimensions dimensions' whole
    // permutations are instead made the first time the pixel draws them, in
    // one SIMD loop (scramble_lanes.h), and read from the table after.
    uint32_t stratumOf(uint32_t index, int dim) {
        if (!tables_.empty() && unsigned(dim) < unsigned(kTabulatedDimensions)) {
            uint32_t* table = tables_.data() + size_t(dim) * size_t(spp_);
            if (!((tableValid_ >> dim) & 1)) {
                permutationTable(strata_, strataHash(dim), table);
                tableValid_ |= uint64_t(1) << dim;
            }
            return table[index];
        }
        return permutationElement(index, strata_, cachedStrataHash(dim));
    }
    // The lanes' strata: their permutation elements alone, side by side
    // (permutationLanes), where a table would compute all spp_ elements for a
    // dimension that, deeper in the paths, few of the pixel's samples draw.
    void lanesStrata(Vec2i p, const int* indices, int count, int dim, uint32_t* strata) {
        setPixel(p);
        uint32_t lanes[kCameraPacketSamples];
        for (int j = 0; j < kCameraPacketSamples; ++j)
            lanes[j] = j < count ? sampleInPixel(indices[j]) : 0;
        permutationLanes(strata_, cachedStrataHash(dim), lanes, strata);
    }
    float jittered1D(uint32_t stratum, float u) const {
        const float v = float(stratum) + u;
        return clampSample(powerOfTwo_ ? v * invSpp_ : v / float(spp_));
    }
    Vec2f jittered2D(uint32_t stratum, float dx, float dy) const {
        if (powerOfTwo_) {
            const auto x = float(stratum & uint32_t(xStrata_ - 1)), y = float(stratum >> xShift_);
            return {clampSample((x + dx) * invX_), clampSample((y + dy) * invY_)};
        }
        const int x = int(stratum) % xStrata_, y = int(stratum) / xStrata_;
        return {clampSample((x + dx) / float(xStrata_)), clampSample((y + dy) / float(yStrata_))};
    }
    static float clampSample(float v) { return v < kOneMinusEpsilon ? v : kOneMinusEpsilon; }

    int spp_;
    uint64_t seed_;
    PermutationDomain strata_;  // of the spp_ strata
    int xStrata_ = 1, yStrata_ = 1;
    bool powerOfTwo_ = false;
    int xShift_ = 0;
    float invSpp_ = 1, invX_ = 1, invY_ = 1;
    Vec2i pixel_{-1, -1};
    uint64_t pixelHash_ = 0;                      // of pixel_, for the jitter cursor
    PixelDimensionCache<uint64_t> strataHashes_;  // the untabulated dimensions' seeds
    // Up to kMaxTabulatedSpp samples per pixel (a table of 256 KB at most):
    // kTabulatedDimensions permutations of spp_ strata, tableValid_ bit d
    // when dimension d's is the current pixel's.
    static constexpr int kTabulatedDimensions = 64, kMaxTabulatedSpp = 1024;
    std::vector<uint32_t> tables_;
    uint64_t tableValid_ = 0;
    uint32_t index_ = 0;
    int dimension_ = 0;
    PcgSampleCursor cursor_;
};

}  // namespace pathlab
