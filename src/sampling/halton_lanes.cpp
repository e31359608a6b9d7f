// The scrambled Halton samplers' lane draws: one tabulated dimension's digits
// for kCameraPacketSamples Halton indices, four lanes to an AVX2 register.
// All lanes of a call share the base and the digit count, so one loop serves
// them; the arithmetic is exact, so each lane's float is, bit for bit, what
// the scalar digit loops of halton.h give (tested):
//   - ⌊a / b⌋ in double precision: for integral a < 2^32, (a + ½)/b lies at
//     least ½/b ≥ 2^-14 from an integer, and the product (a + ½)·RN(1/b)
//     misses it by under 2^-19, so its floor is the quotient;
//   - the digits, the node prefixes and the scrambled integer stay below 2^52
//     (b^digits < 2^51 for every base), where doubles are exact integers;
//   - Owen's node hash is mixBits's 64-bit multiplies built from 32 × 32-bit
//     ones (AVX2 has no 64-bit multiply);
//   - the final scale and floatBelow are the scalar code's operations.
// Processors without AVX2 run the scalar loops lane by lane.
#include <immintrin.h>

#include "core/simd_target.h"
#include "sampling/halton.h"

namespace pathlab {

constexpr int kRegisterLanes = 4;

PATHLAB_AVX2_BEGIN
namespace avx2 {
namespace {

constexpr int kRegisters = kCameraPacketSamples / kRegisterLanes;
static_assert(kRegisters * kRegisterLanes == kCameraPacketSamples);

// Integers below 2^52 to doubles and back, exactly: 2^52's exponent leaves the
// mantissa's 52 bits for the integer.
__m256d exactDouble(__m256i a) {
    const __m256i magic = _mm256_castpd_si256(_mm256_set1_pd(0x1p52));
    return _mm256_sub_pd(_mm256_castsi256_pd(_mm256_or_si256(a, magic)), _mm256_set1_pd(0x1p52));
}
__m256i exactInteger(__m256d x) {
    const __m256d magic = _mm256_set1_pd(0x1p52);
    return _mm256_xor_si256(_mm256_castpd_si256(_mm256_add_pd(x, magic)),
                            _mm256_castpd_si256(magic));
}

// One base's constants, and the digit loop's common step.
struct Digits {
    __m256d base, inverse, half = _mm256_set1_pd(0.5);
    explicit Digits(uint32_t b) : base(_mm256_set1_pd(b)), inverse(_mm256_set1_pd(1.0 / b)) {}
    // The lowest digit of a, returned; a becomes ⌊a / b⌋.
    __m256d next(__m256d& a) const {
        const __m256d quotient = _mm256_floor_pd(_mm256_mul_pd(_mm256_add_pd(a, half), inverse));
        const __m256d digit = _mm256_sub_pd(a, _mm256_mul_pd(quotient, base));
        a = quotient;
        return digit;
    }
    // v · b + digit, exact below 2^53.
    __m256d append(__m256d v, __m256d digit) const {
        return _mm256_add_pd(_mm256_mul_pd(v, base), digit);
    }
};

// x · c mod 2^64 from three 32 × 32 → 64-bit products.
__m256i multiply64(__m256i x, uint64_t c) {
    const __m256i low = _mm256_set1_epi64x(int64_t(c & 0xffffffffu));
    const __m256i high = _mm256_set1_epi64x(int64_t(c >> 32));
    const __m256i cross = _mm256_add_epi64(_mm256_mul_epu32(_mm256_srli_epi64(x, 32), low),
                                           _mm256_mul_epu32(x, high));
    return _mm256_add_epi64(_mm256_mul_epu32(x, low), _mm256_slli_epi64(cross, 32));
}

// core/hash.h's mixBits, lane by lane.
__m256i mixBitsLanes(__m256i v) {
    v = _mm256_xor_si256(v, _mm256_srli_epi64(v, 31));
    v = multiply64(v, 0x7fb5d329728ea185ULL);
    v = _mm256_xor_si256(v, _mm256_srli_epi64(v, 27));
    v = multiply64(v, 0x81dadef4bc2dd44dULL);
    return _mm256_xor_si256(v, _mm256_srli_epi64(v, 33));
}

// floatBelow (halton.h) of four doubles.
__m128 floatBelowLanes(__m256d v) {
    const __m128 rounded = _mm256_cvtpd_ps(v);
    const __m256 up = _mm256_castpd_ps(_mm256_cmp_pd(_mm256_cvtps_pd(rounded), v, _CMP_GT_OQ));
    // The low halves of the four 64-bit masks: −1 where rounding went up.
    const __m128 up32 = _mm_shuffle_ps(_mm256_castps256_ps128(up), _mm256_extractf128_ps(up, 1),
                                       _MM_SHUFFLE(2, 0, 2, 0));
    const __m128i below = _mm_add_epi32(_mm_castps_si128(rounded), _mm_castps_si128(up32));
    return _mm_min_ps(_mm_castsi128_ps(below), _mm_set1_ps(kOneMinusEpsilon));
}

void loadIndices(const uint64_t* a, int registers, __m256d* x) {
    for (int h = 0; h < registers; ++h)
        x[h] = exactDouble(
            _mm256_loadu_si256(reinterpret_cast<const __m256i*>(a + h * kRegisterLanes)));
}

void storeScaled(const HaltonDimension& t, const __m256d* reversed, int registers, float* out) {
    const __m256d scale = _mm256_set1_pd(t.scale);
    for (int h = 0; h < registers; ++h)
        _mm_storeu_ps(out + h * kRegisterLanes, floatBelowLanes(_mm256_mul_pd(reversed[h], scale)));
}

}  // namespace

// Every digit down to float precision: digits past a's last are zeros, whose
// scrambled values add up to the tail the scalar loop appends — the same integer.
// Two digits per step where the dimension has a pair table, as the scalar loop.
void randomDigitLanes(const HaltonDimension& t, const uint64_t* a, int registers, float* out) {
    const Digits digits(t.base);
    __m256d x[kRegisters], reversed[kRegisters];
    loadIndices(a, registers, x);
    for (int h = 0; h < registers; ++h) reversed[h] = _mm256_setzero_pd();
    int k = 0;
    if (t.pairs32) {
        const auto base2 = uint32_t(t.pairDivider.base);
        const Digits pairs(base2);
        for (; k + 1 < t.digits; k += 2) {
            const int32_t* scrambled = t.pairs32 + size_t(k / 2) * base2;
            for (int h = 0; h < registers; ++h) {
                const __m256i pair = exactInteger(pairs.next(x[h]));
                const __m128i value = _mm256_i64gather_epi32(scrambled, pair, 4);
                reversed[h] = pairs.append(reversed[h], _mm256_cvtepi32_pd(value));
            }
        }
    }
    for (; k < t.digits; ++k) {
        const int32_t* scrambled = t.scrambledDigits32 + size_t(k) * t.base;
        for (int h = 0; h < registers; ++h) {
            const __m256i digit = exactInteger(digits.next(x[h]));
            const __m128i value = _mm256_i64gather_epi32(scrambled, digit, 4);
            reversed[h] = digits.append(reversed[h], _mm256_cvtepi32_pd(value));
        }
    }
    storeScaled(t, reversed, registers, out);
}

// Digit k's rotation is hashed from (seed, dimension, k, the digits above k):
// owenRotation, whose prefix is below 2^56, so `|` and `^` agree.
void owenLanes(const HaltonDimension& t, const uint64_t* a, int registers, float* out) {
    const Digits digits(t.base);
    const __m256i base = _mm256_set1_epi64x(t.base), largestDigit = _mm256_set1_epi64x(t.base - 1);
    __m256d x[kRegisters], prefix[kRegisters], reversed[kRegisters];
    loadIndices(a, registers, x);
    for (int h = 0; h < registers; ++h) prefix[h] = reversed[h] = _mm256_setzero_pd();
    for (int k = 0; k < t.digits; ++k) {
        const __m256i level = _mm256_set1_epi64x(int64_t(t.owenHash ^ (uint64_t(k) << 56)));
        for (int h = 0; h < registers; ++h) {
            const __m256d digitValue = digits.next(x[h]);
            const __m256i digit = exactInteger(digitValue);
            const __m256i node = mixBitsLanes(_mm256_xor_si256(level, exactInteger(prefix[h])));
            const __m256i rotation =
                _mm256_srli_epi64(_mm256_mul_epu32(_mm256_srli_epi64(node, 32), base), 32);
            __m256i rotated = _mm256_add_epi64(digit, rotation);
            rotated = _mm256_sub_epi64(
                rotated, _mm256_and_si256(base, _mm256_cmpgt_epi64(rotated, largestDigit)));
            const __m128i value = _mm256_i64gather_epi32(t.permutation32, rotated, 4);
            reversed[h] = digits.append(reversed[h], _mm256_cvtepi32_pd(value));
            prefix[h] = digits.append(prefix[h], digitValue);
        }
    }
    storeScaled(t, reversed, registers, out);
}

}  // namespace avx2
PATHLAB_AVX2_END

// Lanes in registers of four, as many as the live lanes fill; one or two live
// lanes are cheaper lane by lane.
void randomDigitScrambledLanes(const HaltonDimension& t, const uint64_t* a, int count, float* out) {
    if (count > 2 && cpuHasAvx2())
        return avx2::randomDigitLanes(t, a, (count + kRegisterLanes - 1) / kRegisterLanes, out);
    for (int j = 0; j < count; ++j) out[j] = randomDigitScrambled(t, a[j]);
}

void owenScrambledLanes(const HaltonDimension& t, const uint64_t* a, int count, float* out) {
    if (count > 2 && cpuHasAvx2())
        return avx2::owenLanes(t, a, (count + kRegisterLanes - 1) / kRegisterLanes, out);
    for (int j = 0; j < count; ++j) out[j] = owenScrambled(t, a[j]);
}

}  // namespace pathlab
