// The Halton samplers' lane draws: one tabulated dimension's digits
// for kCameraPacketSamples Halton indices, four lanes to an AVX2 register.
// All lanes of a call share the base and the digit count, so one loop serves
// them; the arithmetic is exact, so each lane's float is, bit for bit, what
// the scalar digit loops of halton.h give (tested):
//   - ⌊a / b⌋ in double precision: for integral a < 2^32 and b ≤ 61² (the
//     pair tables' largest divisor), (a + ½)/b lies at least ½/b > 2^-13 from
//     an integer, and the product (a + ½)·RN(1/b) misses it by under 2^-21
//     (fused as a·RN(1/b) + RN(1/b)/2 where the processor has AVX-512), so
//     its floor is the quotient;
//   - the digits, the node prefixes and the scrambled integer stay below 2^52
//     (b^digits < 2^42 for every tabulated base), where doubles are exact;
//   - Owen's node hash is core/hash.h's code on 64-bit lanes (GCC builds
//     their multiplies from 32 × 32-bit ones where the processor has no 64-bit
//     lane multiply, AVX2 alone);
//   - the final scale and floatBelow are the scalar code's operations.
// Processors without AVX2 run the scalar loops lane by lane; those with
// AVX-512DQ and VL run the AVX2 code with their 64-bit lane multiply, and
// those with AVX-512BW and VBMI too look up Owen's permutations and child
// rotations, and the random-digit scramble's digits and small pairs of
// digits (two registers of lanes), with byte permutes instead of gathers.
#include <immintrin.h>

#include "core/simd_target.h"
#include "sampling/halton.h"

namespace pathlab {

constexpr int kRegisterLanes = 4;

PATHLAB_AVX2_BEGIN
namespace avx2 {
#define PATHLAB_LANES_FMA 0
#define PATHLAB_LANES_VBMI 0
#include "sampling/halton_lanes_kernels.inc"
#undef PATHLAB_LANES_VBMI
#undef PATHLAB_LANES_FMA
}  // namespace avx2
PATHLAB_AVX2_END

PATHLAB_AVX512_BEGIN
namespace avx512 {
#define PATHLAB_LANES_FMA 1
#define PATHLAB_LANES_VBMI 0
#include "sampling/halton_lanes_kernels.inc"
#undef PATHLAB_LANES_VBMI
#undef PATHLAB_LANES_FMA
}  // namespace avx512
PATHLAB_AVX512_END

PATHLAB_AVX512_VBMI_BEGIN
namespace avx512vbmi {
#define PATHLAB_LANES_FMA 1
#define PATHLAB_LANES_VBMI 1
#include "sampling/halton_lanes_kernels.inc"
#undef PATHLAB_LANES_VBMI
#undef PATHLAB_LANES_FMA
}  // namespace avx512vbmi
PATHLAB_AVX512_VBMI_END

namespace {
// Lanes in registers of four, as many as the live lanes fill; one or two live
// lanes are cheaper lane by lane (the scalar loops).
int registersFor(int count) {
    return (count + kRegisterLanes - 1) / kRegisterLanes;
}

// kernel(LaneKernels of the best instruction set up to `limit`, registers) for
// three or more live lanes (two for Owen's kernel with byte permutes, which
// draws one register of lanes in less time than two scalar loops:
// HaltonLanes/owen/…/lanes:2 in pathlab_bench); otherwise, or without AVX2,
// scalar(j) for each lane. Inlined into each caller, as the switches it
// replaces were: out of line it added a call per draw (halton-owen frames
// about 1% slower).
template <bool kTwoLanesOnVbmi = false, class Kernel, class Scalar>
[[gnu::always_inline]] inline void dispatch(int count, SimdLevel limit, const Kernel& kernel,
                                            const Scalar& scalar) {
    const SimdLevel best = simdLevelUpTo(limit);
    const int fewestLanes = kTwoLanesOnVbmi && best == SimdLevel::Avx512Vbmi ? 2 : 3;
    switch (count >= fewestLanes ? best : SimdLevel::Baseline) {
        case SimdLevel::Avx512Vbmi:
            return kernel(avx512vbmi::LaneKernels{}, registersFor(count));
        case SimdLevel::Avx512:
            return kernel(avx512::LaneKernels{}, registersFor(count));
        case SimdLevel::Avx2:
            return kernel(avx2::LaneKernels{}, registersFor(count));
        case SimdLevel::Baseline:
            for (int j = 0; j < count; ++j) scalar(j);
    }
}
}  // namespace

void randomDigitScrambledLanes(const HaltonDimension& t, const uint64_t* a, int count, float* out,
                               SimdLevel limit) {
    dispatch(
        count, limit,
        [&](auto kernels, int registers) { kernels.randomDigit(t, a, registers, out); },
        [&](int j) { out[j] = randomDigitScrambled(t, a[j]); });
}

void radicalInverseLanes(const PrimeBase& b, const uint64_t* a, int count, float* out,
                         SimdLevel limit) {
    dispatch(
        count, limit,
        [&](auto kernels, int registers) { kernels.radicalInverse(b, a, registers, out); },
        [&](int j) { out[j] = radicalInverse(b, a[j]); });
}

void owenScrambledLanes(const HaltonDimension& t, const uint64_t* a, int count, float* out,
                        SimdLevel limit) {
    dispatch<true>(
        count, limit, [&](auto kernels, int registers) { kernels.owen(t, a, registers, out); },
        [&](int j) { out[j] = owenScrambled(t, a[j]); });
}

// The 2D draws' two dimensions in one call: one dispatch for both.
void randomDigitScrambledLanes2D(const HaltonDimension& tx, const HaltonDimension& ty,
                                 const uint64_t* a, int count, float* x, float* y,
                                 SimdLevel limit) {
    dispatch(
        count, limit,
        [&](auto kernels, int registers) {
            kernels.randomDigit(tx, a, registers, x);
            kernels.randomDigit(ty, a, registers, y);
        },
        [&](int j) {
            x[j] = randomDigitScrambled(tx, a[j]), y[j] = randomDigitScrambled(ty, a[j]);
        });
}

void radicalInverseLanes2D(const PrimeBase& bx, const PrimeBase& by, const uint64_t* a, int count,
                           float* x, float* y, SimdLevel limit) {
    dispatch(
        count, limit,
        [&](auto kernels, int registers) {
            kernels.radicalInverse(bx, a, registers, x);
            kernels.radicalInverse(by, a, registers, y);
        },
        [&](int j) { x[j] = radicalInverse(bx, a[j]), y[j] = radicalInverse(by, a[j]); });
}

void owenScrambledLanes2D(const HaltonDimension& tx, const HaltonDimension& ty, const uint64_t* a,
                          int count, float* x, float* y, SimdLevel limit) {
    dispatch<true>(
        count, limit,
        [&](auto kernels, int registers) {
            kernels.owen(tx, a, registers, x);
            kernels.owen(ty, a, registers, y);
        },
        [&](int j) { x[j] = owenScrambled(tx, a[j]), y[j] = owenScrambled(ty, a[j]); });
}

}  // namespace pathlab
