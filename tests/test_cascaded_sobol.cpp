// `cascaded-sobol` (Paulin et al. 2021): the draws against the construction's
// definition, the nets the paper proves in every pair of consecutive
// dimensions, non-power-of-two counts, unbiasedness over seeds across the
// cascade, and what the cascade gains over padding.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "sampler_test_util.h"
#include "sampling/cascaded_sobol.h"

namespace pathlab {
namespace {

using testing::drawPoints;
using testing::l2StarDiscrepancy;

constexpr Vec2i kResolution{64, 64};

// True if every elementary interval [i/2^a, (i+1)/2^a) × [j/2^b, (j+1)/2^b)
// with a + b = m holds exactly one of the N = 2^m points.
::testing::AssertionResult isBase2Net(const std::vector<Vec2f>& pts) {
    const int n = int(pts.size());
    const int m = log2Ceil(uint64_t(n));
    for (int a = 0; a <= m; ++a) {
        std::vector<int> count(size_t(n), 0);
        for (const Vec2f& p : pts) {
            const int i = int(std::floor(double(p.x) * (1 << a)));
            const int j = int(std::floor(double(p.y) * (1 << (m - a))));
            if (++count[size_t(j) * (1 << a) + i] > 1)
                return ::testing::AssertionFailure() << "two points in interval " << i << "/2^" << a
                                                     << " x " << j << "/2^" << m - a;
        }
    }
    return ::testing::AssertionSuccess();
}

TEST(CascadedSobol, DrawsEqualTheDefinitionInAnyOrder) {
    // The renderer's draws (1D, 2D, out of order, across pixels, past the
    // kept chain) are, bit for bit, the construction built from the Sobol'
    // matrices dimension after dimension.
    std::mt19937 rng(7);
    for (const int spp : {1, 3, 16, 64, 200}) {
        CascadedSobolSampler s(SamplerConfig{spp, 11, kResolution});
        for (int trial = 0; trial < 400; ++trial) {
            const Vec2i pixel{int(rng() % 4), int(rng() % 3)};
            const int index = int(rng() % unsigned(spp));
            const int dim = int(rng() % 80);
            s.startPixelSample(pixel, index, dim);
            const bool pair = rng() & 1;
            const Vec2f v = pair ? s.get2D() : Vec2f{s.get1D(), 0.0f};
            ASSERT_EQ(v.x, CascadedSobolSampler::definition(pixel, 11, spp, uint32_t(index), dim))
                << "spp " << spp << " pixel " << pixel.x << "," << pixel.y << " sample " << index
                << " dim " << dim;
            if (pair) {
                ASSERT_EQ(v.y, CascadedSobolSampler::definition(pixel, 11, spp, uint32_t(index),
                                                                dim + 1));
            }
        }
    }
}

TEST(CascadedSobol, EveryConsecutivePairIsANet) {
    // The paper's theorem: for N = 2^m, dimensions (d, d + 1) of a pixel's
    // points form a (0,m,2)-net in base 2 for every d — here every pair of a
    // depth-9 path's dimensions and a few past the kept chain, drawn as the
    // renderer draws them (pixel, 2D layout pairs, 1D otherwise).
    for (int m = 0; m <= 8; ++m)
        for (const uint64_t seed : {0u, 5u})
            for (int d = 0; d < 70; ++d)
                ASSERT_TRUE(isBase2Net(
                    drawPoints("cascaded-sobol", 1 << m, d, d + 1, seed, {9, 4}, kResolution)))
                    << "N=" << (1 << m) << " dims " << d << "," << d + 1 << " seed " << seed;
}

TEST(CascadedSobol, OtherCountsTakeTheFirstPointsOfTheNextNet) {
    // spp = 100 is built as the 128-point set: the same first 100 points,
    // so every dimension keeps at most one point per 1/128 interval.
    for (int d = 0; d < 60; d += 3) {
        const auto hundred = drawPoints("cascaded-sobol", 100, d, d + 1, 2, {3, 3}, kResolution);
        const auto all = drawPoints("cascaded-sobol", 128, d, d + 1, 2, {3, 3}, kResolution);
        std::vector<int> xs(128, 0);
        for (size_t i = 0; i < hundred.size(); ++i) {
            ASSERT_EQ(hundred[i].x, all[i].x) << "dim " << d << " sample " << i;
            ASSERT_EQ(hundred[i].y, all[i].y) << "dim " << d + 1 << " sample " << i;
            ASSERT_EQ(++xs[size_t(hundred[i].x * 128)], 1) << "dim " << d << " sample " << i;
        }
    }
}

TEST(CascadedSobol, UnbiasedAcrossTheCascade) {
    // Integrands over dimensions that the cascade links through the ones
    // between them: one bounce of indirect light (the first vertex's BSDF
    // direction, dims 6,7, and the second's light point, 10,11), and a
    // product over a whole path's first 23 dimensions. Mean over seeds within
    // 3 standard errors of the integral.
    constexpr int kN = 32, kSeeds = 512;
    const auto sumBelowTwo = [](const float* x) {  // P(x6+x7+x10+x11 < 2) = 1/2
        return x[6] + x[7] + x[10] + x[11] < 2.0f ? 1.0 : 0.0;
    };
    const auto product = [](const float* x) {  // Π (1 + sin 2π x_d): integral 1
        double p = 1;
        for (int d = 0; d < 23; ++d) p *= 1 + 0.5 * std::sin(2 * M_PI * x[d]);
        return p;
    };
    for (int which = 0; which < 2; ++which) {
        double sum = 0, squares = 0;
        for (int seed = 0; seed < kSeeds; ++seed) {
            CascadedSobolSampler s(SamplerConfig{kN, uint64_t(seed), kResolution});
            double estimate = 0;
            for (int i = 0; i < kN; ++i) {
                float x[23];
                for (int d = 0; d < 23; ++d) s.startPixelSample({17, 40}, i, d), x[d] = s.get1D();
                estimate += (which == 0 ? sumBelowTwo(x) : product(x)) / kN;
            }
            sum += estimate, squares += estimate * estimate;
        }
        const double mean = sum / kSeeds, truth = which == 0 ? 0.5 : 1.0;
        const double se = std::sqrt(std::max(0.0, squares / kSeeds - mean * mean) / (kSeeds - 1));
        EXPECT_LE(std::abs(mean - truth), 3 * se + 1e-6)
            << (which == 0 ? "indirect bounce" : "path product") << ": mean " << mean << " SE "
            << se;
    }
}

TEST(CascadedSobol, StratifiesThePairsPaddingLeavesRandom) {
    // Dimensions that padding draws from different pairs — a light point's y
    // and the BSDF lobe (4,5), the direction's y and the roulette (7,8), the
    // roulette and the next vertex's light choice (8,9) — are random for
    // sobol-owen and a net here: L2-star discrepancy at N = 256, mean of 8
    // seeds, below half of sobol-owen's (whose 1D draws are stratified
    // alone) and a third of independent's.
    constexpr int kN = 256, kSeeds = 8;
    for (const int d : {4, 7, 8}) {
        double cascaded = 0, padded = 0, independent = 0;
        for (int seed = 0; seed < kSeeds; ++seed) {
            const auto draw = [&](const char* name) {
                return l2StarDiscrepancy(
                           drawPoints(name, kN, d, d + 1, uint64_t(seed), {21, 37}, kResolution)) /
                       kSeeds;
            };
            cascaded += draw("cascaded-sobol");
            padded += draw("sobol-owen");
            independent += draw("independent");
        }
        std::printf("dims %d,%d: L2* cascaded-sobol %.5f sobol-owen %.5f independent %.5f\n", d,
                    d + 1, cascaded, padded, independent);
        EXPECT_LT(2 * cascaded, padded) << "dims " << d << "," << d + 1;
        EXPECT_LT(3 * cascaded, independent) << "dims " << d << "," << d + 1;
    }
}

}  // namespace
}  // namespace pathlab
