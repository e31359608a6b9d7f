#include "sampling/scramble_lanes.h"

#include "core/simd_target.h"
#include "sampling/lowdiscrepancy.h"
#include "sampling/sampler.h"

namespace pathlab {

// Every function is compiled twice, for the x86-64 baseline and for AVX2, and
// the processor's best is chosen at run time (core/simd_target.h). Integer
// operations and an exact int-to-float conversion: the same bits from both.
namespace baseline {
#include "sampling/scramble_lanes_kernels.inc"
}  // namespace baseline

PATHLAB_AVX2_BEGIN
namespace avx2 {
#include "sampling/scramble_lanes_kernels.inc"
}  // namespace avx2
PATHLAB_AVX2_END

namespace {
bool useAvx2(SimdLevel limit) {
    return simdLevelUpTo(limit) >= SimdLevel::Avx2;
}
}  // namespace

void owenSobolLanes1D(const uint32_t* index, uint32_t indexSeed, uint32_t valueSeed, float* x) {
    if (cpuHasAvx2()) return avx2::owenSobol1D(index, indexSeed, valueSeed, x);
    baseline::owenSobol1D(index, indexSeed, valueSeed, x);
}

void owenSobolLanes2D(const uint32_t* index, uint32_t indexSeed, uint32_t xSeed, uint32_t ySeed,
                      float* x, float* y) {
    if (cpuHasAvx2()) return avx2::owenSobol2D(index, indexSeed, xSeed, ySeed, x, y);
    baseline::owenSobol2D(index, indexSeed, xSeed, ySeed, x, y);
}

void owenScrambleReversedLanes(const uint32_t* reversed, uint32_t seed, float* x, SimdLevel limit) {
    if (useAvx2(limit)) return avx2::owenScrambleReversed(reversed, seed, x);
    baseline::owenScrambleReversed(reversed, seed, x);
}

void permutationTable(const PermutationDomain& d, uint64_t seed, uint32_t* out, SimdLevel limit) {
    // n ≤ 1 needs no case of its own: the range is {0} (mask 0), or empty.
    const auto s0 = static_cast<uint32_t>(seed), s1 = static_cast<uint32_t>(seed >> 32);
    if (useAvx2(limit))
        avx2::permutationRound(d, s0, s1, out);
    else
        baseline::permutationRound(d, s0, s1, out);
    // Cycle walking (lowdiscrepancy.h) for the elements the first round left
    // outside [0, n). None can be when n is a power of two (the round's range
    // is [0, n) itself), and there the check is skipped: reading each element
    // back just after the vector stores wrote it was 2% of a one-thread
    // profile of a stratified frame at 64 spp, nearly all on the loads.
    const uint32_t n = d.n;
    if ((n & (n - 1)) == 0) return;
    for (uint32_t i = 0; i < n; ++i)
        while (out[i] >= n) out[i] = permuteInRange(out[i], d, s0, s1);
}

}  // namespace pathlab
