// The arithmetic of `sobol-owen`'s and `zsobol`'s lane draws (sampler.h,
// drawLanes1D/2D) and of `stratified`'s permutation tables: many independent
// values side by side — a camera packet's kCameraPacketSamples samples, or a
// permutation's elements — in pure 32-bit integer operations. Out of line so
// that it can be compiled for AVX2 and chosen at run time (eight lanes in one
// register; GCC does not vectorise the 32-bit multiplies for the x86-64
// baseline); the bits are the same whichever version runs. `limit` caps the
// instruction set (tests run each one).
#pragma once

#include <cstdint>

#include "core/simd_target.h"
#include "sampling/lowdiscrepancy.h"

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

// Owen scrambles of values given bit-reversed (zsobol's permuted indices and
// Sobol' dimension 1): x = owenScramble(R(reversed), seed) =
// R(L_seed(reversed)), as floats.
void owenScrambleReversedLanes(const uint32_t* reversed, uint32_t seed, float* x,
                               SimdLevel limit = SimdLevel::Avx512);
// Both dimensions of a 2D draw in one call, written as pairs:
// xy[2j] = R(L_xSeed(reversedX[j])), xy[2j + 1] = R(L_ySeed(reversedY[j])).
void owenScrambleReversedLanes2D(const uint32_t* reversedX, const uint32_t* reversedY,
                                 uint32_t xSeed, uint32_t ySeed, float* xy,
                                 SimdLevel limit = SimdLevel::Avx512Vbmi);

// out[i] = permutationElement(i, d.n, seed) (lowdiscrepancy.h) for every i
// in [0, d.n): a whole permutation, its elements side by side. One element's
// multiply chain is long; a table made in one loop pays it once.
void permutationTable(const PermutationDomain& d, uint64_t seed, uint32_t* out,
                      SimdLevel limit = SimdLevel::Avx512);
// out[j] = permutationElement(index[j], d.n, seed) for the kCameraPacketSamples
// lanes (every index below d.n, the lanes past the live ones too): a lane
// draw's elements alone, for a dimension few of a pixel's samples draw.
void permutationLanes(const PermutationDomain& d, uint64_t seed, const uint32_t* index,
                      uint32_t* out, SimdLevel limit = SimdLevel::Avx512);

}  // namespace pathlab
