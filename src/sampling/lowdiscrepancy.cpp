#include "sampling/lowdiscrepancy.h"

#include <array>
#include <boost/random/detail/sobol_table.hpp>
#include <vector>

namespace pathlab {

const int* primeTable() {
    static const std::array<int, kPrimeTableSize> primes = [] {
        std::array<int, kPrimeTableSize> p{};
        int count = 0;
        for (int candidate = 2; count < kPrimeTableSize; ++candidate) {
            bool prime = true;
            for (int i = 0; i < count && p[i] * p[i] <= candidate; ++i)
                if (candidate % p[i] == 0) {
                    prime = false;
                    break;
                }
            if (prime) p[count++] = candidate;
        }
        return p;
    }();
    return primes.data();
}

const PrimeBase* primeBases() {
    // An index below 2^32 has at most 32 digits (base 2).
    constexpr int kPowers = 33;
    static const std::vector<double> powers = [] {
        std::vector<double> p(size_t(kPrimeTableSize) * kPowers);
        for (int d = 0; d < kPrimeTableSize; ++d) {
            const double inverse = 1.0 / primeTable()[d];
            double power = 1.0;
            for (int k = 0; k < kPowers; ++k, power *= inverse) p[size_t(d) * kPowers + k] = power;
        }
        return p;
    }();
    static const std::vector<PrimeBase> bases = [] {
        std::vector<PrimeBase> b;
        b.reserve(kPrimeTableSize);
        for (int d = 0; d < kPrimeTableSize; ++d) {
            const auto base = uint32_t(primeTable()[d]);
            b.push_back(
                {BaseDivider(base), BaseDivider(base * base), powers.data() + size_t(d) * kPowers});
        }
        return b;
    }();
    return bases.data();
}

float radicalInverse(int base, uint64_t a) {
    // Accumulate the mirrored digits as an integer and scale once at the end,
    // stopping before the integer could overflow (digits past that point are
    // far below float precision).
    const BaseDivider divider{uint32_t(base)};
    const uint64_t limit = ~uint64_t(0) / base - base;
    const double invBase = 1.0 / base;
    double invBaseM = 1.0;
    uint64_t reversed = 0;
    while (a != 0 && reversed < limit) {
        const uint64_t next = divider.quotient(a);
        reversed = reversed * base + (a - next * base);
        invBaseM *= invBase;
        a = next;
    }
    return std::min(static_cast<float>(static_cast<double>(reversed) * invBaseM), kOneMinusEpsilon);
}

int floatDigitCount(int base) {
    // Digits k whose largest contribution (b − 1)·b^-(k+1) still reaches
    // 2^-25, half the spacing of the floats just below 1 — the count of
    // pbrt-v4's scrambled radical inverses (`while (1 - invBaseM < 1)`), for
    // every prime base. (The count was one more before, from a weight that
    // started at b^0 instead of b^-1: a digit worth at most 2^-25/b·(b−1)
    // and a sixth to a third of the scrambling loops' work.) Tabulated for the
    // prime bases' range.
    auto count = [](int b) {
        int digits = 0;
        for (double weight = 1.0 / b; weight * (b - 1) >= 0x1p-25; weight /= b) ++digits;
        return digits;
    };
    static const std::vector<uint8_t> table = [&] {
        const size_t largestPrime = size_t(primeTable()[kPrimeTableSize - 1]);
        std::vector<uint8_t> t(largestPrime + 1);
        for (size_t b = 2; b < t.size(); ++b) t[b] = uint8_t(count(int(b)));
        return t;
    }();
    return size_t(base) < table.size() ? table[size_t(base)] : count(base);
}

const uint32_t* sobolMatrices() {
    static const std::vector<uint32_t> matrices = [] {
        using Table = boost::random::detail::qrng_tables::sobol;
        static_assert(Table::max_dimension == kSobolDimensions);
        std::vector<uint32_t> c(size_t(kSobolDimensions) * kSobolMatrixColumns);
        // m_j: the odd integers < 2^{j+1} whose binary expansion m_j / 2^{j+1}
        // is direction number v_j (Bratley & Fox 1988, §2).
        std::array<uint64_t, kSobolMatrixColumns> m{};
        for (int d = 0; d < kSobolDimensions; ++d) {
            if (d == 0) {
                m.fill(1);  // the van der Corput sequence: C_0 = bit reversal
            } else {
                // Primitive polynomial x^s + a_1 x^{s-1} + … + a_{s-1} x + 1, stored
                // with the coefficient of x^k in bit k.
                const unsigned poly = Table::polynomial(d - 1);
                int s = 0;
                while ((poly >> (s + 1)) != 0) ++s;
                for (int j = 0; j < s; ++j) m[j] = Table::minit(d - 1, j);
                // m_j = 2 a_1 m_{j-1} ⊕ 4 a_2 m_{j-2} ⊕ … ⊕ 2^s m_{j-s} ⊕ m_{j-s}.
                for (int j = s; j < kSobolMatrixColumns; ++j) {
                    uint64_t v = m[j - s];
                    for (int k = 0; k < s; ++k)
                        if ((poly >> k) & 1) v ^= m[j - s + k] << (s - k);
                    m[j] = v;
                }
            }
            // Column j as a 32-bit fraction: m_j · 2^{-(j+1)} truncated to 32 bits.
            for (int j = 0; j < kSobolMatrixColumns; ++j)
                c[size_t(d) * kSobolMatrixColumns + j] =
                    j < 32 ? static_cast<uint32_t>(m[j] << (31 - j))
                           : static_cast<uint32_t>(m[j] >> (j - 31));
        }
        return c;
    }();
    return matrices.data();
}

const SobolNibbleTable* sobolNibbleTables() {
    static const std::vector<SobolNibbleTable> tables = [] {
        std::vector<SobolNibbleTable> t(kSobolNibbleDimensions);
        const uint32_t* matrices = sobolMatrices();
        for (int d = 0; d < kSobolNibbleDimensions; ++d)
            for (int g = 0; g < 8; ++g)
                for (uint32_t value = 0; value < 16; ++value)
                    t[size_t(d)].entries[g][value] =
                        sobolBits(matrices, uint64_t(value) << (4 * g), d);
        return t;
    }();
    return tables.data();
}

}  // namespace pathlab
