#include "sampling/sobol.h"

#include <immintrin.h>

#include <stdexcept>
#include <vector>

#include "core/hash.h"
#include "core/simd_target.h"

namespace pathlab {

// zsobol::digitPermutation for eight consecutive nodes at a time: mixBits
// with 64-bit lane multiplies, then (h >> 24) mod 24 through doubles — h >> 24
// is below 2^40, so ⌊(x + ½)/24⌋ is exact from the rounded reciprocal (its
// error, about 2^-16.6, is far below the ½/24 by which (x + ½)/24 misses an
// integer) — and the 24 permutations looked up by a byte permute. The masked
// intrinsics, with every lane set: GCC 12's unmasked ones pass an undefined
// operand that -Wall reports.
PATHLAB_AVX512_VBMI_BEGIN
namespace avx512vbmi {
void digitPermutations(uint64_t first, uint64_t salt, uint32_t count, uint8_t* out) {
    constexpr __mmask8 kAll = 0xff;
    using Lanes = uint64_t __attribute__((vector_size(64)));
    const __m512i table = _mm512_maskz_loadu_epi8(0xffffff, zsobol::kDigitPermutations);
    const __m512i lanes = _mm512_set_epi64(7, 6, 5, 4, 3, 2, 1, 0);
    const __m512d inverse24 = _mm512_set1_pd(1.0 / 24);
    for (uint32_t n = 0; n < count; n += 8) {
        // mixBits(((first | n) + lane) ^ salt), its steps on 64-bit lanes.
        auto hash =
            Lanes(_mm512_xor_si512(_mm512_add_epi64(_mm512_set1_epi64(int64_t(first | n)), lanes),
                                   _mm512_set1_epi64(int64_t(salt))));
        mixBitsMultiplySteps(hash);
        hash ^= hash >> 33;
        const __m512i x = _mm512_maskz_srli_epi64(kAll, __m512i(hash), 24);
        const __m512d quotient = _mm512_maskz_roundscale_pd(
            kAll,
            _mm512_mul_pd(_mm512_add_pd(_mm512_maskz_cvtepu64_pd(kAll, x), _mm512_set1_pd(0.5)),
                          inverse24),
            _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
        const __m512i remainder = _mm512_sub_epi64(
            x,
            _mm512_mullo_epi64(_mm512_maskz_cvttpd_epu64(kAll, quotient), _mm512_set1_epi64(24)));
        // Each lane's remainder is its low byte; the permutation lands there.
        const __m512i permutation =
            _mm512_maskz_permutexvar_epi8(0x0101010101010101ULL, remainder, table);
        _mm_storel_epi64(reinterpret_cast<__m128i*>(out + n),
                         _mm512_maskz_cvtepi64_epi8(kAll, permutation));
    }
}
}  // namespace avx512vbmi
PATHLAB_AVX512_VBMI_END

void zsobol::digitPermutations(uint64_t first, uint64_t salt, uint32_t count, uint8_t* out,
                               SimdLevel limit) {
    if (simdLevelUpTo(limit) >= SimdLevel::Avx512Vbmi)
        return avx512vbmi::digitPermutations(first, salt, count, out);
    for (uint32_t n = 0; n < count; ++n) out[n] = digitPermutation(first | n, salt);
}

namespace {

// The top m bits of dimensions 0 and 1 of Gray-coded index g, packed as
// (x bits << m) | y bits: which 2^-m square the point falls into.
uint64_t topBits(const uint32_t* matrices, uint64_t g, int m) {
    const uint64_t x = sobolBits(matrices, g, 0) >> (32 - m);
    const uint64_t y = sobolBits(matrices, g, 1) >> (32 - m);
    return (x << m) | y;
}

}  // namespace

SobolImageMapping::SobolImageMapping(const uint32_t* matrices, Vec2i resolution) {
    log2Scale = log2Ceil(uint64_t(std::max({1, resolution.x, resolution.y})));
    const int m = log2Scale, n = 2 * m;
    if (m == 0) return;
    if (m > 16) throw std::invalid_argument("Sobol' image mapping: resolution above 65536");
    // Gauss–Jordan elimination of [A | I] over GF(2), one row per target bit:
    // A maps the low 2m index bits to the 2m top bits of (x, y). A is
    // invertible because the first 2^{2m} Sobol' points form a (0,2m,2)-net.
    uint64_t rows[32];
    for (int r = 0; r < n; ++r) {
        uint64_t row = 0;
        for (int k = 0; k < n; ++k) row |= ((topBits(matrices, uint64_t(1) << k, m) >> r) & 1) << k;
        rows[r] = row | (uint64_t(1) << (32 + r));
    }
    for (int col = 0; col < n; ++col) {
        int pivot = col;
        while (pivot < n && !((rows[pivot] >> col) & 1)) ++pivot;
        if (pivot == n) throw std::logic_error("Sobol' image mapping: singular matrix");
        std::swap(rows[col], rows[pivot]);
        for (int r = 0; r < n; ++r)
            if (r != col && ((rows[r] >> col) & 1)) rows[r] ^= rows[col];
    }
    // Row r of the right half says which target bits index bit r depends on.
    for (int c = 0; c < n; ++c) {
        uint64_t column = 0;
        for (int r = 0; r < n; ++r) column |= ((rows[r] >> (32 + c)) & 1) << r;
        inverse[c] = column;
    }
}

uint64_t SobolImageMapping::index(const uint32_t* matrices, Vec2i p, uint64_t frame) const {
    const uint64_t gray = frame ^ (frame >> 1);
    const int m = log2Scale;
    if (m == 0) return gray;
    const uint64_t high = gray << (2 * m);
    const uint64_t mask = (uint64_t(1) << m) - 1;
    uint64_t target = ((uint64_t(p.x) & mask) << m) | (uint64_t(p.y) & mask);
    target ^= topBits(matrices, high, m);
    // A fixed 2m steps, each column masked in or out: testing each bit of the
    // target was a coin-toss branch per bit (this function was 14% of a
    // sobol frame).
    uint64_t low = 0;
    for (int c = 0; c < 2 * m; ++c) low ^= inverse[c] & (0 - ((target >> c) & 1));
    return high | low;
}

ZSobolSampler::ZSobolSampler(const SamplerConfig& c)
    : spp_(c.samplesPerPixel), seed_(c.seed), matrices_(sobolMatrices()) {
    log2Spp_ = log2Ceil(uint64_t(std::max(1, c.samplesPerPixel)));
    const int log2Resolution = log2Ceil(uint64_t(std::max({1, c.resolution.x, c.resolution.y})));
    base4Digits_ = log2Resolution + (log2Spp_ + 1) / 2;
    static const std::vector<uint32_t> bytes = [matrices = matrices_] {
        std::vector<uint32_t> t(3 * 256);
        for (int byte = 0; byte < 3; ++byte)
            for (uint64_t v = 0; v < 256; ++v)
                t[size_t(byte) * 256 + v] = reverseBits32(sobolBits(matrices, v << (8 * byte), 1));
        return t;
    }();
    reversedSobol1Bytes_ = bytes.data();
    if (log2Spp_ >= 1 && log2Spp_ <= kMaxTableLog2Spp) {
        lowTable_.assign(size_t(kTabulatedDimensions) << log2Spp_, 0);
        lowSobol1_.assign(lowTable_.size(), 0);
    }
    if (log2Spp_ >= 1 && log2Spp_ <= kMaxTreeLog2Spp) {
        const int levels = log2Spp_ / 2;  // full base-4 digits below the pixel's
        for (int j = 0; j < levels; ++j) lowNodes_ += 1 << (2 * j);
        if (log2Spp_ & 1) lowNodes_ += 1 << (log2Spp_ - 1);
        lowPermutations_.assign(size_t(kCachedDimensions) * size_t(lowNodes_), kUnset);
    }
    for (int d = 0; d < kCachedDimensions; ++d) {
        CachedDimension& cd = cache_[d];
        cd.salt = hashValues(d, seed_, 0x5a4fu);
        cd.seed1D = foldSeed(hashValues(d, seed_, 0x5a31u));
        const uint64_t seeds = hashValues(d, seed_, 0x5a32u);
        cd.seeds2D[0] = uint32_t(seeds), cd.seeds2D[1] = uint32_t(seeds >> 32);
    }
}

uint64_t ZSobolSampler::referenceSampleIndex(int dimension) const {
    // With an odd power of two per pixel, the lowest "digit" is a single bit.
    const bool oddBits = log2Spp_ & 1;
    const uint64_t dimensionSalt = hashValues(dimension, seed_, 0x5a4fu);
    uint64_t index = 0;
    for (int i = base4Digits_ - 1; i >= (oddBits ? 1 : 0); --i) {
        const int shift = 2 * i - (oddBits ? 1 : 0);
        const unsigned digit = (mortonIndex_ >> shift) & 3;
        index |= uint64_t(zsobol::permuteDigit(digit, mortonIndex_ >> (shift + 2), dimensionSalt))
                 << shift;
    }
    if (oddBits) index |= (mortonIndex_ & 1) ^ (mixBits((mortonIndex_ >> 1) ^ dimensionSalt) & 1);
    return index;
}

void ZSobolSampler::fillLowTable(int d, uint64_t salt) {
    // The tree of walkLowDigits level by level from the root, expanded in
    // place: entry n of a level holds the permuted digits above it of node n
    // (n = the samples' digits above the level), and its children 4n … 4n + 3
    // (2n, 2n + 1 on an odd last level) get them with their own digit
    // appended. Backwards, so that no entry is overwritten before it is read.
    // The hashes are independent of one another and overlap in the pipeline.
    // The last level also stores each sample's Sobol' dimension 1 part, from
    // the value in hand: reading the entries back after the level's stores
    // waited for those stores (a quarter of this function's time).
    uint16_t* row = lowTable_.data() + tableRow(d);
    uint32_t* sobol1 = lowSobol1_.data() + tableRow(d);
    // Below 2^8, so the first byte's table alone (reversedSobol1).
    static_assert(kMaxTableLog2Spp <= 8);
    const uint32_t* bytes = reversedSobol1Bytes_;
    const int odd = log2Spp_ & 1;
    row[0] = 0;
    uint64_t count = 1;
    // A level's permutations: from the lanes' kernel for levels of 16 or 64
    // nodes (64 and 256 spp's last), one by one for the smaller ones.
    uint8_t permutations[size_t(1) << (kMaxTableLog2Spp - 2)];
    for (int shift = log2Spp_ - 2; shift >= odd; shift -= 2, count *= 4) {
        const uint64_t pixelDigits = pixelMorton_ >> (shift + 2);
        const bool last = !odd && shift == 0;
        const bool lanes = count >= 16;
        if (lanes) zsobol::digitPermutations(pixelDigits, salt, uint32_t(count), permutations);
        for (uint64_t n = count; n-- > 0;) {
            const unsigned perm =
                lanes ? permutations[n] : zsobol::digitPermutation(pixelDigits | n, salt);
            const auto prefix = uint16_t(row[n] << 2);
            for (unsigned digit = 0; digit < 4; ++digit) {
                const auto value = uint16_t(prefix | ((perm >> (2 * digit)) & 3));
                row[4 * n + digit] = value;
                if (last) sobol1[4 * n + digit] = bytes[value];
            }
        }
    }
    if (odd) {
        const uint64_t pixelDigits = pixelMorton_ >> 1;
        for (uint64_t n = count; n-- > 0;) {
            const auto flip = uint16_t(mixBits((pixelDigits | n) ^ salt) & 1);
            const auto prefix = uint16_t(row[n] << 1);
            row[2 * n] = uint16_t(prefix | flip);
            row[2 * n + 1] = uint16_t(prefix | (flip ^ 1));
            sobol1[2 * n] = bytes[prefix | flip];
            sobol1[2 * n + 1] = bytes[prefix | (flip ^ 1)];
        }
    }
}

void ZSobolSampler::fillHighDigits(CachedDimension& c) const {
    // The digits at or above bit log2Spp_ (digit boundaries fall on it for
    // even and odd log2Spp_ alike) and the digits above them come from the
    // pixel only. A digit's permuted value depends on the Morton bits at and
    // above it, so the digits above the highest bit in which this pixel's code
    // differs from the one the entry was computed for keep their values: from
    // one pixel of a tile to the next, about two digits are hashed instead of
    // all of them (log2 of the resolution).
    const int odd = log2Spp_ & 1;
    const uint64_t morton = mortonIndex_ >> log2Spp_ << log2Spp_;
    int shift = 2 * (base4Digits_ - 1) - odd;
    uint64_t index = 0;
    if (c.highMorton != ~uint64_t(0)) {
        const uint64_t changed = morton ^ c.highMorton;
        if (changed == 0) return;
        const int highestChanged = 63 - __builtin_clzll(changed);
        while (shift > highestChanged) shift -= 2;
        index = shift + 2 < 64 ? c.highIndex >> (shift + 2) << (shift + 2) : 0;
    }
    for (; shift >= log2Spp_; shift -= 2)
        index |= uint64_t(zsobol::permuteDigit((mortonIndex_ >> shift) & 3,
                                               mortonIndex_ >> (shift + 2), c.salt))
                 << shift;
    // Sobol' dimension 1 is linear over GF(2): only the changed bits' part
    // (the first time, all of them: both start at zero).
    c.reversedSobol1High ^= reverseBits32(sobolBits(matrices_, index ^ c.highIndex, 1));
    c.highIndex = index;
    c.highMorton = morton;
}

}  // namespace pathlab
