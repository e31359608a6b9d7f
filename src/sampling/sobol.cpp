#include "sampling/sobol.h"

#include <stdexcept>

namespace pathlab {
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
    uint64_t low = 0;
    for (int c = 0; target != 0; ++c, target >>= 1)
        if (target & 1) low ^= inverse[c];
    return high | low;
}

ZSobolSampler::ZSobolSampler(const SamplerConfig& c)
    : spp_(c.samplesPerPixel), seed_(c.seed), matrices_(sobolMatrices()) {
    log2Spp_ = log2Ceil(uint64_t(std::max(1, c.samplesPerPixel)));
    const int log2Resolution = log2Ceil(uint64_t(std::max({1, c.resolution.x, c.resolution.y})));
    base4Digits_ = log2Resolution + (log2Spp_ + 1) / 2;
}

uint64_t ZSobolSampler::sampleIndex(int dimension) const {
    // The 24 permutations of {0,1,2,3}, as base-4 digits packed into a byte.
    static constexpr uint8_t kPermutations[24] = {0xe4, 0xb4, 0xd8, 0x78, 0x9c, 0x6c, 0xe1, 0xb1,
                                                  0xc9, 0x39, 0x8d, 0x2d, 0xd2, 0x72, 0xc6, 0x36,
                                                  0x4e, 0x1e, 0x93, 0x63, 0x87, 0x27, 0x4b, 0x1b};
    // With an odd power of two per pixel, the lowest "digit" is a single bit.
    const bool oddBits = log2Spp_ & 1;
    const uint64_t dimensionSalt = hashValues(dimension, seed_, 0x5a4fu);
    uint64_t index = 0;
    for (int i = base4Digits_ - 1; i >= (oddBits ? 1 : 0); --i) {
        const int shift = 2 * i - (oddBits ? 1 : 0);
        const unsigned digit = (mortonIndex_ >> shift) & 3;
        const uint64_t higherDigits = mortonIndex_ >> (shift + 2);
        const unsigned perm = kPermutations[(mixBits(higherDigits ^ dimensionSalt) >> 24) % 24];
        index |= uint64_t((perm >> (2 * digit)) & 3) << shift;
    }
    if (oddBits) index |= (mortonIndex_ & 1) ^ (mixBits((mortonIndex_ >> 1) ^ dimensionSalt) & 1);
    return index;
}

}  // namespace pathlab
