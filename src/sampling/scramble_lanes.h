// The arithmetic of lane draws (sampler.h, drawLanes1D/2D) for the Owen-
// scrambled Sobol' samplers: kCameraPacketSamples samples side by side, pure
// 32-bit integer operations in SIMD lanes. Out of line so that it can be
// compiled for AVX2 and chosen at run time (eight lanes in one register; the
// x86-64 baseline has no 32-bit vector multiply); the bits are the same
// whichever version runs.
#pragma once

#include <cstdint>

namespace pathlab {

// Burley 2020's shuffled, scrambled Sobol' dimension 0 (and, for the 2D form,
// dimension 1) of the lanes' sample indices:
//   i = R(L_indexSeed(R(index))), x = R(L_xSeed(i)), y = R(L_ySeed(Z(i))),
// R the bit reversal, L the Laine–Karras permutation, Z the superset transform
// (lowdiscrepancy.h) — the values OwenSobolSampler::get1D/get2D compute, as
// floats (fixedPointToFloat).
void owenSobolLanes1D(const uint32_t* index, uint32_t indexSeed, uint32_t valueSeed, float* x);
void owenSobolLanes2D(const uint32_t* index, uint32_t indexSeed, uint32_t xSeed, uint32_t ySeed,
                      float* x, float* y);

// x = R(L_xSeed(a)), y = R(L_ySeed(b)) as floats: the last step of ZSobol's
// draws, given the lanes' permuted indices a and their bit-reversed Sobol'
// dimension 1, b.
void laineKarrasLanes1D(const uint32_t* a, uint32_t xSeed, float* x);
void laineKarrasLanes2D(const uint32_t* a, const uint32_t* b, uint32_t xSeed, uint32_t ySeed,
                        float* x, float* y);

}  // namespace pathlab
