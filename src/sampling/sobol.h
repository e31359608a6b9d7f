// The Sobol' samplers: `sobol`, `sobol-xor`, `sobol-global-owen`, `sobol-owen`
// and `zsobol`.
//
// `sobol` / `sobol-xor` / `sobol-global-owen` — one global Sobol' sequence over the whole image
// (pbrt-v4's SobolSampler). Dimensions 0 and 1 cover the image scaled to the
// next power of two 2^m ≥ max(width, height); the first 2^{2m} points of a
// (0,2)-sequence put exactly one point in every 2^-m × 2^-m square, so the
// indices whose first two coordinates fall into pixel p are found by solving a
// 2m × 2m linear system over GF(2) once (SobolImageMapping). Every other
// dimension d is Sobol' dimension d of the same index, up to the 3667
// dimensions of the Joe–Kuo table in Boost; past them dimensions wrap to 2.
// Sample indices follow the Gray code (Antonov & Saleev 1979), which is the
// order in which the sequence is usually listed: (0,0), (.5,.5), (.75,.25),
// (.25,.75), … — any 2^k consecutive aligned Gray indices are the same set.
// `sobol-xor` applies a random digital shift seeded per dimension;
// `sobol-global-owen` a nested uniform (Owen) scramble seeded per dimension
// (Owen 1995; the hash-based form of Burley 2020), as pbrt-v4's SobolSampler
// does by default ("fastowen"). Both scramble dimensions 2 and up only, the
// same way in every pixel; the pixel dimensions stay as the mapping put them.
//
// `sobol-owen` — Burley 2020 ("Practical Hash-based Owen Scrambling", JCGT
// 9(4), §4 "padding"): every 2D draw is the first two Sobol' dimensions — a
// (0,2)-sequence — at a shuffled index, Owen-scrambled with seeds hashed from
// (pixel, dimension, seed). The index shuffle is itself a nested (Owen)
// scramble of the index bits, which maps aligned blocks of 2^k indices to
// aligned blocks, so any power-of-two prefix of a pixel's samples is still a
// (0,k,2)-net in every pair. Dimension pairs are independent of each other:
// "padding" (Kollig & Keller 2002) with unbounded dimensions.
//
// `zsobol` — Ahmed & Wonka 2020, "Screen-Space Blue-Noise Diffusion of Monte
// Carlo Sampling Error via Hierarchical Ordering of Pixels" (SIGGRAPH Asia),
// as pbrt-v4's ZSobolSampler: the sample's global index is the pixel's Morton
// code followed by the sample index, and its base-4 digits are permuted from
// the most significant down, each digit's permutation chosen by hashing the
// digits above it and the dimension. Pixels close on the Z curve therefore take
// consecutive, well-stratified Sobol' points, so their errors are negatively
// correlated — the error image is blue noise. Each 2D draw uses Sobol'
// dimensions 0 and 1 with Owen scrambling seeded per dimension.
#pragma once

#include <algorithm>
#include <array>
#include <memory>
#include <vector>

#include "sampling/lowdiscrepancy.h"
#include "sampling/pixel_dimension_cache.h"
#include "sampling/sampler.h"
#include "sampling/scramble_lanes.h"

namespace pathlab {

// Which indices of a global Sobol' sequence fall into which pixel.
struct SobolImageMapping {
    int log2Scale = 0;          // m
    uint64_t inverse[32] = {};  // columns of the inverse of the 2m × 2m map
    explicit SobolImageMapping(const uint32_t* matrices, Vec2i resolution);
    // The Gray-coded Sobol' index of sample `frame` of pixel p.
    uint64_t index(const uint32_t* matrices, Vec2i p, uint64_t frame) const;
};

enum class SobolScrambling { None, Xor, Owen };

template <SobolScrambling kScrambling>
class GlobalSobolSamplerT {
  public:
    explicit GlobalSobolSamplerT(const SamplerConfig& c)
        : spp_(c.samplesPerPixel),
          seed_(c.seed),
          matrices_(sobolMatrices()),
          nibbleTables_(sobolNibbleTables()),
          mapping_(std::make_shared<const SobolImageMapping>(matrices_, c.resolution)) {
        if constexpr (kScrambling != SobolScrambling::None)
            for (int d = 0; d < kSobolNibbleDimensions; ++d)
                scrambleSeeds_[size_t(d)] = scrambleSeedOf(d);
    }

    int samplesPerPixel() const { return spp_; }
    void startPixelSample(Vec2i p, int index, int dim) {
        // A path restarts at every vertex with the same pixel sample, and the
        // renderer first draws the camera rays of kRecentIndices samples (a
        // batch), then their paths: the image mapping is inverted once per
        // pixel sample, and the last kRecentIndices results are kept (slot
        // index mod kRecentIndices).
        if (p.x != pixel_.x || p.y != pixel_.y) pixel_ = p, index_ = -1, recentIndex_.fill(-1);
        if (index != index_) {
            index_ = index;
            const auto slot = size_t(index) % kRecentIndices;
            if (recentIndex_[slot] != index) {
                recentIndex_[slot] = index;
                recentSobolIndex_[slot] = mapping_->index(matrices_, p, uint64_t(index));
            }
            sobolIndex_ = recentSobolIndex_[slot];
        }
        dimension_ = std::max(2, dim);
    }
    float get1D() { return sampleDimension(dimension_++); }
    Vec2f get2D() {
        const int d = dimension_;
        dimension_ += 2;
        return {sampleDimension(d), sampleDimension(d + 1)};
    }
    // The bits of dimensions 0 and 1 below the image-scale bits: the position
    // inside the pixel. Left unscrambled (scrambling them would move samples
    // to other pixels), as in pbrt-v4.
    Vec2f getPixel2D() {
        const int m = mapping_->log2Scale;
        const uint32_t x = sobolBits(matrices_, sobolIndex_, 0);
        const uint32_t y = sobolBits(matrices_, sobolIndex_, 1);
        return {fixedPointToFloat(m == 0 ? x : x << m), fixedPointToFloat(m == 0 ? y : y << m)};
    }

    // Dimension d of the current index: its value and its scramble's seed
    // come from tables for the first kSobolNibbleDimensions dimensions (the
    // same bits: tested against sampleDimensionByDefinition).
    float sampleDimension(int d) const {
        if (d < kSobolNibbleDimensions) {
            const uint32_t v = sobolBitsByNibbles(nibbleTables_[d],
                                                  matrices_ + d * kSobolMatrixColumns, sobolIndex_);
            return fixedPointToFloat(scramble(v, scrambleSeeds_[size_t(d)]));
        }
        return sampleDimensionByDefinition(d);
    }

  public:
    float sampleDimensionByDefinition(int d) const {
        const int wrapped = d < kSobolDimensions ? d : 2 + (d - 2) % (kSobolDimensions - 2);
        const uint32_t v = sobolBits(matrices_, sobolIndex_, wrapped);
        return fixedPointToFloat(scramble(v, scrambleSeedOf(d)));
    }

  private:
    static uint32_t scramble(uint32_t v, uint32_t seed) {
        if constexpr (kScrambling == SobolScrambling::Xor) return xorScramble(v, seed);
        if constexpr (kScrambling == SobolScrambling::Owen) return owenScramble(v, seed);
        return v;
    }
    // Seeded per dimension (the tags keep sobol-xor's shifts as they were).
    uint32_t scrambleSeedOf(int d) const {
        if constexpr (kScrambling == SobolScrambling::Owen)
            return foldSeed(hashValues(d, seed_, 0x4f57454eu));
        return foldSeed(hashValues(d, seed_, 0x584f52u));
    }

    int spp_;
    uint64_t seed_;
    const uint32_t* matrices_;
    const SobolNibbleTable* nibbleTables_;
    std::array<uint32_t, kSobolNibbleDimensions> scrambleSeeds_{};  // by dimension
    std::shared_ptr<const SobolImageMapping> mapping_;
    static constexpr size_t kRecentIndices = kBatchSamples;
    Vec2i pixel_{-1, -1};
    int index_ = -1;
    uint64_t sobolIndex_ = 0;
    std::array<int, kRecentIndices> recentIndex_{};  // of pixel_, reset to −1 (empty) per pixel
    std::array<uint64_t, kRecentIndices> recentSobolIndex_{};
    int dimension_ = 0;
};

using SobolSampler = GlobalSobolSamplerT<SobolScrambling::None>;
using XorSobolSampler = GlobalSobolSamplerT<SobolScrambling::Xor>;
using GlobalOwenSobolSampler = GlobalSobolSamplerT<SobolScrambling::Owen>;

// `sobol-owen`: padded, shuffled, Owen-scrambled Sobol' (Burley 2020).
class OwenSobolSampler {
  public:
    explicit OwenSobolSampler(const SamplerConfig& c)
        : spp_(c.samplesPerPixel), seed_(c.seed), matrices_(sobolMatrices()) {}

    int samplesPerPixel() const { return spp_; }
    void startPixelSample(Vec2i p, int index, int dim) {
        // A path repositions several times per vertex: hash a pixel once, and
        // forget the dimensions' seeds of the pixel before.
        if (p.x != pixel_.x || p.y != pixel_.y)
            pixel_ = p, pixelHash_ = pixelHash(p, seed_), seeds1D_.clear(), seeds2D_.clear();
        // The index's reversal, which the index scramble starts from, once
        // per sample rather than once per draw.
        if (static_cast<uint32_t>(index) != index_)
            index_ = static_cast<uint32_t>(index), reversedIndex_ = reverseBits32(index_);
        dimension_ = dim;
    }
    // By definition (Burley 2020): the index shuffled by a nested scramble of
    // its bits, i = O_h(index), then x = O_sx(C_0 i), y = O_sy(C_1 i) — see
    // definition1D/2D. With O_s(v) = R(L_s(R(v))) (R the bit reversal, L_s
    // the Laine–Karras permutation), C_0 = R and C_1 = R∘Z (Z the superset
    // transform of sobolSecondDimension), the reversals that meet cancel:
    // i = R(L_h(R(index))), x = R(L_sx(i)), y = R(L_sy(Z(i))) — four
    // reversals per pair instead of eight, the same bits; R(index) is kept
    // per sample, and the last two are one 64-bit reversal (reverseBits32Pair).
    // The seeds depend on the pixel and the dimension only, so they are kept
    // for the pixel's other samples (PixelDimensionCache).
    float get1D() {
        const Seeds k = seeds(dimension_++, 0x31, seeds1D_);
        const uint32_t i = reverseBits32(laineKarrasPermutation(reversedIndex_, k.index));
        return fixedPointToFloat(reverseBits32(laineKarrasPermutation(i, foldSeed(k.values))));
    }
    Vec2f get2D() {
        const Seeds k = seeds(dimension_, 0x32, seeds2D_);
        dimension_ += 2;
        const uint32_t i = reverseBits32(laineKarrasPermutation(reversedIndex_, k.index));
        const uint64_t xy = reverseBits32Pair(
            laineKarrasPermutation(i, uint32_t(k.values)),
            laineKarrasPermutation(uint32_t(sobolSupersetTransform(i)), uint32_t(k.values >> 32)));
        return {fixedPointToFloat(uint32_t(xy)), fixedPointToFloat(uint32_t(xy >> 32))};
    }
    // The definitions the draws above must equal (for tests): dimension `dim`
    // of sample `index` for a pixel whose hash is `pixelHash`.
    static float definition1D(uint64_t pixelHash, uint32_t index, int dim) {
        const uint64_t h = mixBits(pixelHash ^ (uint64_t(dim) << 40 | 0x31));
        const uint32_t i = owenScramble(index, static_cast<uint32_t>(h));
        return fixedPointToFloat(
            owenScramble(sobolBits(sobolMatrices(), i, 0), foldSeed(mixBits(h))));
    }
    static Vec2f definition2D(uint64_t pixelHash, uint32_t index, int dim) {
        const uint64_t h = mixBits(pixelHash ^ (uint64_t(dim) << 40 | 0x32));
        const uint32_t i = owenScramble(index, static_cast<uint32_t>(h));
        const uint64_t s = mixBits(h);
        return {
            fixedPointToFloat(owenScramble(sobolBits(sobolMatrices(), i, 0), uint32_t(s))),
            fixedPointToFloat(owenScramble(sobolBits(sobolMatrices(), i, 1), uint32_t(s >> 32)))};
    }
    static uint64_t pixelHash(Vec2i p, uint64_t seed) { return hashValues(p.x, p.y, seed); }
    Vec2f getPixel2D() { return get2D(); }
    void getPixel2DLanes(Vec2i p, const int* indices, int count, Vec2f* out) {
        get2DLanes(p, indices, count, dims::kPixel, out);
    }

    // Lane draws (sampler.h): the dimension's seeds once for all the lanes,
    // the lanes' bit operations side by side (scramble_lanes.h). The side by
    // side kernel does all eight lanes; one or two live lanes are cheaper
    // drawn one by one.
    void get1DLanes(Vec2i p, const int* indices, int count, int dim, float* out) {
        if (count <= kFewLanes) return drawEachLane1D(*this, p, indices, count, dim, out);
        startPixelSample(p, indices[0], dim);
        const Seeds k = seeds(dim, 0x31, seeds1D_);
        uint32_t index[kCameraPacketSamples];
        padLanes(indices, count, index);
        float x[kCameraPacketSamples];
        owenSobolLanes1D(index, k.index, foldSeed(k.values), x);
        for (int j = 0; j < count; ++j) out[j] = x[j];
        dimension_ = dim + 1;
    }
    void get2DLanes(Vec2i p, const int* indices, int count, int dim, Vec2f* out) {
        if (count <= kFewLanes) return drawEachLane2D(*this, p, indices, count, dim, out);
        startPixelSample(p, indices[0], dim);
        const Seeds k = seeds(dim, 0x32, seeds2D_);
        uint32_t index[kCameraPacketSamples];
        padLanes(indices, count, index);
        float x[kCameraPacketSamples], y[kCameraPacketSamples];
        owenSobolLanes2D(index, k.index, uint32_t(k.values), uint32_t(k.values >> 32), x, y);
        for (int j = 0; j < count; ++j) out[j] = {x[j], y[j]};
        dimension_ = dim + 2;
    }

  private:
    static constexpr int kFewLanes = 2;
    // h = mixBits(pixel hash, dimension, tag) scrambles the index (its low 32
    // bits) and mixBits(h) seeds the output scrambles.
    struct Seeds {
        uint32_t index = 0;
        uint64_t values = 0;
    };
    Seeds seeds(int d, uint64_t tag, PixelDimensionCache<Seeds>& cache) const {
        return cache.get(d, [&] {
            const uint64_t h = mixBits(pixelHash_ ^ (uint64_t(d) << 40 | tag));
            return Seeds{static_cast<uint32_t>(h), mixBits(h)};
        });
    }

    int spp_;
    uint64_t seed_;
    const uint32_t* matrices_;
    Vec2i pixel_{-1, -1};
    uint64_t pixelHash_ = 0;
    uint32_t index_ = 0;
    uint32_t reversedIndex_ = 0;  // reverseBits32(index_)
    int dimension_ = 0;
    PixelDimensionCache<Seeds> seeds1D_, seeds2D_;
};

namespace zsobol {
// The 24 permutations of {0,1,2,3}, as base-4 digits packed into a byte.
inline constexpr uint8_t kDigitPermutations[24] = {0xe4, 0xb4, 0xd8, 0x78, 0x9c, 0x6c, 0xe1, 0xb1,
                                                   0xc9, 0x39, 0x8d, 0x2d, 0xd2, 0x72, 0xc6, 0x36,
                                                   0x4e, 0x1e, 0x93, 0x63, 0x87, 0x27, 0x4b, 0x1b};
// The permutation that the digits above a digit (`higherDigits`) and the
// dimension's salt choose, packed as in kDigitPermutations.
inline uint8_t digitPermutation(uint64_t higherDigits, uint64_t salt) {
    return kDigitPermutations[(mixBits(higherDigits ^ salt) >> 24) % 24];
}
// Base-4 digit `digit` of a Morton index, permuted by that permutation.
inline unsigned permuteDigit(unsigned digit, uint64_t higherDigits, uint64_t salt) {
    return (digitPermutation(higherDigits, salt) >> (2 * digit)) & 3;
}
// out[n] = digitPermutation(first | n, salt) for n in [0, count), count a
// multiple of 8 and first's low log2(count) bits zero: a level of a pixel's
// low-digit tree, its hashes side by side (eight 64-bit lanes with AVX-512
// DQ and VBMI). `limit` caps the instruction set (tests run each one).
void digitPermutations(uint64_t first, uint64_t salt, uint32_t count, uint8_t* out,
                       SimdLevel limit = SimdLevel::Avx512Vbmi);
}  // namespace zsobol

// `zsobol`: Morton-ordered, base-4-digit-permuted, Owen-scrambled Sobol'.
class ZSobolSampler {
  public:
    explicit ZSobolSampler(const SamplerConfig& c);

    int samplesPerPixel() const { return spp_; }
    void startPixelSample(Vec2i p, int index, int dim) {
        if (p.x != pixel_.x || p.y != pixel_.y)
            pixel_ = p, pixelMorton_ = encodeMorton2(uint32_t(p.x), uint32_t(p.y)) << log2Spp_;
        mortonIndex_ = pixelMorton_ | uint64_t(index);
        // The digits above the sample index's bits are the pixel's: their
        // permuted values stay cached while those bits stay the same.
        const uint64_t high = mortonIndex_ >> log2Spp_;
        if (high != cachedHigh_) cachedHigh_ = high, cacheValid_ = 0;
        dimension_ = dim;
    }
    float get1D() {
        const int d = dimension_++;
        if (d >= kCachedDimensions) {
            const uint32_t seed = foldSeed(hashValues(d, seed_, 0x5a31u));
            return fixedPointToFloat(
                owenScramble(sobolBits(matrices_, referenceSampleIndex(d), 0), seed));
        }
        CachedDimension& c = cached(d);
        // Sobol' dimension 0 is the bit reversal, which owenScramble undoes:
        // owenScramble(reverse(i), s) = reverse(laineKarras(i, s)).
        const uint32_t index = uint32_t(c.highIndex | lowDigits(d, c));
        return fixedPointToFloat(reverseBits32(laineKarrasPermutation(index, c.seed1D)));
    }
    Vec2f get2D() {
        const int d = dimension_;
        dimension_ += 2;
        if (d >= kCachedDimensions) {
            const uint64_t index = referenceSampleIndex(d);
            const uint64_t seeds = hashValues(d, seed_, 0x5a32u);
            return {
                fixedPointToFloat(owenScramble(sobolBits(matrices_, index, 0), uint32_t(seeds))),
                fixedPointToFloat(
                    owenScramble(sobolBits(matrices_, index, 1), uint32_t(seeds >> 32)))};
        }
        CachedDimension& c = cached(d);
        return scrambled2D(d, c, lowDigits(d, c));
    }
    Vec2f getPixel2D() { return get2D(); }
    void getPixel2DLanes(Vec2i p, const int* indices, int count, Vec2f* out) {
        get2DLanes(p, indices, count, dims::kPixel, out);
    }

    // Lane draws (sampler.h): the dimension's cache entry once for the live
    // paths, their low digits lane after lane (each lane's last-level node is
    // usually the lane before's), then their scrambles side by side in SIMD
    // lanes (scramble_lanes.h). One or two live paths are cheaper drawn one
    // by one.
    void get1DLanes(Vec2i p, const int* indices, int count, int dim, float* out) {
        if (count <= kFewLanes || !lanesCached(indices, count, dim))
            return drawEachLane1D(*this, p, indices, count, dim, out);
        startPixelSample(p, indices[0], dim);
        CachedDimension& c = cached(dim);
        uint32_t index[kCameraPacketSamples] = {};
        if (tabulated(dim)) {
            const uint16_t* low = lowTable_.data() + tableRow(dim);
            for (int j = 0; j < count; ++j) index[j] = uint32_t(c.highIndex) | low[indices[j]];
        } else {
            for (int j = 0; j < count; ++j)
                index[j] = uint32_t(c.highIndex | laneLowDigits(c, dim, indices[j]));
        }
        float x[kCameraPacketSamples];
        owenScrambleReversedLanes(index, c.seed1D, x);
        for (int j = 0; j < count; ++j) out[j] = x[j];
        dimension_ = dim + 1;
    }
    void get2DLanes(Vec2i p, const int* indices, int count, int dim, Vec2f* out) {
        if (count <= kFewLanes || !lanesCached(indices, count, dim))
            return drawEachLane2D(*this, p, indices, count, dim, out);
        startPixelSample(p, indices[0], dim);
        CachedDimension& c = cached(dim);
        uint32_t index[kCameraPacketSamples] = {}, reversed1[kCameraPacketSamples] = {};
        if (tabulated(dim)) {
            // Two loads per lane from the pixel's tables, no member written.
            const uint16_t* low = lowTable_.data() + tableRow(dim);
            const uint32_t* lowSobol1 = lowSobol1_.data() + tableRow(dim);
            const auto high = uint32_t(c.highIndex);
            for (int j = 0; j < count; ++j) {
                index[j] = high | low[indices[j]];
                reversed1[j] = c.reversedSobol1High ^ lowSobol1[indices[j]];
            }
        } else {
            for (int j = 0; j < count; ++j) {
                const uint64_t low = laneLowDigits(c, dim, indices[j]);
                index[j] = uint32_t(c.highIndex | low);
                reversed1[j] = lowReversedSobol1(dim, c, low);
            }
        }
        float xy[2 * kCameraPacketSamples];
        owenScrambleReversedLanes2D(index, reversed1, c.seeds2D[0], c.seeds2D[1], xy);
        for (int j = 0; j < count; ++j) out[j] = {xy[2 * j], xy[2 * j + 1]};
        dimension_ = dim + 2;
    }

    // The permuted global index for the current pixel sample in `dimension`
    // (Ahmed & Wonka 2020, §4: random permutation of each base-4 digit chosen
    // by the digits above it), computed digit by digit from the top. The
    // draws compute the same value from a per-pixel cache (tested bit-identical).
    uint64_t referenceSampleIndex(int dimension) const;
    // The value the draws use.
    uint64_t sampleIndex(int dimension) {
        if (dimension >= kCachedDimensions) return referenceSampleIndex(dimension);
        CachedDimension& c = cached(dimension);
        return c.highIndex | lowDigits(dimension, c);
    }

  private:
    // A path of depth 8 draws 58 dimensions; deeper ones are computed uncached.
    static constexpr int kCachedDimensions = 64;
    struct CachedDimension {
        // Per dimension, for every pixel: the digit hashes' salt and the Owen seeds.
        uint64_t salt = 0;
        uint32_t seed1D = 0;
        uint32_t seeds2D[2] = {0, 0};
        // Per pixel: the permuted digits above the sample-index bits and the
        // (bit-reversed) Sobol' dimension 1 of them.
        uint64_t highIndex = 0;
        uint32_t reversedSobol1High = 0;
        // The pixel's Morton code they were computed for (~0: none yet).
        uint64_t highMorton = ~uint64_t(0);
        // The last draw's node of the tree's last level (see lowDigits): its
        // parent's number (~0: none yet in this pixel), the permuted digits
        // above it and its permutation (or flip bit).
        uint64_t lastParent = ~uint64_t(0);
        uint64_t lastPrefix = 0;
        uint8_t lastPermutation = 0;
    };
    CachedDimension& cached(int d) {
        CachedDimension& c = cache_[size_t(d)];
        if (!((cacheValid_ >> d) & 1)) {
            fillHighDigits(c);
            c.lastParent = ~uint64_t(0);
            if (tabulated(d))
                fillLowTable(d, c.salt);
            else if (lowNodes_ > 0)
                std::fill_n(lowPermutations_.begin() + d * lowNodes_, lowNodes_, kUnset);
            cacheValid_ |= uint64_t(1) << d;
        }
        return c;
    }
    void fillHighDigits(CachedDimension& c) const;
    void fillLowTable(int d, uint64_t salt);
    // Lane draws share the dimension's cache entry and the pixel's high
    // digits: a cached dimension, every index inside the pixel's samples.
    bool lanesCached(const int* indices, int count, int dim) const {
        if (dim >= kCachedDimensions) return false;
        for (int j = 0; j < count; ++j)
            if (unsigned(indices[j]) >= unsigned(spp_)) return false;
        return true;
    }
    static constexpr int kFewLanes = 2;
    uint64_t laneLowDigits(CachedDimension& c, int dim, int index) {
        mortonIndex_ = pixelMorton_ | uint64_t(index);
        return lowDigits(dim, c);
    }
    // Sobol' dimension 1 of the permuted index, bit-reversed. It is linear
    // over GF(2) and the high and low index bits are disjoint, so its value
    // is the cached high part XOR the low part. The low part a byte at a
    // time from tables: a loop over its set bits would end at an
    // unpredictable count.
    uint32_t reversedSobol1(const CachedDimension& c, uint64_t low) const {
        uint32_t reversed1 = c.reversedSobol1High ^ reversedSobol1Bytes_[low & 0xff] ^
                             reversedSobol1Bytes_[256 + ((low >> 8) & 0xff)] ^
                             reversedSobol1Bytes_[512 + ((low >> 16) & 0xff)];
        if (low >> 24) reversed1 ^= reverseBits32(sobolBits(matrices_, low >> 24 << 24, 1));
        return reversed1;
    }
    // The same; where the low digits are tabulated, their part of it is too,
    // by sample: one load, not one that waits for the load of the low digits.
    uint32_t lowReversedSobol1(int d, const CachedDimension& c, uint64_t low) const {
        if (!tabulated(d)) return reversedSobol1(c, low);
        return c.reversedSobol1High ^ lowSobol1_[tableSlot(d)];
    }
    // Dimensions d, d + 1 from the permuted index's low digits (both kept
    // bit-reversed, as owenScramble wants them).
    Vec2f scrambled2D(int d, const CachedDimension& c, uint64_t low) const {
        const uint64_t xy =
            reverseBits32Pair(laineKarrasPermutation(uint32_t(c.highIndex | low), c.seeds2D[0]),
                              laineKarrasPermutation(lowReversedSobol1(d, c, low), c.seeds2D[1]));
        return {fixedPointToFloat(uint32_t(xy)), fixedPointToFloat(uint32_t(xy >> 32))};
    }
    // The permuted digits below the pixel's: the ⌈log2 spp / 2⌉ digits that
    // change from sample to sample (same loop as referenceSampleIndex's). A
    // digit's permutation depends on the digits above it only, so for one
    // pixel the low digits form a tree of 1 + 4 + 16 + … nodes (and a last
    // level of single bits for an odd log2 spp): each node's permutation is
    // hashed when a sample first reaches it and kept in lowPermutations_ for
    // the pixel's other samples — at 256 spp 85 hashes per dimension and pixel
    // instead of four per draw.
    //
    // The renderer draws a dimension for a pixel's samples in order, so most
    // draws fall into the same node of the last level as the draw before
    // (samples 4k … 4k + 3 share one, or 2k, 2k + 1 for an odd log2 spp): that
    // node's permutation and the digits above it are kept per dimension, and
    // such a draw reads one digit instead of walking the tree from the root.
    //
    // The check for the last draw's node is inlined into the draws; the walk
    // from the root is not.
    //
    // Up to 256 spp, the dimensions that nearly every sample draws (the first
    // three vertices') read their low digits from a per-pixel table instead,
    // made from the whole tree the first time the pixel draws the dimension
    // (fillLowTable): 2.5% off a Cornell-box frame against walking for them
    // too, where the walks' hashes waited for each other.
    [[gnu::always_inline]] uint64_t lowDigits(int d, CachedDimension& c) {
        if (tabulated(d)) return lowTable_[tableSlot(d)];
        const int odd = log2Spp_ & 1;
        if (lowNodes_ == 0) return lowDigitsUncached(c.salt);
        const uint64_t sample = sampleBits();
        const int lastBits = odd ? 1 : 2;
        if ((sample >> lastBits) == c.lastParent)
            return c.lastPrefix | lastLevelDigits(c.lastPermutation, sample, odd);
        return walkLowDigits(d, c, sample);
    }
    [[gnu::noinline]] uint64_t walkLowDigits(int d, CachedDimension& c, uint64_t sample) {
        const int odd = log2Spp_ & 1;
        const int lastBits = odd ? 1 : 2;
        // The tree is stored level after level, each node's children 4n + 1 … 4n + 4
        // (a 4-ary heap): the node at a level is found from the one above it
        // and the digit just read, without the level's offset.
        uint8_t* tree = lowPermutations_.data() + size_t(d) * size_t(lowNodes_);
        uint64_t index = 0;
        size_t node = 0;
        uint8_t last = 0;
        for (int shift = log2Spp_ - 2; shift >= odd; shift -= 2) {
            uint8_t& perm = tree[node];
            if (perm == kUnset)
                perm = zsobol::digitPermutation(mortonIndex_ >> (shift + 2), c.salt);
            const auto digit = unsigned(sample >> shift) & 3;
            index = index << 2 | ((perm >> (2 * digit)) & 3);
            node = 4 * node + 1 + digit;
            last = perm;
        }
        if (odd) {
            uint8_t& flip = tree[node];
            if (flip == kUnset) flip = uint8_t(mixBits((mortonIndex_ >> 1) ^ c.salt) & 1);
            index = index << 1 | ((sample & 1) ^ flip);
            last = flip;
        }
        c.lastParent = sample >> lastBits;
        c.lastPrefix = index >> lastBits << lastBits;
        c.lastPermutation = last;
        return index;
    }
    // The last level's permuted digit of `sample`: its two low bits through
    // the permutation, or (odd log2 spp) its low bit XOR the flip.
    static uint64_t lastLevelDigits(uint8_t permutation, uint64_t sample, int odd) {
        return odd ? (sample & 1) ^ permutation : (permutation >> (2 * (sample & 3))) & 3;
    }
    uint64_t lowDigitsUncached(uint64_t salt) const {
        const int odd = log2Spp_ & 1;
        uint64_t index = 0;
        for (int shift = log2Spp_ - 2; shift >= odd; shift -= 2)
            index |= uint64_t(zsobol::permuteDigit((mortonIndex_ >> shift) & 3,
                                                   mortonIndex_ >> (shift + 2), salt))
                     << shift;
        if (odd) index |= (mortonIndex_ & 1) ^ (mixBits((mortonIndex_ >> 1) ^ salt) & 1);
        return index;
    }
    // Up to 4096 spp the trees are kept: 1365 nodes per dimension at most.
    static constexpr int kMaxTreeLog2Spp = 12;
    static constexpr uint8_t kUnset = 0xff;  // no permutation of four digits is 0xff
    // Up to 256 spp, every sample's permuted low digits are tabulated instead
    // (fillLowTable), when the pixel first draws the dimension.
    static constexpr int kMaxTableLog2Spp = 8;
    // Only the dimensions of the first three path vertices, which nearly every
    // sample draws; deeper ones, drawn by fewer samples, walk the tree. (With
    // a thin lens the vertices start two dimensions later: the third
    // vertex's last two then walk the tree too — the same values, a little
    // slower.)
    static constexpr int kTabulatedDimensions = dims::bounceBase(3);
    std::vector<uint16_t> lowTable_;   // kTabulatedDimensions × 2^log2Spp_ (empty: none)
    std::vector<uint32_t> lowSobol1_;  // their bit-reversed Sobol' dimension 1, alike
    bool tabulated(int d) const { return d < kTabulatedDimensions && !lowTable_.empty(); }
    // The current sample's index bits, and its entry in dimension d's tables.
    uint64_t sampleBits() const { return mortonIndex_ & ((uint64_t(1) << log2Spp_) - 1); }
    size_t tableRow(int d) const { return size_t(d) << log2Spp_; }  // dimension d's first entry
    size_t tableSlot(int d) const { return tableRow(d) | sampleBits(); }
    int lowNodes_ = 0;                      // nodes per dimension (0: no tree kept)
    std::vector<uint8_t> lowPermutations_;  // kCachedDimensions × lowNodes_

    int spp_;
    uint64_t seed_;
    const uint32_t* matrices_;
    int log2Spp_ = 0;
    int base4Digits_ = 0;
    Vec2i pixel_{-1, -1};
    uint64_t pixelMorton_ = 0;  // the pixel's Morton code, shifted by log2Spp_
    uint64_t mortonIndex_ = 0;
    int dimension_ = 0;
    uint64_t cachedHigh_ = ~uint64_t(0);
    uint64_t cacheValid_ = 0;  // bit d: cache_[d]'s per-pixel part is current
    // Bit-reversed Sobol' dimension 1 of every value of index bits 0–7, 8–15
    // and 16–23 (the renderer's spp ≤ 2^24): three tables of 256.
    const uint32_t* reversedSobol1Bytes_;
    CachedDimension cache_[kCachedDimensions];
};

}  // namespace pathlab
