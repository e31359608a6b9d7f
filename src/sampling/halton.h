// The presentation's three Halton samplers: `halton`, `halton-rd`, `halton-owen`.
//
// Dimension d (past the two pixel dimensions) is the radical inverse of the
// sample's Halton index in the d-th prime base (Halton 1960). Image-plane
// mapping follows pbrt-v4's HaltonSampler (Pharr, Jakob & Humphreys,
// "Physically Based Rendering", 4th ed., §8.6): the pixel dimensions 0 and 1
// cover the whole image — base 2 scaled by 2^j ≥ width, base 3 by 3^k ≥ height —
// so the Halton indices that fall into pixel p are h_p + i · 2^j 3^k for a
// per-pixel offset h_p found with the Chinese remainder theorem. Every pixel
// gets its own indices (no two pixels share a pattern) and its samples are a
// stratified subsequence of one global sequence. Unlike pbrt-v4 the image scale
// is not capped at 128 pixels, so pixels never repeat each other's indices.
//
// Randomisation (the presentation's code, generalised so it is a bijection of
// b-adic intervals — see docs/samplers.md):
//   None         — the plain radical inverse.
//   RandomDigit  — one seeded random permutation π_b of {0..b−1} per base, as
//                  in the presentation, applied to every digit down to float
//                  precision (trailing zero digits included, so the map is a
//                  bijection of the b-adic intervals at every level). Digit k
//                  becomes π_b((d_k + s_k) mod b) with a seeded shift s_k per
//                  base and digit position: with π_b alone, equal digits stay
//                  equal, so a point is not uniformly distributed over seeds and
//                  the estimator is biased (in base 2 the only "scramble" would
//                  be x ↦ 1 − x); the shift makes every digit independent and
//                  uniform — a random digital shift (Matoušek 1998) composed
//                  with the presentation's permutation.
//   Owen         — nested scrambling: digit k becomes π_b((d_k + r) mod b)
//                  where the rotation r is a hash of (seed, dimension, k and all
//                  higher digits) — Owen 1995's tree of random permutations
//                  realised by hashing, as the presentation and pbrt-v4's
//                  OwenScrambledRadicalInverse do. (They hash the higher digits
//                  after scrambling; those name the same node of the tree, see
//                  owenScrambledDigits.)
// Past the kPrimeTableSize (1000) prime bases, dimensions wrap back to 2, as in
// pbrt-v4; the Owen variant hashes the unwrapped dimension, so wrapped
// dimensions still get fresh scrambles there.
#pragma once

#include <algorithm>
#include <bit>
#include <memory>
#include <vector>

#include "core/simd_target.h"
#include "sampling/lowdiscrepancy.h"
#include "sampling/sampler.h"

namespace pathlab {

enum class HaltonScrambling { None, RandomDigit, Owen };

// The first kTabulatedBases permutations are tables (a path of depth 8 uses 58
// dimensions); beyond them the permutation of base b is evaluated on the fly
// by permutationElement with a seed hashed from (seed, b) — also a seeded
// pseudo-random permutation, just slower — so building the tables for a new
// seed costs well under a millisecond instead of 7 MB for all 1000 bases.
struct DigitPermutation {
    const uint16_t* table;  // null: evaluate with permutationElement
    uint64_t hash;
    uint32_t base;
    uint32_t operator()(uint32_t digit) const {
        return table ? table[digit] : permutationElement(digit, base, hash);
    }
};

// Everything a scrambled radical inverse of tabulated dimension d needs,
// gathered per seed so that a draw neither hashes the seed, nor looks up the
// prime and its digit count, nor divides by the base (BaseDivider multiplies).
struct HaltonDimension {
    BaseDivider divider;
    uint32_t base;
    int digits;    // floatDigitCount(base)
    double scale;  // base^-digits, rounded exactly as the digit loops compute it
    const uint16_t* permutation;
    const uint16_t* shifts;  // RandomDigit: s_k
    // RandomDigit: once the index has no digits left, digits k… are zeros and
    // the rest of the scrambled integer is the constant tail[k]; it joins the
    // digits above it as reversed · power[k] + tail[k] (power[k] = base^(digits−k)).
    const uint64_t* tail;
    const uint64_t* power;
    // RandomDigit, bases up to kMaxPairBase: digits k and k+1 (k even) are
    // scrambled together, pairs[(k/2)·b² + d_k + b·d_{k+1}] being the two
    // scrambled digits as d'_k·b + d'_{k+1}; null for larger bases.
    const uint16_t* pairs;
    BaseDivider pairDivider;  // b²
    uint64_t owenHash;        // Owen: hashValues(seed, d, 0x4f57454e)
    // Owen: the rotations of the root ([0]) and of its children ([1 + d_0]).
    const uint16_t* rotations;
    // RandomDigit: digit k's scrambled value π_b((d + s_k) mod b) at [k·b + d],
    // for the lane draws (the scalar loop scrambles the digit itself). The
    // lane draws gather from these 16-bit tables and from `permutation`,
    // `pairs` and `rotations` 32 bits at a time, keeping the low half: each
    // table's vector holds one entry more than it uses, so that the last
    // entry's read stays inside it.
    const uint16_t* scrambledDigits;
    double inverseBase, inversePairBase;  // RN(1 / b), RN(1 / b²)
    // Owen, bases up to kMaxByteTableBase: `permutation` and the children's
    // `rotations` again as bytes, which the AVX-512 VBMI lane draws hold in
    // registers instead of gathering them; null for larger bases. Up to
    // kMaxWrapFreeBase the permutation's bytes are written twice over
    // (entry i is π_b(i mod b) for i < 2b), so that a rotated digit d + r
    // looks its value up without first wrapping the sum below b.
    const uint8_t* permutationBytes = nullptr;
    const uint8_t* childRotationBytes = nullptr;
    // RandomDigit, bases up to kMaxByteTableBase: `scrambledDigits` as bytes,
    // and up to kMaxBytePairBase (b² ≤ 256) `pairs` too, which the AVX-512
    // VBMI lane draws hold in registers per digit position instead of
    // gathering them; null for larger bases.
    const uint8_t* scrambledDigitBytes = nullptr;
    const uint8_t* pairBytes = nullptr;
};

// The lane draws' arithmetic (halton_lanes.cpp): out[j] = randomDigitScrambled
// or owenScrambled(t, a[j]) for the indices a[0 … count), bit for bit (tested)
// — the lanes side by side in AVX2 registers where the processor has them. a
// and out hold kCameraPacketSamples entries whatever the count: a register's
// four lanes are read and written together, so every entry of a must be below
// 2^32, the lanes past count too (the sampler pads them with its first index).
// `limit` caps the instruction set (the tests run every one the processor has).
void randomDigitScrambledLanes(const HaltonDimension& t, const uint64_t* a, int count, float* out,
                               SimdLevel limit = SimdLevel::Avx512Vbmi);
void owenScrambledLanes(const HaltonDimension& t, const uint64_t* a, int count, float* out,
                        SimdLevel limit = SimdLevel::Avx512Vbmi);
// The same for the plain sampler: out[j] = radicalInverse(b, a[j]).
void radicalInverseLanes(const PrimeBase& b, const uint64_t* a, int count, float* out,
                         SimdLevel limit = SimdLevel::Avx512Vbmi);
// Two dimensions of the same indices (a 2D draw) in one call: x from tx or
// bx, y from ty or by, each exactly as the calls above give it.
void randomDigitScrambledLanes2D(const HaltonDimension& tx, const HaltonDimension& ty,
                                 const uint64_t* a, int count, float* x, float* y,
                                 SimdLevel limit = SimdLevel::Avx512Vbmi);
void owenScrambledLanes2D(const HaltonDimension& tx, const HaltonDimension& ty, const uint64_t* a,
                          int count, float* x, float* y, SimdLevel limit = SimdLevel::Avx512Vbmi);
void radicalInverseLanes2D(const PrimeBase& bx, const PrimeBase& by, const uint64_t* a, int count,
                           float* x, float* y, SimdLevel limit = SimdLevel::Avx512Vbmi);

// Seeded digit permutations for every prime base (immutable, shared by copies).
struct HaltonDigitPermutations {
    static constexpr int kMaxDigits = 32;  // floatDigitCount(2) = 25
    static constexpr int kTabulatedBases = 128;
    // Pair tables stop here: b² entries per pair of digit positions (61: 3721
    // entries, 3 pairs), 122 KB per seed for the 18 bases up to 61 together.
    static constexpr int kMaxPairBase = 61;
    // Byte copies stop here: every digit and rotation fits a byte, and two
    // byte permutes of two registers each look up 256 entries.
    static constexpr int kMaxByteTableBase = 256;
    // Doubled permutations stop here: 2b entries in two registers.
    static constexpr int kMaxWrapFreeBase = 64;
    // Byte pair tables stop here: 13² = 169 entries in four registers.
    static constexpr int kMaxBytePairBase = 16;
    // The most bytes a lane kernel loads from a byte table's start: four
    // 64-byte registers.
    static constexpr size_t kRegisterTableBytes = 256;
    uint64_t seed;
    std::vector<uint32_t> offset;  // start of base b_d's permutation in `table`
    std::vector<uint16_t> table;
    std::vector<uint16_t> shifts;           // kMaxDigits per base: the per-position digit shifts
    std::vector<uint64_t> tails, powers;    // kMaxDigits per tabulated base
    std::vector<uint16_t> rotations;        // 1 + b per tabulated base
    std::vector<uint16_t> pairTables;       // HaltonDimension::pairs of every base ≤ kMaxPairBase
    std::vector<uint16_t> scrambledDigits;  // HaltonDimension::scrambledDigits of every base
    std::vector<uint8_t> byteTables;        // HaltonDimension's byte copies
    std::vector<HaltonDimension> dimensions;  // the first kTabulatedBases
    explicit HaltonDigitPermutations(uint64_t seed);
    DigitPermutation forDimension(int d, int base) const {
        return {d < kTabulatedBases ? table.data() + offset[d] : nullptr,
                hashValues(seed, base, 0x5244u), uint32_t(base)};
    }
    const uint16_t* shiftsForDimension(int d) const { return shifts.data() + d * kMaxDigits; }

  private:
    void addByteTables();
};

// The tables for a seed, shared by every sampler built with it.
std::shared_ptr<const HaltonDigitPermutations> haltonDigitPermutations(uint64_t seed);

// The image-plane mapping shared by the three variants.
struct HaltonImageMapping {
    int baseScales[2] = {1, 1};     // 2^j, 3^k
    int baseExponents[2] = {0, 0};  // j, k
    uint64_t multInverse[2] = {0, 0};
    explicit HaltonImageMapping(Vec2i resolution);
    // The Halton index of sample `index` of pixel p: pixelOffset(p) + index · stride().
    uint64_t index(Vec2i p, int sampleIndex) const {
        return pixelOffset(p) + uint64_t(sampleIndex) * stride();
    }
    // The pixel's first index h_p (the Chinese remainder theorem, a dozen 64-bit
    // divisions: the samplers compute it once per pixel).
    uint64_t pixelOffset(Vec2i p) const;
    uint64_t stride() const { return uint64_t(baseScales[0]) * uint64_t(baseScales[1]); }
};

template <HaltonScrambling kScrambling>
class HaltonSamplerT {
  public:
    explicit HaltonSamplerT(const SamplerConfig& c);

    int samplesPerPixel() const { return spp_; }
    void startPixelSample(Vec2i p, int index, int dim) {
        // The image mapping's pixel offset once per pixel; a sample's index is
        // then one multiply-add (mapping_.index(p, index), bit for bit).
        if (p.x != pixel_.x || p.y != pixel_.y) pixel_ = p, pixelOffset_ = mapping_.pixelOffset(p);
        haltonIndex_ = pixelOffset_ + uint64_t(index) * stride_;
        dimension_ = std::max(2, dim);
    }
    float get1D() { return sampleDimension(dimension_++); }
    Vec2f get2D() {
        const int d = dimension_;
        dimension_ += 2;
        return {sampleDimension(d), sampleDimension(d + 1)};
    }
    // The pixel dimensions are the unscrambled digits below the image-scale
    // digits: scrambling them would move samples into other pixels.
    Vec2f getPixel2D() {
        return {radicalInverse(bases_[0], haltonIndex_ >> mapping_.baseExponents[0]),
                radicalInverse(bases_[1], haltonIndex_ / uint64_t(mapping_.baseScales[1]))};
    }

    // The pixel dimensions of several samples (sampler.h's drawPixelLanes),
    // the same floats as getPixel2D: base 2's radical inverse is a bit
    // reversal, base 3's runs side by side in the lane kernels, and the
    // image-scale digits are dropped by a shift and a multiply instead of a
    // division per sample.
    void getPixel2DLanes(Vec2i p, const int* indices, int count, Vec2f* out) {
        uint64_t a[kCameraPacketSamples];
        if (!laneIndices(p, indices, count, dims::kPixel, 2, a)) {
            for (int j = 0; j < count; ++j)
                startPixelSample(p, indices[j], dims::kPixel), out[j] = getPixel2D();
            return;
        }
        float x[kCameraPacketSamples], y[kCameraPacketSamples];
        for (int j = 0; j < kCameraPacketSamples; ++j) {
            x[j] = radicalInverseBase2(uint32_t(a[j] >> mapping_.baseExponents[0]));
            a[j] = rowScale_.base > 1 ? rowScale_.quotient32(a[j]) : a[j];
        }
        radicalInverseLanes(bases_[1], a, count, y);
        for (int j = 0; j < count; ++j) out[j] = {x[j], y[j]};
    }

    // Lane draws (sampler.h): a tabulated dimension's digits for all the
    // lanes at once. Untabulated dimensions and indices from 2^32 on take the
    // digit loops lane by lane.
    void get1DLanes(Vec2i p, const int* indices, int count, int dim, float* out) {
        uint64_t a[kCameraPacketSamples];
        if (!laneIndices(p, indices, count, dim, 1, a))
            return drawEachLane1D(*this, p, indices, count, dim, out);
        float x[kCameraPacketSamples];
        scrambleLanes(dimension_ - 1, a, count, x);
        for (int j = 0; j < count; ++j) out[j] = x[j];
    }
    void get2DLanes(Vec2i p, const int* indices, int count, int dim, Vec2f* out) {
        uint64_t a[kCameraPacketSamples];
        if (!laneIndices(p, indices, count, dim, 2, a))
            return drawEachLane2D(*this, p, indices, count, dim, out);
        float x[kCameraPacketSamples], y[kCameraPacketSamples];
        scrambleLanes2D(dimension_ - 2, a, count, x, y);
        for (int j = 0; j < count; ++j) out[j] = {x[j], y[j]};
    }

    // The value of dimension d of Halton index a (exposed for tests and tools).
    float sampleDimension(int d) const;

  private:
    // The lanes' Halton indices (padded with the pixel's first); positions the
    // sampler past the `used` dimensions from dim. False when the lane kernels
    // do not apply: a dimension past the tables, or an index from 2^32 on.
    bool laneIndices(Vec2i p, const int* indices, int count, int dim, int used, uint64_t* a) {
        startPixelSample(p, indices[0], dim);
        const int first = dimension_;
        dimension_ += used;
        uint64_t largest = 0;
        for (int j = 0; j < kCameraPacketSamples; ++j) {
            a[j] = pixelOffset_ + uint64_t(j < count ? indices[j] : indices[0]) * stride_;
            largest = std::max(largest, a[j]);
        }
        return first + used <= HaltonDigitPermutations::kTabulatedBases && largest >> 32 == 0;
    }
    void scrambleLanes2D(int d, const uint64_t* a, int count, float* x, float* y) const {
        if constexpr (kScrambling == HaltonScrambling::None)
            radicalInverseLanes2D(bases_[d], bases_[d + 1], a, count, x, y);
        else if constexpr (kScrambling == HaltonScrambling::RandomDigit)
            randomDigitScrambledLanes2D(dimensions_[d], dimensions_[d + 1], a, count, x, y);
        else
            owenScrambledLanes2D(dimensions_[d], dimensions_[d + 1], a, count, x, y);
    }
    void scrambleLanes(int d, const uint64_t* a, int count, float* out) const {
        if constexpr (kScrambling == HaltonScrambling::None)
            radicalInverseLanes(bases_[d], a, count, out);
        else if constexpr (kScrambling == HaltonScrambling::RandomDigit)
            randomDigitScrambledLanes(dimensions_[d], a, count, out);
        else
            owenScrambledLanes(dimensions_[d], a, count, out);
    }

    int spp_;
    uint64_t seed_;
    HaltonImageMapping mapping_;
    uint64_t stride_;  // mapping_.stride()
    // 3^k, mapping_.baseScales[1]; for k = 0 (an image one pixel tall) its
    // reciprocal wraps to 0, so the lane draws skip the division by 1.
    BaseDivider rowScale_;
    std::shared_ptr<const HaltonDigitPermutations> permutations_;
    const HaltonDimension* dimensions_ = nullptr;  // permutations_->dimensions
    const int* primes_;
    const PrimeBase* bases_;  // primeBases()
    Vec2i pixel_{-1, -1};
    uint64_t pixelOffset_ = 0;  // mapping_.pixelOffset(pixel_)
    uint64_t haltonIndex_ = 0;
    int dimension_ = 0;
};

using HaltonSampler = HaltonSamplerT<HaltonScrambling::None>;
using RandomDigitHaltonSampler = HaltonSamplerT<HaltonScrambling::RandomDigit>;
using OwenHaltonSampler = HaltonSamplerT<HaltonScrambling::Owen>;

// The float nearest below v: rounding to nearest could lift a point sitting
// just under a b-adic stratum boundary into the next stratum.
// Branch-free, because whether rounding went up is a coin flip per point and
// a mispredicted branch costs more than a digit. v ≥ 0, so when f > v, f > 0
// and the next float towards 0 is one ulp less.
inline float floatBelow(double v) {
    const float f = static_cast<float>(v);
    const uint32_t roundedUp = static_cast<double>(f) > v;
    return std::min(std::bit_cast<float>(std::bit_cast<uint32_t>(f) - roundedUp), kOneMinusEpsilon);
}

// (digit + rotation) mod base, for digit and rotation both below base.
// Whether the sum wraps is a coin flip per digit, so it is computed with a
// mask: written as a conditional, the profile-guided build turned it into a
// branch that mispredicted half the time (halton-owen's frames took 1.3× as long).
inline uint32_t rotateDigit(uint32_t digit, uint32_t rotation, uint32_t base) {
    const uint32_t rotated = digit + rotation;
    const uint32_t wrapped = 0u - uint32_t(rotated >= base);  // all ones when it wraps
    return rotated - (base & wrapped);
}

// The rotation of the node of Owen's tree at depth k named by prefix (the
// digits above it, d_0 … d_{k−1}, as the integer d_0·b^{k−1} + … + d_{k−1},
// below 2^40 for every base's float digits): the hash's top 32 bits scaled to
// [0, base) (Lemire's multiply-shift range reduction, no division).
inline uint32_t owenRotation(uint64_t dimensionHash, int k, uint64_t prefix, uint32_t base) {
    const uint64_t nodeHigh = mixBitsHigh32(dimensionHash ^ (prefix | uint64_t(k) << 56));
    return uint32_t((nodeHigh * base) >> 32);
}

// Owen scrambling of a's first `digits` base-b digits (b = divider.base): digit k
// becomes permutation((d_k + r) mod b) with the rotation r hashed from
// (dimensionHash, k, d_0 … d_{k−1}) — the node of Owen's tree the point lies
// in, so points sharing their first k digits share digit k's permutation and
// b-adic strata map to b-adic strata. The node is named by the input digits
// above k; given the seed they determine the scrambled ones and vice versa,
// so this is the same tree as hashing the scrambled digits (pbrt-v4), but no
// digit's hash waits for the digit above it to be scrambled.
template <typename Permutation>
float owenScrambledDigits(uint64_t a, const BaseDivider& divider, int digits, double scale,
                          Permutation permutation, uint64_t dimensionHash) {
    const auto base = uint32_t(divider.base);
    uint64_t reversed = 0, prefix = 0;
    for (int k = 0; k < digits; ++k) {
        const uint64_t next = divider.quotient(a);
        const auto digit = uint32_t(a - next * base);
        reversed =
            reversed * base +
            permutation(rotateDigit(digit, owenRotation(dimensionHash, k, prefix, base), base));
        prefix = prefix * base + digit;
        a = next;
    }
    return floatBelow(static_cast<double>(reversed) * scale);
}

// base^-digits as the product of `digits` rounded 1/base — the value every
// digit loop scales its scrambled integer by.
inline double inverseBasePower(int base, int digits) {
    const double invBase = 1.0 / base;
    double scale = 1.0;
    for (int k = 0; k < digits; ++k) scale *= invBase;
    return scale;
}

// Digit-level reference implementations for any base (also the path for the
// untabulated dimensions), exposed for tests.
float randomDigitScrambledRadicalInverse(int base, uint64_t a, DigitPermutation permutation,
                                         const uint16_t* shifts);
float owenScrambledRadicalInverse(int base, uint64_t a, DigitPermutation permutation,
                                  uint64_t dimensionHash);

// The two scramblers for a tabulated dimension (the samplers' hot path),
// bit-identical to the digit loops above (tested). Indices from 2^32 on, where
// BaseDivider needs a true division, take those loops.
inline float randomDigitScrambled(const HaltonDimension& t, uint64_t a) {
    if (a >> 32)
        return randomDigitScrambledRadicalInverse(int(t.base), a, {t.permutation, 0, t.base},
                                                  t.shifts);
    uint64_t reversed = 0;
    int k = 0;
    // Two digits per step where a pair table exists: the chain of divisions
    // through a, which sets the loop's latency, is half as long. A pair whose
    // upper digit is a zero past a's last digit gives the same integer as
    // stopping before it, since tail[k+1] = π_b(s_{k+1})·power[k+2] + tail[k+2].
    if (t.pairs) {
        const uint64_t base2 = t.pairDivider.base;
        for (; a != 0 && k + 1 < t.digits; k += 2) {
            const uint64_t next = t.pairDivider.quotient32(a);
            reversed = reversed * base2 + t.pairs[size_t(k / 2) * base2 + (a - next * base2)];
            a = next;
        }
    }
    // Once a has no digits left, the rest are zeros: their scrambled value is tail[k].
    for (; a != 0 && k < t.digits; ++k) {
        const uint64_t next = t.divider.quotient32(a);
        const auto digit = uint32_t(a - next * t.base);
        reversed = reversed * t.base + t.permutation[rotateDigit(digit, t.shifts[k], t.base)];
        a = next;
    }
    reversed = reversed * t.power[k] + t.tail[k];
    return floatBelow(static_cast<double>(reversed) * t.scale);
}
inline float owenScrambled(const HaltonDimension& t, uint64_t a) {
    if (a >> 32)
        return owenScrambledRadicalInverse(int(t.base), a, {t.permutation, 0, t.base}, t.owenHash);
    // Digits 0 and 1: the rotations of the root and of its b children are
    // tabulated (the same hashes, computed once per seed).
    const uint32_t base = t.base;
    uint64_t next = t.divider.quotient32(a);
    const auto d0 = uint32_t(a - next * base);
    a = next;
    next = t.divider.quotient32(a);
    const auto d1 = uint32_t(a - next * base);
    a = next;
    uint64_t reversed = uint64_t(t.permutation[rotateDigit(d0, t.rotations[0], base)]) * base +
                        t.permutation[rotateDigit(d1, t.rotations[1 + d0], base)];
    uint64_t prefix = uint64_t(d0) * base + d1;
    for (int k = 2; k < t.digits; ++k) {
        next = t.divider.quotient32(a);
        const auto digit = uint32_t(a - next * base);
        reversed =
            reversed * base +
            t.permutation[rotateDigit(digit, owenRotation(t.owenHash, k, prefix, base), base)];
        prefix = prefix * base + digit;
        a = next;
    }
    return floatBelow(static_cast<double>(reversed) * t.scale);
}

template <HaltonScrambling kScrambling>
HaltonSamplerT<kScrambling>::HaltonSamplerT(const SamplerConfig& c)
    : spp_(c.samplesPerPixel),
      seed_(c.seed),
      mapping_(c.resolution),
      stride_(mapping_.stride()),
      rowScale_(uint32_t(mapping_.baseScales[1])),
      primes_(primeTable()),
      bases_(primeBases()) {
    if constexpr (kScrambling != HaltonScrambling::None) {
        permutations_ = haltonDigitPermutations(c.seed);
        dimensions_ = permutations_->dimensions.data();
    }
}

template <HaltonScrambling kScrambling>
float HaltonSamplerT<kScrambling>::sampleDimension(int d) const {
    if constexpr (kScrambling != HaltonScrambling::None) {
        if (unsigned(d) < unsigned(HaltonDigitPermutations::kTabulatedBases)) {
            if constexpr (kScrambling == HaltonScrambling::RandomDigit)
                return randomDigitScrambled(dimensions_[d], haltonIndex_);
            else
                return owenScrambled(dimensions_[d], haltonIndex_);
        }
    }
    const int wrapped = d < kPrimeTableSize ? d : 2 + (d - 2) % (kPrimeTableSize - 2);
    [[maybe_unused]] const int base = primes_[wrapped];
    if constexpr (kScrambling == HaltonScrambling::None) {
        return radicalInverse(bases_[wrapped], haltonIndex_);
    } else if constexpr (kScrambling == HaltonScrambling::RandomDigit) {
        return randomDigitScrambledRadicalInverse(base, haltonIndex_,
                                                  permutations_->forDimension(wrapped, base),
                                                  permutations_->shiftsForDimension(wrapped));
    } else {
        return owenScrambledRadicalInverse(base, haltonIndex_,
                                           permutations_->forDimension(wrapped, base),
                                           hashValues(seed_, d, 0x4f57454eu));
    }
}

}  // namespace pathlab
