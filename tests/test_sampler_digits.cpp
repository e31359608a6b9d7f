// The digit-level fast paths of the Halton and Sobol' samplers against the
// digit-by-digit definitions they must reproduce.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <iostream>
#include <random>
#include <set>
#include <vector>

#include "core/rng.h"
#include "sampling/halton.h"
#include "sampling/scramble_lanes.h"
#include "sampling/sobol.h"

namespace pathlab {
namespace {

uint32_t bits(float f) {
    return std::bit_cast<uint32_t>(f);
}

// Indices a Halton sampler meets, and harder ones: small, around 2^32 (where
// BaseDivider switches to a true division) and with more digits than a float keeps.
std::vector<uint64_t> haltonIndices() {
    std::vector<uint64_t> v;
    for (uint64_t a = 0; a < 2000; ++a) v.push_back(a);
    Pcg32 rng(17, 3);
    for (int i = 0; i < 3000; ++i) {
        const uint64_t hi = rng.nextUInt(), lo = rng.nextUInt();
        v.push_back(lo >> rng.nextUInt(32));
        v.push_back(((hi << 32) | lo) >> (24 + rng.nextUInt(24)));
    }
    for (uint64_t a : {0xffffffffULL, 0x100000000ULL, 0x100000001ULL, 0xffffffffffffULL})
        v.push_back(a);
    return v;
}

TEST(SobolDigits, SecondDimensionIsThePascalMatrixFromBoostsDirectionNumbers) {
    // The closed form of Sobol' dimension 1 against the generator matrix built
    // from the Joe-Kuo direction numbers, column by column.
    const uint32_t* column = sobolMatrices() + kSobolMatrixColumns;
    auto matrixProduct = [&](uint64_t a) {
        uint32_t v = 0;
        for (int k = 0; k < kSobolMatrixColumns; ++k)
            if (a >> k & 1) v ^= column[k];
        return v;
    };
    for (int k = 0; k < kSobolMatrixColumns; ++k)
        ASSERT_EQ(sobolSecondDimension(uint64_t(1) << k), column[k]) << "column " << k;
    Pcg32 rng(23, 1);
    for (uint64_t a = 0; a < 70000; ++a) ASSERT_EQ(sobolSecondDimension(a), matrixProduct(a)) << a;
    for (int i = 0; i < 100000; ++i) {
        const uint64_t a = uint64_t(rng.nextUInt()) << 32 | rng.nextUInt();
        ASSERT_EQ(sobolSecondDimension(a), matrixProduct(a)) << a;
    }
}

TEST(SobolDigits, NibbleTablesEqualTheColumnLoop) {
    // Every tabulated dimension, on small indices (every 4-bit group value),
    // random 32-bit ones and ones past 2^32 (whose high bits take the loop).
    const uint32_t* matrices = sobolMatrices();
    const SobolNibbleTable* tables = sobolNibbleTables();
    Pcg32 rng(29, 5);
    for (int d = 0; d < kSobolNibbleDimensions; ++d) {
        const uint32_t* column = matrices + d * kSobolMatrixColumns;
        for (uint64_t a = 0; a < 4096; ++a)
            ASSERT_EQ(sobolBitsByNibbles(tables[d], column, a), sobolBits(matrices, a, d)) << d;
        for (int i = 0; i < 4000; ++i) {
            const uint64_t wide = uint64_t(rng.nextUInt()) << 32 | rng.nextUInt();
            const uint64_t a = i % 2 ? wide : wide >> 32;
            ASSERT_EQ(sobolBitsByNibbles(tables[d], column, a), sobolBits(matrices, a, d))
                << d << " " << a;
        }
    }
}

template <typename S>
void expectGlobalSobolDrawsMatchDefinition(uint64_t seed) {
    // A 4096² image maps pixel samples to indices beyond 2^32 for large sample
    // numbers; dimensions cross the end of the tables (64).
    S sampler(SamplerConfig{1 << 20, seed, {4096, 4096}});
    Pcg32 rng(43, seed);
    for (int call = 0; call < 20000; ++call) {
        const Vec2i p{int(rng.nextUInt(4096)), int(rng.nextUInt(4096))};
        const int index = int(call % 2 ? rng.nextUInt(1 << 20) : rng.nextUInt(64));
        const int dim = 2 + int(rng.nextUInt(90));
        sampler.startPixelSample(p, index, dim);
        const float fast = sampler.get1D();
        sampler.startPixelSample(p, index, dim);
        ASSERT_EQ(bits(fast), bits(sampler.sampleDimensionByDefinition(dim)))
            << p.x << "," << p.y << " #" << index << " dim " << dim;
    }
}

TEST(SobolDigits, GlobalSobolDrawsEqualTheirDefinition) {
    for (uint64_t seed : {0, 12}) {
        expectGlobalSobolDrawsMatchDefinition<SobolSampler>(seed);
        expectGlobalSobolDrawsMatchDefinition<XorSobolSampler>(seed);
        expectGlobalSobolDrawsMatchDefinition<GlobalOwenSobolSampler>(seed);
    }
}

TEST(SobolDigits, OwenSobolDrawsEqualBurleysDefinition) {
    // sobol-owen's draws skip the bit reversals that cancel; every value must
    // be the composition of scrambles it is defined as.
    for (uint64_t seed : {0, 9}) {
        OwenSobolSampler sampler(SamplerConfig{64, seed, {16, 16}});
        Pcg32 rng(41, seed);
        for (int call = 0; call < 20000; ++call) {
            const Vec2i p{int(rng.nextUInt(16)), int(rng.nextUInt(16))};
            const uint32_t index = call % 3 == 0 ? rng.nextUInt() : rng.nextUInt(4096);
            const int dim = int(rng.nextUInt(80));
            const uint64_t pixelHash = OwenSobolSampler::pixelHash(p, seed);
            sampler.startPixelSample(p, int(index & 0x7fffffff), dim);
            const uint32_t i = index & 0x7fffffff;
            if (call % 2) {
                ASSERT_EQ(bits(sampler.get1D()),
                          bits(OwenSobolSampler::definition1D(pixelHash, i, dim)));
            } else {
                const Vec2f a = sampler.get2D(),
                            b = OwenSobolSampler::definition2D(pixelHash, i, dim);
                ASSERT_EQ(bits(a.x), bits(b.x));
                ASSERT_EQ(bits(a.y), bits(b.y));
            }
        }
    }
}

TEST(HaltonDigits, TabulatedRadicalInverseMatchesTheDigitLoop) {
    // The unscrambled sampler's table-driven radical inverse against the
    // general one (which divides), bit for bit, in every prime base.
    const int* primes = primeTable();
    const PrimeBase* bases = primeBases();
    const auto indices = haltonIndices();
    for (int d = 0; d < kPrimeTableSize; d += (d < 64 ? 1 : 37)) {
        ASSERT_EQ(bases[d].divider.base, uint64_t(primes[d]));
        for (uint64_t a : indices)
            ASSERT_EQ(bits(radicalInverse(bases[d], a)), bits(radicalInverse(primes[d], a)))
                << "base " << primes[d] << " index " << a;
    }
}

TEST(HaltonDigits, DigitCountIsPbrtV4s) {
    // The scrambled radical inverses stop after the digit whose largest
    // contribution reaches 2^-25: pbrt-v4's loop condition, in float, for
    // every prime base.
    auto pbrtDigitCount = [](int base) {
        const float invBase = 1.0f / float(base);
        float invBaseM = 1.0f;
        int digits = 0;
        for (; 1.0f - invBaseM < 1.0f; ++digits) invBaseM *= invBase;
        return digits;
    };
    for (int d = 0; d < kPrimeTableSize; ++d)
        ASSERT_EQ(floatDigitCount(primeTable()[d]), pbrtDigitCount(primeTable()[d]))
            << "base " << primeTable()[d];
    EXPECT_EQ(floatDigitCount(2), 25);
    EXPECT_EQ(floatDigitCount(3), 16);
}

TEST(HaltonDigits, BaseTwoBitReversalMatchesTheDigitLoop) {
    // The pixel lanes' base-2 radical inverse (a bit reversal) against the
    // general digit loop: every index below 2^20, then a spread up to 2^32 − 1.
    for (uint32_t a = 0; a < (1u << 20); ++a)
        ASSERT_EQ(bits(radicalInverseBase2(a)), bits(radicalInverse(2, a))) << "index " << a;
    std::mt19937 rng(3);
    for (int i = 0; i < 200000; ++i) {
        const uint32_t a = rng() | (i & 1 ? 0x80000000u : 0u);
        ASSERT_EQ(bits(radicalInverseBase2(a)), bits(radicalInverse(2, a))) << "index " << a;
    }
    ASSERT_EQ(bits(radicalInverseBase2(~0u)), bits(radicalInverse(2, ~0u)));
}

TEST(HaltonDigits, TabulatedDimensionsMatchTheDigitLoops) {
    const int* primes = primeTable();
    const auto indices = haltonIndices();
    for (uint64_t seed : {0, 5}) {
        const auto perms = haltonDigitPermutations(seed);
        ASSERT_EQ(perms->dimensions.size(), size_t(HaltonDigitPermutations::kTabulatedBases));
        for (int d = 0; d < HaltonDigitPermutations::kTabulatedBases; ++d) {
            const int base = primes[d];
            const DigitPermutation perm = perms->forDimension(d, base);
            const uint64_t owenHash = hashValues(seed, d, 0x4f57454eu);
            // Bases up to kMaxPairBase take the two-digit path, the others one digit at a time.
            ASSERT_EQ(perms->dimensions[size_t(d)].pairs != nullptr,
                      base <= HaltonDigitPermutations::kMaxPairBase);
            for (uint64_t a : indices) {
                ASSERT_EQ(bits(randomDigitScrambled(perms->dimensions[size_t(d)], a)),
                          bits(randomDigitScrambledRadicalInverse(base, a, perm,
                                                                  perms->shiftsForDimension(d))))
                    << "base " << base << " index " << a;
                ASSERT_EQ(bits(owenScrambled(perms->dimensions[size_t(d)], a)),
                          bits(owenScrambledRadicalInverse(base, a, perm, owenHash)))
                    << "base " << base << " index " << a;
            }
        }
    }
}

// haltonIndices below 2^32 (the lane kernels' range), padded to whole packets.
std::vector<uint64_t> haltonLaneIndices() {
    std::vector<uint64_t> indices;
    for (uint64_t a : haltonIndices())
        if (a >> 32 == 0) indices.push_back(a);
    while (indices.size() % kCameraPacketSamples != 0) indices.push_back(0xffffffffULL);
    return indices;
}

// Every instruction set this processor has for the Halton lane kernels (the
// baseline always).
std::vector<SimdLevel> haltonLaneLevels() {
    std::vector<SimdLevel> levels = {SimdLevel::Baseline};
    for (SimdLevel level : {SimdLevel::Avx2, SimdLevel::Avx512, SimdLevel::Avx512Vbmi})
        if (level <= bestSimdLevel()) levels.push_back(level);
    return levels;
}

TEST(HaltonDigits, LaneKernelsMatchTheScalarScramblers) {
    // The lane draws' kernels (AVX2 on processors that have it) on every
    // tabulated dimension, eight indices below 2^32 per call — among them
    // 0, 2^32 − 1 and indices with more digits than a float keeps — against
    // the scalar scramblers lane by lane.
    const std::vector<uint64_t> indices = haltonLaneIndices();
    const std::vector<SimdLevel> levels = haltonLaneLevels();
    if (levels.size() < 4)
        std::cout << "(this processor runs " << levels.size() - 1 << " of the 3 SIMD kernels)\n";
    for (uint64_t seed : {0, 5}) {
        const auto perms = haltonDigitPermutations(seed);
        for (const HaltonDimension& t : perms->dimensions) {
            for (size_t i = 0; i < indices.size(); i += kCameraPacketSamples) {
                const uint64_t* a = indices.data() + i;
                // Every count: four lanes to a register, the last one partly live.
                const int count = 1 + int(i / kCameraPacketSamples) % kCameraPacketSamples;
                for (SimdLevel level : levels) {
                    float randomDigit[kCameraPacketSamples], owen[kCameraPacketSamples];
                    randomDigitScrambledLanes(t, a, count, randomDigit, level);
                    owenScrambledLanes(t, a, count, owen, level);
                    // The 2D calls, with this dimension second and the first
                    // dimension first.
                    const HaltonDimension& first = perms->dimensions[0];
                    float rdFirst[kCameraPacketSamples], rdSecond[kCameraPacketSamples];
                    float owenFirst[kCameraPacketSamples], owenSecond[kCameraPacketSamples];
                    randomDigitScrambledLanes2D(first, t, a, count, rdFirst, rdSecond, level);
                    owenScrambledLanes2D(first, t, a, count, owenFirst, owenSecond, level);
                    for (int j = 0; j < count; ++j) {
                        ASSERT_EQ(bits(randomDigit[j]), bits(randomDigitScrambled(t, a[j])))
                            << "base " << t.base << " index " << a[j] << " level " << int(level);
                        ASSERT_EQ(bits(owen[j]), bits(owenScrambled(t, a[j])))
                            << "base " << t.base << " index " << a[j] << " level " << int(level);
                        ASSERT_EQ(bits(rdSecond[j]), bits(randomDigit[j])) << "2D, base " << t.base;
                        ASSERT_EQ(bits(owenSecond[j]), bits(owen[j])) << "2D, base " << t.base;
                        ASSERT_EQ(bits(rdFirst[j]), bits(randomDigitScrambled(first, a[j])));
                        ASSERT_EQ(bits(owenFirst[j]), bits(owenScrambled(first, a[j])));
                    }
                }
            }
        }
    }
}

TEST(HaltonDigits, OwenTwoDimensionDrawsMatchTheScalarScrambler) {
    // The 2D lane draw on every pair of adjacent dimensions (as the samplers
    // draw them), in both orders — either may have more digits, and some
    // pairs straddle a change of table kind (bases 31/37, 61/67, 127/131,
    // 251/257) — on every instruction set and lane count.
    const std::vector<uint64_t> indices = haltonLaneIndices();
    const std::vector<SimdLevel> levels = haltonLaneLevels();
    const auto perms = haltonDigitPermutations(3);
    const auto& dims = perms->dimensions;
    for (size_t d = 0; d + 1 < dims.size(); ++d) {
        for (size_t i = 0; i < indices.size(); i += kCameraPacketSamples) {
            const uint64_t* a = indices.data() + i;
            const int count = 1 + int(i / kCameraPacketSamples) % kCameraPacketSamples;
            for (SimdLevel level : levels) {
                for (const auto& [tx, ty] :
                     {std::pair{&dims[d], &dims[d + 1]}, std::pair{&dims[d + 1], &dims[d]}}) {
                    float x[kCameraPacketSamples], y[kCameraPacketSamples];
                    owenScrambledLanes2D(*tx, *ty, a, count, x, y, level);
                    for (int j = 0; j < count; ++j) {
                        ASSERT_EQ(bits(x[j]), bits(owenScrambled(*tx, a[j])))
                            << "bases " << tx->base << ", " << ty->base << " level " << int(level);
                        ASSERT_EQ(bits(y[j]), bits(owenScrambled(*ty, a[j])))
                            << "bases " << tx->base << ", " << ty->base << " level " << int(level);
                    }
                }
            }
        }
    }
}

TEST(HaltonDigits, PlainLaneKernelMatchesTheScalarRadicalInverse) {
    // `halton`'s lane kernel on every tabulated dimension's base, every
    // instruction set and every live-lane count: lanes of one call have
    // different digit counts (0 has none), so each lane stops on its own.
    const std::vector<uint64_t> indices = haltonLaneIndices();
    const std::vector<SimdLevel> levels = haltonLaneLevels();
    for (int d = 0; d < HaltonDigitPermutations::kTabulatedBases; ++d) {
        const PrimeBase& b = primeBases()[d];
        for (size_t i = 0; i < indices.size(); i += kCameraPacketSamples) {
            const uint64_t* a = indices.data() + i;
            const int count = 1 + int(i / kCameraPacketSamples) % kCameraPacketSamples;
            for (SimdLevel level : levels) {
                float x[kCameraPacketSamples], first[kCameraPacketSamples],
                    second[kCameraPacketSamples];
                radicalInverseLanes(b, a, count, x, level);
                radicalInverseLanes2D(primeBases()[1], b, a, count, first, second, level);
                for (int j = 0; j < count; ++j) {
                    ASSERT_EQ(bits(x[j]), bits(radicalInverse(primeTable()[d], a[j])))
                        << "base " << primeTable()[d] << " index " << a[j] << " level "
                        << int(level);
                    ASSERT_EQ(bits(second[j]), bits(x[j])) << "2D, base " << primeTable()[d];
                    ASSERT_EQ(bits(first[j]), bits(radicalInverse(3, a[j])));
                }
            }
        }
    }
}

TEST(HaltonDigits, SamplersDrawTheDigitLoopsValues) {
    // Across the end of the tables (128 dimensions) and for pixels of a real image.
    const int* primes = primeTable();
    const SamplerConfig config{16, 9, {40, 30}};
    RandomDigitHaltonSampler rd(config);
    OwenHaltonSampler owen(config);
    const HaltonImageMapping mapping(config.resolution);
    const auto perms = haltonDigitPermutations(config.seed);
    for (Vec2i p : {Vec2i{0, 0}, Vec2i{39, 29}, Vec2i{17, 4}})
        for (int i = 0; i < 16; i += 5)
            for (int d = 2; d < 140; ++d) {
                const uint64_t a = mapping.index(p, i);
                const DigitPermutation perm = perms->forDimension(d, primes[d]);
                rd.startPixelSample(p, i, d);
                owen.startPixelSample(p, i, d);
                ASSERT_EQ(bits(rd.get1D()), bits(randomDigitScrambledRadicalInverse(
                                                primes[d], a, perm, perms->shiftsForDimension(d))))
                    << "dim " << d;
                ASSERT_EQ(bits(owen.get1D()),
                          bits(owenScrambledRadicalInverse(
                              primes[d], a, perm, hashValues(config.seed, d, 0x4f57454eu))))
                    << "dim " << d;
            }
}

// Digit k (0 = most significant) of x in base b.
int digitOf(float x, int b, int k) {
    double v = x;
    for (int i = 0; i < k; ++i) v = v * b - std::floor(v * b);
    return int(std::floor(v * b));
}

TEST(HaltonDigits, NodeHashIsTheTopHalfOfMixBits) {
    // Owen's node rotations hash with mixBitsHigh32, which leaves out
    // mixBits's last step; the top halves must agree for every input — checked
    // on the node names the rotations hash (small prefixes, digit positions in
    // the top byte) and on random 64-bit values.
    std::mt19937_64 random(11);
    for (int i = 0; i < 200000; ++i) {
        const uint64_t v = i < 100000 ? (uint64_t(i % 40) << 56) ^ uint64_t(i) : random();
        ASSERT_EQ(mixBitsHigh32(v), uint32_t(mixBits(v) >> 32)) << v;
    }
}

TEST(HaltonDigits, OwenPermutesEachDigitByItsOwnNode) {
    // Owen's nested scrambling: the second digit's permutation depends on the
    // first digit (the node), so the b nodes below the root do not all use
    // the same permutation — which is what tells it from a per-position
    // (random-digit) scramble, where they all do.
    const int* primes = primeTable();
    const auto perms = haltonDigitPermutations(3);
    for (int d = 2; d < 8; ++d) {
        const int b = primes[d];
        const DigitPermutation perm = perms->forDimension(d, b);
        std::set<std::vector<int>> owenMaps, rdMaps;
        for (int first = 0; first < b; ++first) {
            std::vector<int> owenMap, rdMap;
            std::set<int> owenFirst;
            for (int second = 0; second < b; ++second) {
                const uint64_t a = uint64_t(first) + uint64_t(b) * second;
                const float x = owenScrambledRadicalInverse(
                    b, a, perm, hashValues(uint64_t(3), d, 0x4f57454eu));
                owenFirst.insert(digitOf(x, b, 0));
                owenMap.push_back(digitOf(x, b, 1));
                rdMap.push_back(digitOf(
                    randomDigitScrambledRadicalInverse(b, a, perm, perms->shiftsForDimension(d)), b,
                    1));
            }
            // Within the node: the first digit is shared, the second a bijection.
            EXPECT_EQ(owenFirst.size(), 1u);
            EXPECT_EQ(std::set<int>(owenMap.begin(), owenMap.end()).size(), size_t(b));
            owenMaps.insert(owenMap);
            rdMaps.insert(rdMap);
        }
        EXPECT_EQ(rdMaps.size(), 1u) << "base " << b;
        EXPECT_GT(owenMaps.size(), 1u) << "base " << b;
    }
}

// One draw of dimension d at the sampler's current pixel sample, checked
// against the digit-by-digit reference index.
void expectZSobolDrawMatchesReference(ZSobolSampler& s, int d, uint64_t seed, bool twoD) {
    const uint32_t* matrices = sobolMatrices();
    const uint64_t reference = s.referenceSampleIndex(d);
    if (!twoD) {
        const uint32_t seed1 = foldSeed(hashValues(d, seed, 0x5a31u));
        ASSERT_EQ(bits(s.get1D()),
                  bits(fixedPointToFloat(owenScramble(sobolBits(matrices, reference, 0), seed1))));
        return;
    }
    const uint64_t seeds = hashValues(d, seed, 0x5a32u);
    const Vec2f u = s.get2D();
    ASSERT_EQ(
        bits(u.x),
        bits(fixedPointToFloat(owenScramble(sobolBits(matrices, reference, 0), uint32_t(seeds)))));
    ASSERT_EQ(bits(u.y), bits(fixedPointToFloat(owenScramble(sobolBits(matrices, reference, 1),
                                                             uint32_t(seeds >> 32)))));
}

// permutationElement's values as the implementation before PermutationDomain gave them.
constexpr uint32_t kPinnedElements[5] = {58, 7, 4, 71, 5};

// The instruction sets the scramble_lanes kernels can run here.
std::vector<SimdLevel> scrambleLaneLevels() {
    std::vector<SimdLevel> levels = {SimdLevel::Baseline};
    if (cpuHasAvx2()) levels.push_back(SimdLevel::Avx2);
    if (bestSimdLevel() >= SimdLevel::Avx512Vbmi) levels.push_back(SimdLevel::Avx512Vbmi);
    return levels;
}

TEST(PermutationDigits, TablesEqualTheElementByElementPermutation) {
    // permutationTable (stratified's strata), with every instruction set
    // available, against permutationElement: sizes that are powers of two
    // (one round) and that are not (cycle walking). Each is checked to be a
    // permutation of [0, n) on the way.
    for (SimdLevel level : scrambleLaneLevels()) {
        for (uint32_t n : {1u, 2u, 3u, 5u, 8u, 9u, 24u, 64u, 100u, 1024u}) {
            for (uint64_t seed : {uint64_t(0), uint64_t(0x9e3779b97f4a7c15), uint64_t(12345)}) {
                std::vector<uint32_t> table(n);
                permutationTable(PermutationDomain(n), seed, table.data(), level);
                std::vector<int> hits(n, 0);
                for (uint32_t i = 0; i < n; ++i) {
                    EXPECT_EQ(table[i], permutationElement(i, n, seed)) << "n " << n << " i " << i;
                    ++hits[permutationElement(i, n, seed)];
                }
                EXPECT_EQ(std::count(hits.begin(), hits.end(), 1), int(n)) << "n " << n;
            }
        }
    }
}

TEST(PermutationDigits, LanesEqualTheElementByElementPermutation) {
    // permutationLanes (stratified's lane draws), with every instruction set
    // available: eight indices at a time, spread over [0, n) in steps of 7,
    // against permutationElement.
    for (SimdLevel level : scrambleLaneLevels())
        for (uint32_t n : {1u, 3u, 8u, 24u, 64u, 100u, 1024u})
            for (uint64_t seed : {uint64_t(0), uint64_t(0x9e3779b97f4a7c15)})
                for (uint32_t first = 0; first < n; first += kCameraPacketSamples) {
                    uint32_t index[kCameraPacketSamples], out[kCameraPacketSamples];
                    for (int j = 0; j < kCameraPacketSamples; ++j)
                        index[j] = (first + uint32_t(j) * 7) % n;
                    permutationLanes(PermutationDomain(n), seed, index, out, level);
                    for (int j = 0; j < kCameraPacketSamples; ++j)
                        EXPECT_EQ(out[j], permutationElement(index[j], n, seed))
                            << "n " << n << " index " << index[j];
                }
}

TEST(PermutationDigits, PermutationElementKeepsItsValues) {
    // Values of permutationElement from before its range was kept in a
    // PermutationDomain (kPinnedElements): the stratified sampler's strata
    // must not change.
    EXPECT_EQ(permutationElement(0, 64, 0x9e3779b97f4a7c15), kPinnedElements[0]);
    EXPECT_EQ(permutationElement(17, 64, 0x9e3779b97f4a7c15), kPinnedElements[1]);
    EXPECT_EQ(permutationElement(5, 24, 12345), kPinnedElements[2]);
    EXPECT_EQ(permutationElement(99, 100, 0xdeadbeefcafef00d), kPinnedElements[3]);
    EXPECT_EQ(permutationElement(3, 7, 1), kPinnedElements[4]);
}

TEST(ZSobolDigits, LaneScramblesEqualTheScalarScramble) {
    // owenScrambleReversedLanes, with every instruction set available,
    // against R(L_seed(v)) lane by lane.
    std::mt19937 rng(5);
    for (SimdLevel level : scrambleLaneLevels()) {
        for (int round = 0; round < 200; ++round) {
            uint32_t v[kCameraPacketSamples];
            for (uint32_t& x : v) x = uint32_t(rng());
            const auto seed = uint32_t(rng());
            float x[kCameraPacketSamples];
            owenScrambleReversedLanes(v, seed, x, level);
            for (int j = 0; j < kCameraPacketSamples; ++j)
                EXPECT_EQ(
                    bits(x[j]),
                    bits(fixedPointToFloat(reverseBits32(laineKarrasPermutation(v[j], seed)))));
        }
    }
}

TEST(ZSobolDigits, LevelPermutationsEqualTheNodeByNodeHash) {
    // zsobol::digitPermutations, with every instruction set available, against
    // digitPermutation node by node: levels of 8, 16 and 64 nodes, Morton
    // prefixes up to 2^40 (the kernel's remainder goes through doubles), and
    // the permutation chosen must be one of the 24 (all 24 turn up).
    std::mt19937_64 rng(7);
    for (SimdLevel level : scrambleLaneLevels()) {
        std::set<uint8_t> seen;
        for (int round = 0; round < 300; ++round) {
            const uint32_t count = round % 3 == 0 ? 8 : round % 3 == 1 ? 16 : 64;
            const uint64_t first = (rng() >> 24) & ~uint64_t(count - 1);
            const uint64_t salt = rng();
            uint8_t out[64];
            zsobol::digitPermutations(first, salt, count, out, level);
            for (uint32_t n = 0; n < count; ++n) {
                ASSERT_EQ(out[n], zsobol::digitPermutation(first | n, salt))
                    << "first " << first << " n " << n;
                seen.insert(out[n]);
            }
        }
        EXPECT_EQ(seen.size(), 24u);
    }
}

TEST(ZSobolDigits, PairedLaneScramblesEqualTheScalarScramble) {
    // owenScrambleReversedLanes2D, with every instruction set available: each
    // pair is the two dimensions' scalar scrambles, each with its own seed.
    std::mt19937 rng(6);
    for (SimdLevel level : scrambleLaneLevels()) {
        for (int round = 0; round < 200; ++round) {
            uint32_t vx[kCameraPacketSamples], vy[kCameraPacketSamples];
            for (uint32_t& v : vx) v = uint32_t(rng());
            for (uint32_t& v : vy) v = uint32_t(rng());
            const auto xSeed = uint32_t(rng()), ySeed = uint32_t(rng());
            float xy[2 * kCameraPacketSamples];
            owenScrambleReversedLanes2D(vx, vy, xSeed, ySeed, xy, level);
            for (int j = 0; j < kCameraPacketSamples; ++j) {
                EXPECT_EQ(
                    bits(xy[2 * j]),
                    bits(fixedPointToFloat(reverseBits32(laineKarrasPermutation(vx[j], xSeed)))));
                EXPECT_EQ(
                    bits(xy[2 * j + 1]),
                    bits(fixedPointToFloat(reverseBits32(laineKarrasPermutation(vy[j], ySeed)))));
            }
        }
    }
}

// The renderer's order: a pixel's samples one after another, each drawing its
// dimensions in order, and some paths ending early — the draws that reuse the
// previous draw's node of the last tree level must give the reference values.
TEST(ZSobolDigits, DrawsInTheRenderersOrderMatchTheReference) {
    for (int spp : {1, 2, 3, 4, 6, 8, 32, 64, 128, 512})
        for (uint64_t seed : {0, 11}) {
            ZSobolSampler s(SamplerConfig{spp, seed, {64, 64}});
            Pcg32 rng(uint64_t(spp) * 7 + seed, 3);
            for (Vec2i pixel : {Vec2i{0, 0}, Vec2i{5, 9}, Vec2i{0, 0}, Vec2i{63, 63}})
                for (int index = 0; index < spp; ++index) {
                    // A path of up to 40 dimensions (from 0), ending early at
                    // random: past the tabulated dimensions of zsobol's low
                    // digits (the first three vertices') into its trees.
                    const int dims = 2 + int(rng.nextUInt(39));
                    for (int d = 0; d < dims;) {
                        const bool twoD = d + 1 < dims && rng.nextUInt(2);
                        s.startPixelSample(pixel, index, d);
                        SCOPED_TRACE(testing::Message()
                                     << "spp " << spp << " index " << index << " dim " << d);
                        expectZSobolDrawMatchesReference(s, d, seed, twoD);
                        d += twoD ? 2 : 1;
                    }
                }
        }
}

TEST(ZSobolDigits, CachedIndexAndDrawsMatchTheDigitByDigitReference) {
    const uint32_t* matrices = sobolMatrices();
    for (int spp : {1, 2, 3, 4, 8, 16, 32, 48, 64, 128, 256, 1024, 1 << 20, (1 << 25) + 3})
        for (Vec2i res : {Vec2i{1, 1}, Vec2i{5, 3}, Vec2i{64, 64}, Vec2i{512, 384}})
            for (uint64_t seed : {0, 11}) {
                ZSobolSampler s(SamplerConfig{spp, seed, res});
                Pcg32 rng(uint64_t(spp) * 1000 + uint64_t(res.x) + seed, 1);
                Vec2i pixel{0, 0};
                for (int step = 0; step < 1500; ++step) {
                    // Mostly stay in one pixel, as the renderer does; sometimes
                    // jump, sometimes to a pixel seen before.
                    const uint32_t r = rng.nextUInt(8);
                    if (r == 0)
                        pixel = {int(rng.nextUInt(uint32_t(res.x))),
                                 int(rng.nextUInt(uint32_t(res.y)))};
                    else if (r == 1)
                        pixel = {res.x - 1, res.y - 1};
                    else if (r == 2 && step % 5 == 0)  // outside the image (`points --pixel`)
                        pixel = {res.x + int(rng.nextUInt(40)), 3 * res.y + 1};
                    const int index = int(rng.nextUInt(uint32_t(spp)));
                    const int d = int(rng.nextUInt(72));  // past the 64 cached dimensions
                    s.startPixelSample(pixel, index, d);
                    const uint64_t reference = s.referenceSampleIndex(d);
                    ASSERT_EQ(s.sampleIndex(d), reference)
                        << "spp " << spp << " pixel " << pixel.x << "," << pixel.y << " index "
                        << index << " dim " << d;
                    if (rng.nextUInt(2)) {
                        const uint32_t seed1 = foldSeed(hashValues(d, seed, 0x5a31u));
                        ASSERT_EQ(bits(s.get1D()), bits(fixedPointToFloat(owenScramble(
                                                       sobolBits(matrices, reference, 0), seed1))));
                    } else {
                        const uint64_t seeds = hashValues(d, seed, 0x5a32u);
                        const Vec2f u = s.get2D();
                        ASSERT_EQ(bits(u.x),
                                  bits(fixedPointToFloat(owenScramble(
                                      sobolBits(matrices, reference, 0), uint32_t(seeds)))));
                        ASSERT_EQ(bits(u.y),
                                  bits(fixedPointToFloat(owenScramble(
                                      sobolBits(matrices, reference, 1), uint32_t(seeds >> 32)))));
                    }
                }
            }
}

}  // namespace
}  // namespace pathlab
