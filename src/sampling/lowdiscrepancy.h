// Building blocks of the low-discrepancy samplers: radical inverses (Halton),
// Sobol' generator matrices, binary scramblers (random digital shift, hash-based
// Owen scrambling), seeded permutations of [0, n) and Morton codes.
//
// Everything here is a pure function of its arguments, so samplers stay
// deterministic whatever order pixels are rendered in.
#pragma once

#include <algorithm>
#include <cstdint>

#include "core/hash.h"
#include "core/math.h"

namespace pathlab {

// ---------------------------------------------------------------------------
// Primes: the bases of the Halton sequence, dimension d using the d-th prime.
inline constexpr int kPrimeTableSize = 1000;  // 2, 3, 5, …, 7919
const int* primeTable();                      // kPrimeTableSize entries

// ---------------------------------------------------------------------------
// Bits.
//
// The few-instruction primitives of the samplers' inner loops are forced
// inline: the renderer instantiates every sampler in one translation unit, and
// once GCC's unit-growth limit is reached it calls them out of line (measured:
// sobol-owen 25% slower when the ZSobol and Halton fast paths were added).
[[gnu::always_inline]] constexpr uint32_t reverseBits32(uint32_t v) {
    v = (v << 16) | (v >> 16);
    v = ((v & 0x00ff00ffu) << 8) | ((v & 0xff00ff00u) >> 8);
    v = ((v & 0x0f0f0f0fu) << 4) | ((v & 0xf0f0f0f0u) >> 4);
    v = ((v & 0x33333333u) << 2) | ((v & 0xccccccccu) >> 2);
    v = ((v & 0x55555555u) << 1) | ((v & 0xaaaaaaaau) >> 1);
    return v;
}

// Two 32-bit reversals at once: the low half of the result is lo's reversal,
// the high half hi's — one 64-bit reversal (a byte swap and three mask-and-shift
// steps) instead of two 32-bit ones, for samplers that draw two dimensions.
[[gnu::always_inline]] constexpr uint64_t reverseBits32Pair(uint32_t lo, uint32_t hi) {
    uint64_t v = uint64_t(lo) << 32 | hi;
    v = __builtin_bswap64(v);
    v = ((v & 0x0f0f0f0f0f0f0f0fULL) << 4) | ((v & 0xf0f0f0f0f0f0f0f0ULL) >> 4);
    v = ((v & 0x3333333333333333ULL) << 2) | ((v & 0xccccccccccccccccULL) >> 2);
    v = ((v & 0x5555555555555555ULL) << 1) | ((v & 0xaaaaaaaaaaaaaaaaULL) >> 1);
    return v;
}

// A 32-bit fixed-point fraction (value · 2^-32) as a float in [0, 1). The low
// 8 bits are truncated rather than rounded, so the result is exact, never 1,
// and stays inside every dyadic interval the fixed-point value lies in —
// rounding up could move a point into the next stratum.
constexpr float fixedPointToFloat(uint32_t v) {
    return static_cast<float>(v >> 8) * 0x1p-24f;
}

// Interleaves the bits of x and y (x in the even bits): the Morton (Z-order)
// index of a pixel, used by ZSobol to walk the image along a space-filling curve.
constexpr uint64_t spreadBits32(uint32_t v) {
    uint64_t x = v;
    x = (x | (x << 16)) & 0x0000ffff0000ffffULL;
    x = (x | (x << 8)) & 0x00ff00ff00ff00ffULL;
    x = (x | (x << 4)) & 0x0f0f0f0f0f0f0f0fULL;
    x = (x | (x << 2)) & 0x3333333333333333ULL;
    x = (x | (x << 1)) & 0x5555555555555555ULL;
    return x;
}
constexpr uint64_t encodeMorton2(uint32_t x, uint32_t y) {
    return spreadBits32(x) | (spreadBits32(y) << 1);
}

constexpr int log2Ceil(uint64_t n) {
    int k = 0;
    while ((uint64_t(1) << k) < n) ++k;
    return k;
}

// ---------------------------------------------------------------------------
// Halton: the radical inverse Φ_b(a) = Σ d_k b^{-k-1} mirrors the base-b
// digits d_k of a about the radix point (Halton 1960).
float radicalInverse(int base, uint64_t a);

// Number of base-b digits that still change a float in [0,1): digits beyond it
// are lost to rounding, so scramblers stop there.
int floatDigitCount(int base);

// Division by a small base as a multiply, the hot operation of every radical
// inverse. For a < 2^32 the high half of a·⌈2^64/b⌉ is exactly ⌊a/b⌋: the
// rounding error a·(⌈2^64/b⌉ − 2^64/b)/2^64 < 2^-32 never reaches the 1/b gap
// between a/b's fractional part and the next integer (Granlund & Montgomery
// 1994, "Division by Invariant Integers using Multiplication"). For b ≥ 2:
// b = 1 would need the reciprocal 2^64, which wraps to 0.
struct BaseDivider {
    uint64_t base, reciprocal;
    explicit BaseDivider(uint32_t b) : base(b), reciprocal(~uint64_t(0) / b + 1) {}
    uint64_t quotient(uint64_t a) const {
        if (a >> 32) return a / base;
        return quotient32(a);
    }
    // For callers that have checked a < 2^32 once for a whole digit loop.
    uint64_t quotient32(uint64_t a) const {
        return static_cast<uint64_t>((static_cast<unsigned __int128>(a) * reciprocal) >> 64);
    }
};

// A prime base ready for digit loops: its divider and its rounded reciprocal.
// primeBases()[d] belongs to primeTable()[d]; built once, shared.
struct PrimeBase {
    BaseDivider divider;
    BaseDivider pairDivider;  // base²
    // [k]: 1.0 multiplied k times by the rounded 1.0 / base, as radicalInverse's
    // digit loop scales its integer, k ≤ 32.
    const double* inversePowers;
};
const PrimeBase* primeBases();

// radicalInverse(base, a) without its two divisions per call (the divider's
// reciprocal and the overflow limit): for a < 2^32 the mirrored integer has no
// more digits than a and cannot overflow. The same digits, the same integer and
// the same product of reciprocals, so the same float (tested).
// Two digits per step while a has two left: the chain of divisions through a,
// which sets the loop's latency, is half as long, and splitting the pair into
// its digits is off that chain. The scale is looked up by the digit count
// instead of multiplied up digit by digit (the same product, so the same bits).
inline float radicalInverse(const PrimeBase& b, uint64_t a) {
    if (a >> 32) return radicalInverse(int(b.divider.base), a);
    const uint64_t base = b.divider.base, base2 = b.pairDivider.base;
    uint64_t reversed = 0;
    int digits = 0;
    for (; a >= base; digits += 2) {
        const uint64_t next = b.pairDivider.quotient32(a);
        const uint64_t pair = a - next * base2;  // d_k + b·d_{k+1}
        const uint64_t upper = b.divider.quotient32(pair);
        reversed = reversed * base2 + (pair - upper * base) * base + upper;
        a = next;
    }
    if (a != 0) reversed = reversed * base + a, ++digits;
    return std::min(static_cast<float>(static_cast<double>(reversed) * b.inversePowers[digits]),
                    kOneMinusEpsilon);
}

// radicalInverse in base 2 for a < 2^32: the mirrored digits are a's bits
// reversed, and reverse(a)·2^-32 is the same exact double as the digit loop's
// mirrored integer times 2^-digits, so the same float (tested) — a dozen
// instructions instead of a chain of a dozen digit steps.
inline float radicalInverseBase2(uint32_t a) {
    return std::min(static_cast<float>(static_cast<double>(reverseBits32(a)) * 0x1p-32),
                    kOneMinusEpsilon);
}

// The index whose first `digits` base-b digits, mirrored, give `inverse`:
// Φ_b^{-1} restricted to `digits` digits (used for Halton's image-plane mapping).
constexpr uint64_t inverseRadicalInverse(uint64_t inverse, int base, int digits) {
    uint64_t index = 0;
    for (int i = 0; i < digits; ++i) {
        index = index * base + inverse % base;
        inverse /= base;
    }
    return index;
}

// ---------------------------------------------------------------------------
// Sobol' (Sobol' 1967) with the Joe–Kuo direction numbers ("Constructing Sobol
// sequences with better two-dimensional projections", SIAM J. Sci. Comput.
// 2008) as shipped in Boost (boost/random/detail/sobol_table.hpp: 3667
// dimensions). Dimension d of sample a is the GF(2) matrix–vector product
// C_d · a, written as the XOR of the columns selected by a's set bits.
inline constexpr int kSobolDimensions = 3667;
inline constexpr int kSobolMatrixColumns = 64;  // indices up to 2^64
// Column-major: column j of dimension d is sobolMatrices()[d * 64 + j], a 32-bit
// fraction whose most significant bit is 1/2.
const uint32_t* sobolMatrices();

// Sobol' dimension 1 without its matrix. Its direction numbers (polynomial
// x + 1, m_1 = 1) make C_1 Pascal's triangle mod 2: by Lucas' theorem, column k
// has bit j (weight 2^-j-1) set iff the binary digits of j are a subset of k's.
// So bit j of the product is the XOR of a's bits at the supersets of j — a
// superset-sum transform over the six bits of the position, six shift-XORs —
// then mirrored into a fraction. Equal to the matrix product (tested).
[[gnu::always_inline]] inline uint64_t sobolSupersetTransform(uint64_t a) {
    a ^= (a & 0xaaaaaaaaaaaaaaaaULL) >> 1;
    a ^= (a & 0xccccccccccccccccULL) >> 2;
    a ^= (a & 0xf0f0f0f0f0f0f0f0ULL) >> 4;
    a ^= (a & 0xff00ff00ff00ff00ULL) >> 8;
    a ^= (a & 0xffff0000ffff0000ULL) >> 16;
    a ^= (a & 0xffffffff00000000ULL) >> 32;
    return a;
}
// The same transform of a 32-bit index (its last step only moves bits above 32).
[[gnu::always_inline]] constexpr uint32_t sobolSupersetTransform32(uint32_t a) {
    a ^= (a & 0xaaaaaaaau) >> 1;
    a ^= (a & 0xccccccccu) >> 2;
    a ^= (a & 0xf0f0f0f0u) >> 4;
    a ^= (a & 0xff00ff00u) >> 8;
    a ^= (a & 0xffff0000u) >> 16;
    return a;
}
[[gnu::always_inline]] inline uint32_t sobolSecondDimension(uint64_t a) {
    return reverseBits32(static_cast<uint32_t>(sobolSupersetTransform(a)));
}

inline uint32_t sobolBits(const uint32_t* matrices, uint64_t a, int dimension) {
    // Dimension 0 is the van der Corput sequence: C_0 is the bit reversal
    // (its columns past 32 are zero).
    if (dimension == 0) return reverseBits32(static_cast<uint32_t>(a));
    if (dimension == 1) return sobolSecondDimension(a);
    const uint32_t* column = matrices + dimension * kSobolMatrixColumns;
    uint32_t v = 0;
    // One XOR per set bit of a, without data-dependent branches per bit.
    for (; a != 0; a &= a - 1) v ^= column[__builtin_ctzll(a)];
    return v;
}

// The same products for the first kSobolNibbleDimensions dimensions by table:
// C_d · a is linear over GF(2), so it is the XOR over a's eight 4-bit groups g
// of C_d · (g's bits in place) — eight precomputed entries of 16 instead of one
// column per set bit (about eleven for the indices of a 256×256 image at 64
// spp), with no loop to mispredict. 512 bytes per dimension; the 64 dimensions
// a path of depth 8 uses fit in L1. Bits of a from 32 on go column by column.
inline constexpr int kSobolNibbleDimensions = 64;
struct SobolNibbleTable {
    uint32_t entries[8][16];  // [group][value]
};
const SobolNibbleTable* sobolNibbleTables();  // kSobolNibbleDimensions of them

inline uint32_t sobolBitsByNibbles(const SobolNibbleTable& t, const uint32_t* column, uint64_t a) {
    const auto low = static_cast<uint32_t>(a);
    uint32_t v = t.entries[0][low & 15] ^ t.entries[1][(low >> 4) & 15] ^
                 t.entries[2][(low >> 8) & 15] ^ t.entries[3][(low >> 12) & 15] ^
                 t.entries[4][(low >> 16) & 15] ^ t.entries[5][(low >> 20) & 15] ^
                 t.entries[6][(low >> 24) & 15] ^ t.entries[7][low >> 28];
    for (uint64_t high = a >> 32; high != 0; high &= high - 1)
        v ^= column[32 + __builtin_ctzll(high)];
    return v;
}

// ---------------------------------------------------------------------------
// Binary scramblers applied to a 32-bit fraction.

// Random digital shift (XOR scrambling): flips the same bits of every point.
// Preserves every elementary-interval stratification of a (t,m,s)-net.
constexpr uint32_t xorScramble(uint32_t v, uint32_t seed) {
    return v ^ seed;
}

// Hash-based Owen scrambling (Laine & Karras 2011, "Stratified sampling for
// stochastic transparency"; Burley 2020, "Practical Hash-based Owen
// Scrambling", JCGT 9(4)). A permutation of the bits of the *reversed* value in
// which every bit is changed only by bits below it — i.e., in the unreversed
// value, a bit's flip depends only on the more significant bits: exactly
// Owen's nested scrambling, with a hash in place of a tree of random flips.
// The multiply constants are Vegdahl's improved set ("Building a Better LK
// Hash", 2021), whose avalanche from low to high bits is much closer to ideal
// than the original Laine–Karras constants.
[[gnu::always_inline]] constexpr uint32_t laineKarrasPermutation(uint32_t x, uint32_t seed) {
    x ^= x * 0x3d20adeau;
    x += seed;
    x *= (seed >> 16) | 1u;
    x ^= x * 0x05526c56u;
    x ^= x * 0x53a22864u;
    return x;
}
[[gnu::always_inline]] constexpr uint32_t owenScramble(uint32_t v, uint32_t seed) {
    return reverseBits32(laineKarrasPermutation(reverseBits32(v), seed));
}

// ---------------------------------------------------------------------------
// permutationElement(i, n, seed): the image of i under a pseudo-random
// permutation of [0, n) chosen by seed, without storing it. A seeded bijection
// on the smallest power-of-two range covering n (odd multiplies and xorshifts
// are invertible modulo 2^w) is iterated until it lands inside [0, n) — "cycle
// walking", as in Kensler 2013, "Correlated Multi-Jittered Sampling".
//
// The range's mask and shifts depend on n only: a caller drawing many elements
// of permutations of one n keeps them in a PermutationDomain.
struct PermutationDomain {
    explicit PermutationDomain(uint32_t size) : n(size) {
        if (n <= 1) return;
        mask = n - 1;
        mask |= mask >> 1, mask |= mask >> 2, mask |= mask >> 4, mask |= mask >> 8;
        mask |= mask >> 16;
        const int bits = 32 - __builtin_clz(mask);
        shift = bits / 2 + 1;
        innerShift = shift > 1 ? shift - 1 : 1;
    }
    uint32_t n;
    uint32_t mask = 0;  // 2^w − 1 for the smallest 2^w ≥ n
    int shift = 1, innerShift = 1;
};

// One round of the bijection on [0, 2^w).
inline uint32_t permuteInRange(uint32_t i, const PermutationDomain& d, uint32_t s0, uint32_t s1) {
    const uint32_t mask = d.mask;
    i ^= s0;
    i = (i * 0xe170893du) & mask;
    i ^= i >> d.shift;
    i = (i + s1) & mask;
    i = (i * (0x0929eb3fu | 1u)) & mask;
    i ^= (i & mask) >> d.innerShift;
    i = (i * (s1 | 1u)) & mask;
    i ^= i >> d.shift;
    i = (i * 0x6935fa69u) & mask;
    return i ^ (s0 & mask);
}

inline uint32_t permutationElement(uint32_t i, const PermutationDomain& d, uint64_t seed) {
    if (d.n <= 1) return 0;
    const auto s0 = static_cast<uint32_t>(seed), s1 = static_cast<uint32_t>(seed >> 32);
    do {
        i = permuteInRange(i, d, s0, s1);
    } while (i >= d.n);
    return i;
}

inline uint32_t permutationElement(uint32_t i, uint32_t n, uint64_t seed) {
    return permutationElement(i, PermutationDomain(n), seed);
}

// 32-bit seed from a 64-bit hash (the two halves folded).
constexpr uint32_t foldSeed(uint64_t h) {
    return static_cast<uint32_t>(h ^ (h >> 32));
}

}  // namespace pathlab
