#include "sampling/halton.h"

#include <cmath>
#include <deque>
#include <mutex>

#include "core/rng.h"

namespace pathlab {
namespace {

// Extended Euclid: the inverse of a modulo n (a and n coprime).
uint64_t multiplicativeInverse(int64_t a, int64_t n) {
    int64_t r0 = n, r1 = a % n, t0 = 0, t1 = 1;
    while (r1 != 0) {
        const int64_t q = r0 / r1;
        const int64_t r2 = r0 - q * r1, t2 = t0 - q * t1;
        r0 = r1, r1 = r2, t0 = t1, t1 = t2;
    }
    return static_cast<uint64_t>(((t0 % n) + n) % n);
}

}  // namespace

HaltonDigitPermutations::HaltonDigitPermutations(uint64_t seed_) : seed(seed_) {
    const int* primes = primeTable();
    offset.resize(kTabulatedBases);
    size_t total = 0;
    for (int d = 0; d < kTabulatedBases; ++d) {
        offset[d] = static_cast<uint32_t>(total);
        total += primes[d];
    }
    table.resize(total + 1);  // + 1: the lane draws' 32-bit reads (HaltonDimension)
    shifts.resize(size_t(kPrimeTableSize) * kMaxDigits);
    for (int d = 0; d < kPrimeTableSize; ++d) {
        const int base = primes[d];
        Pcg32 rng(hashValues(seed, base, 0x5244u), 0);
        if (d >= kTabulatedBases) {
            for (int k = 0; k < kMaxDigits; ++k)
                shifts[size_t(d) * kMaxDigits + k] = static_cast<uint16_t>(rng.nextUInt(base));
            continue;
        }
        // Fisher–Yates with a PCG32 stream per base: the presentation's "array
        // the size of the base, each digit mapped to a randomly chosen digit".
        uint16_t* perm = table.data() + offset[d];
        for (int i = 0; i < base; ++i) perm[i] = static_cast<uint16_t>(i);
        for (int i = base - 1; i > 0; --i) std::swap(perm[i], perm[rng.nextUInt(i + 1)]);
        for (int k = 0; k < kMaxDigits; ++k)
            shifts[size_t(d) * kMaxDigits + k] = static_cast<uint16_t>(rng.nextUInt(base));
    }
    size_t pairTotal = 0;  // sized first: dimensions point into the vector
    for (int d = 0; d < kTabulatedBases && primes[d] <= kMaxPairBase; ++d)
        pairTotal += size_t(primes[d]) * size_t(primes[d]) * size_t(floatDigitCount(primes[d]) / 2);
    pairTables.resize(pairTotal + 1);
    uint16_t* nextPairs = pairTables.data();
    tails.resize(size_t(kTabulatedBases) * kMaxDigits);
    powers.resize(size_t(kTabulatedBases) * kMaxDigits);
    dimensions.reserve(kTabulatedBases);
    rotations.resize(total + kTabulatedBases + 1);
    size_t scrambledTotal = 0;
    for (int d = 0; d < kTabulatedBases; ++d)
        scrambledTotal += size_t(primes[d]) * size_t(floatDigitCount(primes[d]));
    scrambledDigits.resize(scrambledTotal + 1);
    uint16_t* nextScrambled = scrambledDigits.data();
    for (int d = 0; d < kTabulatedBases; ++d) {
        const int base = primes[d];
        const int digits = floatDigitCount(base);
        const uint16_t* perm = table.data() + offset[d];
        const uint16_t* shift = shifts.data() + size_t(d) * kMaxDigits;
        uint64_t* tail = tails.data() + size_t(d) * kMaxDigits;
        uint64_t* power = powers.data() + size_t(d) * kMaxDigits;
        tail[digits] = 0, power[digits] = 1;
        for (int k = digits - 1; k >= 0; --k) {
            power[k] = power[k + 1] * uint64_t(base);
            tail[k] = perm[shift[k]] * power[k + 1] + tail[k + 1];  // digit 0 ↦ π_b(s_k)
        }
        const double scale = inverseBasePower(base, digits);
        const uint64_t owenHash = hashValues(seed, d, 0x4f57454eu);
        uint16_t* rotation = rotations.data() + offset[d] + d;
        rotation[0] = uint16_t(owenRotation(owenHash, 0, 0, uint32_t(base)));
        for (int d0 = 0; d0 < base; ++d0)
            rotation[1 + d0] = uint16_t(owenRotation(owenHash, 1, uint64_t(d0), uint32_t(base)));
        uint16_t* pairs = base <= kMaxPairBase ? nextPairs : nullptr;
        if (pairs) {
            const uint32_t b = uint32_t(base);
            for (int k = 0; k + 1 < digits; k += 2)
                for (uint32_t q = 0; q < b * b; ++q)
                    *nextPairs++ = uint16_t(perm[rotateDigit(q % b, shift[k], b)] * b +
                                            perm[rotateDigit(q / b, shift[k + 1], b)]);
        }
        uint16_t* scrambled = nextScrambled;
        for (int k = 0; k < digits; ++k)
            for (int digit = 0; digit < base; ++digit)
                *nextScrambled++ = perm[rotateDigit(uint32_t(digit), shift[k], uint32_t(base))];
        dimensions.push_back(HaltonDimension{BaseDivider{uint32_t(base)}, uint32_t(base), digits,
                                             scale, perm, shift, tail, power, pairs,
                                             BaseDivider{uint32_t(base * base)}, owenHash, rotation,
                                             scrambled, 1.0 / base, 1.0 / (double(base) * base)});
    }
    addByteTables();
}

void HaltonDigitPermutations::addByteTables() {
    // The pair tables' digit positions: floor(digits / 2) tables of b² entries.
    auto pairEntries = [](const HaltonDimension& t) {
        return t.base <= uint32_t(kMaxBytePairBase) ? size_t(t.digits / 2) * t.base * t.base : 0;
    };
    size_t total = 0;  // sized first: dimensions point into the vector
    for (const HaltonDimension& t : dimensions)
        if (t.base <= uint32_t(kMaxByteTableBase))
            total += (t.base <= uint32_t(kMaxWrapFreeBase) ? 3 : 2) * size_t(t.base) +
                     size_t(t.digits) * t.base + pairEntries(t);
    // Padding past the last table: the lane kernels load a table's 64·k
    // bytes whatever its size (kRegisterTableBytes), reading on into the
    // next table or here, but look up only entries below its size.
    byteTables.resize(total + kRegisterTableBytes);
    uint8_t* next = byteTables.data();
    // from[i mod size] for i < count.
    auto copy = [&next](const uint16_t* from, size_t size, size_t count) {
        uint8_t* start = next;
        for (size_t i = 0; i < count; ++i) *next++ = uint8_t(from[i % size]);
        return start;
    };
    for (HaltonDimension& t : dimensions) {
        if (t.base > uint32_t(kMaxByteTableBase)) continue;
        const bool wrapFree = t.base <= uint32_t(kMaxWrapFreeBase);
        t.permutationBytes = copy(t.permutation, t.base, (wrapFree ? 2 : 1) * size_t(t.base));
        t.childRotationBytes = copy(t.rotations + 1, t.base, t.base);
        const size_t digitEntries = size_t(t.digits) * t.base;
        t.scrambledDigitBytes = copy(t.scrambledDigits, digitEntries, digitEntries);
        if (const size_t pairs = pairEntries(t)) t.pairBytes = copy(t.pairs, pairs, pairs);
    }
}

std::shared_ptr<const HaltonDigitPermutations> haltonDigitPermutations(uint64_t seed) {
    // The tables of the few most recently used seeds stay alive (a study
    // renders one seed after another; tests switch seeds often).
    static std::mutex mutex;
    static std::deque<std::pair<uint64_t, std::shared_ptr<const HaltonDigitPermutations>>> recent;
    const std::lock_guard<std::mutex> lock(mutex);
    for (const auto& [s, tables] : recent)
        if (s == seed) return tables;
    auto tables = std::make_shared<const HaltonDigitPermutations>(seed);
    recent.emplace_back(seed, tables);
    if (recent.size() > 4) recent.pop_front();
    return tables;
}

HaltonImageMapping::HaltonImageMapping(Vec2i resolution) {
    const int bases[2] = {2, 3};
    const int extent[2] = {std::max(1, resolution.x), std::max(1, resolution.y)};
    for (int i = 0; i < 2; ++i) {
        while (baseScales[i] < extent[i]) {
            baseScales[i] *= bases[i];
            ++baseExponents[i];
        }
    }
    // Pixel (x, y) needs an index h with h ≡ Φ_2^{-1}(x) (mod 2^j) and
    // h ≡ Φ_3^{-1}(y) (mod 3^k); by the Chinese remainder theorem
    // h = Σ_i r_i · (M / m_i) · ((M / m_i)^{-1} mod m_i) mod M.
    multInverse[0] = baseScales[0] > 1 ? multiplicativeInverse(baseScales[1], baseScales[0]) : 0;
    multInverse[1] = baseScales[1] > 1 ? multiplicativeInverse(baseScales[0], baseScales[1]) : 0;
}

uint64_t HaltonImageMapping::pixelOffset(Vec2i p) const {
    const uint64_t stride = this->stride();
    uint64_t h = 0;
    if (stride > 1) {
        const int pm[2] = {((p.x % baseScales[0]) + baseScales[0]) % baseScales[0],
                           ((p.y % baseScales[1]) + baseScales[1]) % baseScales[1]};
        for (int i = 0; i < 2; ++i) {
            if (baseScales[i] == 1) continue;
            const uint64_t residue = inverseRadicalInverse(pm[i], i == 0 ? 2 : 3, baseExponents[i]);
            h += residue * (stride / baseScales[i]) % stride * multInverse[i] % stride;
        }
        h %= stride;
    }
    return h;
}

float randomDigitScrambledRadicalInverse(int base, uint64_t a, DigitPermutation permutation,
                                         const uint16_t* shifts) {
    // All digits down to float precision are permuted — including the zero
    // digits past a's leading digit — so the map x → scrambled(x) is a
    // bijection of the b-adic intervals at every level (unlike stopping at the
    // last non-zero digit, which would leave point 0 and short indices fixed).
    const int digits = floatDigitCount(base);
    const BaseDivider divider{uint32_t(base)};
    uint64_t reversed = 0;
    for (int k = 0; k < digits; ++k) {
        const uint64_t next = divider.quotient(a);
        const auto digit = uint32_t(a - next * base);
        reversed = reversed * base + permutation(rotateDigit(digit, shifts[k], uint32_t(base)));
        a = next;
    }
    return floatBelow(static_cast<double>(reversed) * inverseBasePower(base, digits));
}

float owenScrambledRadicalInverse(int base, uint64_t a, DigitPermutation permutation,
                                  uint64_t dimensionHash) {
    const int digits = floatDigitCount(base);
    return owenScrambledDigits(a, BaseDivider{uint32_t(base)}, digits,
                               inverseBasePower(base, digits), permutation, dimensionHash);
}

}  // namespace pathlab
