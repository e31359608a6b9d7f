#include "sampling/scramble_lanes.h"

#include <immintrin.h>

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

// The paired scramble with AVX-512 BW: both dimensions' eight lanes in one
// register, each lane with its dimension's seed. The bit reversal is a byte
// swap and a nibble-table lookup per byte (vpshufb), and the pairs are
// interleaved by one permute: about a third of the AVX2 loop's instructions.
PATHLAB_AVX512_VBMI_BEGIN
namespace avx512bw {
// The masked forms with every lane set: GCC 12's unmasked ones pass an
// undefined operand that -Wall reports.
constexpr __mmask16 kAllLanes = 0xffff;

__m512i broadcastBytes(__m128i bytes) {
    return _mm512_maskz_broadcast_i32x4(kAllLanes, bytes);
}

void owenScrambleReversed2D(const uint32_t* reversedX, const uint32_t* reversedY, uint32_t xSeed,
                            uint32_t ySeed, float* xy) {
    static_assert(kCameraPacketSamples == 8, "one 256-bit half per dimension");
    constexpr __mmask16 kYLanes = 0xff00;
    const __m512i v0 = _mm512_mask_blend_epi32(
        kYLanes,
        _mm512_maskz_broadcast_i64x4(
            0xff, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(reversedX))),
        _mm512_maskz_broadcast_i64x4(
            0xff, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(reversedY))));
    const __m512i seed = _mm512_mask_blend_epi32(kYLanes, _mm512_set1_epi32(int(xSeed)),
                                                 _mm512_set1_epi32(int(ySeed)));
    const __m512i multiplier =
        _mm512_or_si512(_mm512_maskz_srli_epi32(kAllLanes, seed, 16), _mm512_set1_epi32(1));
    // laineKarrasPermutation (lowdiscrepancy.h), lane by lane.
    __m512i v = _mm512_xor_si512(v0, _mm512_mullo_epi32(v0, _mm512_set1_epi32(0x3d20adea)));
    v = _mm512_mullo_epi32(_mm512_add_epi32(v, seed), multiplier);
    v = _mm512_xor_si512(v, _mm512_mullo_epi32(v, _mm512_set1_epi32(0x05526c56)));
    v = _mm512_xor_si512(v, _mm512_mullo_epi32(v, _mm512_set1_epi32(0x53a22864)));
    // reverseBits32: bytes swapped within each lane, each byte's bits reversed
    // as two nibbles looked up in a 16-entry table.
    const __m512i byteSwap =
        broadcastBytes(_mm_setr_epi8(3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15, 14, 13, 12));
    const __m512i nibbleReversed =
        broadcastBytes(_mm_setr_epi8(0, 8, 4, 12, 2, 10, 6, 14, 1, 9, 5, 13, 3, 11, 7, 15));
    const __m512i lowNibbles = _mm512_set1_epi8(0x0f);
    v = _mm512_shuffle_epi8(v, byteSwap);
    const __m512i high = _mm512_shuffle_epi8(nibbleReversed, _mm512_and_si512(v, lowNibbles));
    const __m512i low =
        _mm512_shuffle_epi8(nibbleReversed, _mm512_and_si512(_mm512_srli_epi16(v, 4), lowNibbles));
    v = _mm512_or_si512(_mm512_slli_epi16(high, 4), low);
    // fixedPointToFloat: the top 24 bits, exactly, times 2^-24.
    const __m512 values =
        _mm512_mul_ps(_mm512_maskz_cvtepi32_ps(kAllLanes, _mm512_maskz_srli_epi32(kAllLanes, v, 8)),
                      _mm512_set1_ps(0x1p-24f));
    const __m512i pairs = _mm512_setr_epi32(0, 8, 1, 9, 2, 10, 3, 11, 4, 12, 5, 13, 6, 14, 7, 15);
    _mm512_storeu_ps(xy, _mm512_maskz_permutexvar_ps(kAllLanes, pairs, values));
}
}  // namespace avx512bw
PATHLAB_AVX512_VBMI_END

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

void owenScrambleReversedLanes2D(const uint32_t* reversedX, const uint32_t* reversedY,
                                 uint32_t xSeed, uint32_t ySeed, float* xy, SimdLevel limit) {
    if (simdLevelUpTo(limit) >= SimdLevel::Avx512Vbmi)
        return avx512bw::owenScrambleReversed2D(reversedX, reversedY, xSeed, ySeed, xy);
    if (useAvx2(limit)) return avx2::owenScrambleReversed2D(reversedX, reversedY, xSeed, ySeed, xy);
    baseline::owenScrambleReversed2D(reversedX, reversedY, xSeed, ySeed, xy);
}

namespace {
// Cycle walking (lowdiscrepancy.h) for the `count` elements a first round
// left outside [0, n). None can be when n is a power of two (the round's
// range is [0, n) itself), and there the check is skipped: reading each
// element back just after the vector stores wrote it was 2% of a one-thread
// profile of a stratified frame at 64 spp, nearly all on the loads.
void walkIntoRange(const PermutationDomain& d, uint32_t s0, uint32_t s1, uint32_t* out,
                   uint32_t count) {
    const uint32_t n = d.n;
    if ((n & (n - 1)) == 0) return;
    for (uint32_t i = 0; i < count; ++i)
        while (out[i] >= n) out[i] = permuteInRange(out[i], d, s0, s1);
}
}  // namespace

void permutationTable(const PermutationDomain& d, uint64_t seed, uint32_t* out, SimdLevel limit) {
    // n ≤ 1 needs no case of its own: the range is {0} (mask 0), or empty.
    const auto s0 = static_cast<uint32_t>(seed), s1 = static_cast<uint32_t>(seed >> 32);
    if (useAvx2(limit))
        avx2::permutationRound(d, s0, s1, out);
    else
        baseline::permutationRound(d, s0, s1, out);
    walkIntoRange(d, s0, s1, out, d.n);
}

void permutationLanes(const PermutationDomain& d, uint64_t seed, const uint32_t* index,
                      uint32_t* out, SimdLevel limit) {
    const auto s0 = static_cast<uint32_t>(seed), s1 = static_cast<uint32_t>(seed >> 32);
    if (useAvx2(limit))
        avx2::permutationLanesRound(d, s0, s1, index, out);
    else
        baseline::permutationLanesRound(d, s0, s1, index, out);
    walkIntoRange(d, s0, s1, out, kCameraPacketSamples);
}

}  // namespace pathlab
