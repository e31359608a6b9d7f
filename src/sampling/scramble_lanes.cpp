#include "sampling/scramble_lanes.h"

#include "sampling/lowdiscrepancy.h"
#include "sampling/sampler.h"

namespace pathlab {

// Every function is compiled twice, for AVX2 and for the x86-64 baseline, and
// the loader picks one for the processor (GCC's and Clang's target_clones).
// Integer operations and an exact int-to-float conversion: the same bits from both.
#define PATHLAB_LANES [[gnu::target_clones("avx2", "default")]]

PATHLAB_LANES void owenSobolLanes1D(const uint32_t* index, uint32_t indexSeed, uint32_t valueSeed,
                                    float* x) {
    for (int j = 0; j < kCameraPacketSamples; ++j) {
        const uint32_t i =
            reverseBits32(laineKarrasPermutation(reverseBits32(index[j]), indexSeed));
        x[j] = fixedPointToFloat(reverseBits32(laineKarrasPermutation(i, valueSeed)));
    }
}

PATHLAB_LANES void owenSobolLanes2D(const uint32_t* index, uint32_t indexSeed, uint32_t xSeed,
                                    uint32_t ySeed, float* x, float* y) {
    for (int j = 0; j < kCameraPacketSamples; ++j) {
        const uint32_t i =
            reverseBits32(laineKarrasPermutation(reverseBits32(index[j]), indexSeed));
        x[j] = fixedPointToFloat(reverseBits32(laineKarrasPermutation(i, xSeed)));
        y[j] = fixedPointToFloat(
            reverseBits32(laineKarrasPermutation(sobolSupersetTransform32(i), ySeed)));
    }
}

PATHLAB_LANES void laineKarrasLanes1D(const uint32_t* a, uint32_t xSeed, float* x) {
    for (int j = 0; j < kCameraPacketSamples; ++j)
        x[j] = fixedPointToFloat(reverseBits32(laineKarrasPermutation(a[j], xSeed)));
}

PATHLAB_LANES void laineKarrasLanes2D(const uint32_t* a, const uint32_t* b, uint32_t xSeed,
                                      uint32_t ySeed, float* x, float* y) {
    for (int j = 0; j < kCameraPacketSamples; ++j) {
        x[j] = fixedPointToFloat(reverseBits32(laineKarrasPermutation(a[j], xSeed)));
        y[j] = fixedPointToFloat(reverseBits32(laineKarrasPermutation(b[j], ySeed)));
    }
}

}  // namespace pathlab
