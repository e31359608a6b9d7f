// `blue-noise`: the presentation's Blue Noise Sampler, and the generator of
// its texture.
//
// The texture is a dither array made by void-and-cluster (Ulichney 1993, "The
// void-and-cluster method for dither array generation", Proc. SPIE 1913): a
// Gaussian-filtered (σ = 1.5, toroidal) energy picks, one pixel at a time, the
// tightest cluster to remove or the largest void to fill; the order in which
// pixels are filled is their rank. Every rank 0..S²−1 appears exactly once, so
// values (rank + ½)/S² are uniform, and any threshold of the array is a
// blue-noise point set: its spectrum has little energy at low frequencies.
// Generation takes about a second for 128²; the texture is cached in
// cacheDirectory() (written atomically, checked when read) and shared.
//
// Lookup (the presentation's BlueNoiseRand): dimension d of sample i at pixel
// (x, y) reads texel
//   row = (y + D·100937 + i·1091 + depth·133337) mod S,
//   col = (x + D·99523  + i·2399 + depth·2549)   mod S,
// where depth is the path vertex the dimension belongs to (0 for the pixel
// dimensions and the first vertex) and D the dimension's place within its
// block (0,1 for the pixel, 2..8 within a vertex block) — see sampler.h.
// The seed adds a toroidal offset to the lookup and a Cranley–Patterson
// rotation (Cranley & Patterson 1976) per dimension; the rotation makes every
// dimension, and every pair, exactly uniform over seeds — so the estimator is
// unbiased — while each dimension keeps the texture's spatial blue-noise
// spectrum. The presentation's lookup cycles through only S texels as the
// sample index grows (1091 and 2399 are odd, so i ↦ (1091 i, 2399 i) mod S has
// period S): every further block of S samples gets a fresh rotation, so the
// estimate keeps converging past S samples per pixel. Any number of dimensions.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <filesystem>
#include <memory>
#include <vector>

#include "core/hash.h"
#include "sampling/lowdiscrepancy.h"
#include "sampling/sampler.h"

namespace pathlab {

struct BlueNoiseTexture {
    int size = 0;
    std::vector<uint32_t> rank;  // row-major, a permutation of 0..size²−1
    // The value of a texel as a 32-bit fixed-point fraction: (rank + ½) / size².
    std::vector<uint32_t> fixedPoint;
    void computeValues();
    float value(int x, int y) const { return fixedPointToFloat(fixedPoint[size_t(y) * size + x]); }
};

// Void-and-cluster on a size × size torus; deterministic for a given seed.
BlueNoiseTexture generateBlueNoiseTexture(int size, uint64_t seed, double sigma = 1.5);

// Reads `file` if it holds a valid texture of this size, else generates one
// and writes it atomically (a temporary file renamed into place).
std::shared_ptr<const BlueNoiseTexture> loadOrCreateBlueNoiseTexture(
    const std::filesystem::path& file, int size, uint64_t seed);

inline constexpr int kBlueNoiseTextureSize = 128;
// The process-wide texture: cacheDirectory()/blue-noise-vc-128.bin.
std::shared_ptr<const BlueNoiseTexture> defaultBlueNoiseTexture();

namespace blue_noise {
// What dimension d adds to the lookup's row and column: its place D in its
// block and the vertex it belongs to, times the presentation's constants.
struct LayoutTerms {
    uint64_t row, col;
};
constexpr LayoutTerms layoutTerms(int d) {
    const int vertex = dims::depthOfDimension(d);
    const uint64_t depth = uint64_t(vertex < 0 ? 0 : vertex);
    const uint64_t inBlock =
        d < dims::kFirstBounce
            ? uint64_t(d)
            : uint64_t(dims::kFirstBounce + (d - dims::kFirstBounce) % dims::kDimsPerBounce);
    return {inBlock * 100937 + depth * 133337, inBlock * 99523 + depth * 2549};
}
// A path of depth 8 draws 58 dimensions: the first 64 are tabulated.
inline constexpr int kCachedDimensions = 64;
inline constexpr std::array<LayoutTerms, kCachedDimensions> kLayoutTerms = [] {
    std::array<LayoutTerms, kCachedDimensions> t{};
    for (int d = 0; d < kCachedDimensions; ++d) t[size_t(d)] = layoutTerms(d);
    return t;
}();
}  // namespace blue_noise

class BlueNoiseSampler {
  public:
    explicit BlueNoiseSampler(const SamplerConfig& c)
        : spp_(c.samplesPerPixel), seed_(c.seed), texture_(defaultBlueNoiseTexture()) {
        const uint64_t h = hashValues(c.seed, 0x424eu);
        offsetX_ = static_cast<uint32_t>(h % uint64_t(texture_->size));
        offsetY_ = static_cast<uint32_t>((h >> 32) % uint64_t(texture_->size));
        const uint64_t size = uint64_t(texture_->size);
        sizeMask_ = (size & (size - 1)) == 0 ? size - 1 : 0;
        std::fill(std::begin(rotationBlock_), std::end(rotationBlock_), ~uint64_t(0));
    }

    int samplesPerPixel() const { return spp_; }
    void startPixelSample(Vec2i p, int index, int dim) {
        pixel_ = p;
        index_ = static_cast<uint64_t>(index);
        dimension_ = dim;
    }
    float get1D() { return sampleDimension(dimension_++); }
    Vec2f get2D() {
        const int d = dimension_;
        dimension_ += 2;
        return {sampleDimension(d), sampleDimension(d + 1)};
    }
    Vec2f getPixel2D() { return get2D(); }

    // The lookup above, computed from scratch: what the draws must equal.
    float definition(Vec2i pixel, uint64_t index, int d) const {
        const blue_noise::LayoutTerms t = blue_noise::layoutTerms(d);
        return lookup(pixel, index, t, rotation(d, block(index)));
    }

  private:
    // Which block of `size` samples index lies in: each gets its own rotation.
    uint64_t block(uint64_t index) const {
        return sizeMask_ ? index >> std::countr_zero(uint64_t(texture_->size))
                         : index / uint64_t(texture_->size);
    }
    uint32_t rotation(int d, uint64_t block) const {
        return foldSeed(hashValues(seed_, d, block, 0x4350u));
    }
    float lookup(Vec2i pixel, uint64_t index, blue_noise::LayoutTerms t, uint32_t rotation) const {
        const uint64_t x = uint64_t(uint32_t(pixel.x)) + offsetX_;
        const uint64_t y = uint64_t(uint32_t(pixel.y)) + offsetY_;
        const uint64_t row = wrap(y + t.row + index * 1091);
        const uint64_t col = wrap(x + t.col + index * 2399);
        return fixedPointToFloat(texture_->fixedPoint[row * uint64_t(texture_->size) + col] +
                                 rotation);
    }
    // A path of depth 8 draws 58 dimensions: their layout terms are a table,
    // and their rotations (four chained hashes) are kept while the sample
    // index stays in one block — for all of a pixel's first `size` samples.
    static constexpr int kCachedDimensions = blue_noise::kCachedDimensions;
    float sampleDimension(int d) {
        if (d >= kCachedDimensions) return definition(pixel_, index_, d);
        const uint64_t b = block(index_);
        if (rotationBlock_[d] != b) rotationBlock_[d] = b, rotation_[d] = rotation(d, b);
        return lookup(pixel_, index_, blue_noise::kLayoutTerms[size_t(d)], rotation_[d]);
    }
    uint32_t rotation_[kCachedDimensions] = {};
    uint64_t rotationBlock_[kCachedDimensions];  // ~0: not yet computed

    int spp_;
    uint64_t seed_;
    std::shared_ptr<const BlueNoiseTexture> texture_;
    // v mod size: a mask for the power-of-two sizes (the default 128), which
    // saves two 64-bit divisions per dimension.
    uint64_t wrap(uint64_t v) const {
        return sizeMask_ ? v & sizeMask_ : v % uint64_t(texture_->size);
    }
    uint32_t offsetX_ = 0, offsetY_ = 0;
    uint64_t sizeMask_ = 0;  // size − 1 when size is a power of two, else 0
    Vec2i pixel_;
    uint64_t index_ = 0;
    int dimension_ = 0;
};

}  // namespace pathlab
