// `sobol-bluenoise`: the keys' construction and cache, the nets its ranking
// keeps, unbiasedness, and the blue-noise error it is made for.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>

#include "sampler_test_util.h"
#include "sampling/sobol_bluenoise.h"
#include "sampling/spectrum.h"

namespace pathlab {
namespace {

using testing::drawPoints;

// A small tile, quick to optimise, for the optimiser's own properties.
SobolBlueNoiseOptimizer smallSettings() {
    SobolBlueNoiseOptimizer s;
    s.size = 16;
    s.levels = 4;
    s.passes = 4;
    s.swapRadius = 3;
    return s;
}

bool isNet(const std::vector<Vec2f>& pts, int m) {
    for (int a = 0; a <= m; ++a) {
        std::vector<int> count(size_t(1) << m, 0);
        for (const Vec2f& p : pts) {
            const int i = int(std::floor(double(p.x) * (1 << a)));
            const int j = int(std::floor(double(p.y) * (1 << (m - a))));
            if (++count[size_t(j) * (1 << a) + i] > 1) return false;
        }
    }
    return true;
}

TEST(SobolBlueNoise, RankingKeepsEveryPowerOfTwoPrefixANet) {
    // Whatever a pixel's ranking key, its first 2^k samples are a
    // (0,k,2)-net, k ≤ 8, in every optimised pair and in a fallback pair.
    for (uint64_t seed : {0, 7})
        for (Vec2i pixel : {Vec2i{0, 0}, Vec2i{37, 101}, Vec2i{127, 64}})
            for (int d : {0, 3, 6, 17}) {
                const auto pts =
                    drawPoints("sobol-bluenoise", 256, d, d + 1, seed, pixel, {128, 128});
                for (int k = 0; k <= 8; ++k)
                    EXPECT_TRUE(isNet({pts.begin(), pts.begin() + (1 << k)}, k))
                        << "seed " << seed << " pixel " << pixel.x << "," << pixel.y << " dims "
                        << d << " k=" << k;
            }
}

TEST(SobolBlueNoise, PairIsScrambledSobolAndANestedBijection) {
    // For a fixed key, index ↦ point maps the 2^16 indices of an aligned
    // block to 2^16 distinct 16-bit strata of x (and of y); and two values
    // with the same top j bits keep equal top j bits after the scramble
    // (Owen's nested property: a bit's flip depends only on bits above it).
    const SobolBlueNoiseKey key{0x9e3779b9u, 0x85ebca6bu, 0xc2b2ae35u, 0x5du};
    // By definition: Sobol' dimensions 0 and 1 of the ranked index (the
    // nested scramble, then the offset), each Owen-scrambled with its seed.
    for (uint32_t i : {0u, 1u, 2u, 3u, 255u, 256u, 65535u, 0x12345678u, 0xffffffffu}) {
        const uint64_t xy = sobolBlueNoisePair(key, i);
        const uint32_t ranked = owenScramble(i, key.rank) ^ key.offset;
        EXPECT_EQ(uint32_t(xy), owenScramble(sobolBits(sobolMatrices(), ranked, 0), key.scrambleX));
        EXPECT_EQ(uint32_t(xy >> 32),
                  owenScramble(sobolBits(sobolMatrices(), ranked, 1), key.scrambleY));
    }
    std::vector<uint8_t> seenX(1 << 16, 0), seenY(1 << 16, 0);
    for (uint32_t i = 0; i < (1u << 16); ++i) {
        const uint64_t xy = sobolBlueNoisePair(key, i);
        ASSERT_EQ(seenX[uint32_t(xy) >> 16]++, 0) << i;
        ASSERT_EQ(seenY[uint32_t(xy >> 32) >> 16]++, 0) << i;
    }
    for (uint32_t v = 1; v < 4096; ++v) {
        const uint32_t a = v * 0x9e3779b1u, b = a ^ (v * 0x7f4a7c15u >> (v % 31));
        const int common = a == b ? 32 : __builtin_clz(a ^ b);
        const uint32_t sa = owenScramble(a, key.scrambleX), sb = owenScramble(b, key.scrambleX);
        EXPECT_GE(sa == sb ? 32 : __builtin_clz(sa ^ sb), common) << v;
        EXPECT_EQ(common == 32, sa == sb);
    }
}

TEST(SobolBlueNoise, OptimiserPermutesThePoolDeterministically) {
    const SobolBlueNoiseOptimizer s = smallSettings();
    const SobolBlueNoiseKeys a = optimizeSobolBlueNoiseKeys(s), b = optimizeSobolBlueNoiseKeys(s);
    EXPECT_EQ(a.key, b.key);
    const std::vector<SobolBlueNoiseKey> pool = sobolBlueNoiseKeyPool(s);
    EXPECT_NE(a.key, pool);  // it moved keys
    std::multiset<std::tuple<uint32_t, uint32_t, uint32_t>> fromPool, fromTile;
    std::set<uint32_t> offsets;
    for (const auto& k : pool) fromPool.insert({k.rank, k.scrambleX, k.scrambleY});
    for (const auto& k : a.key) {
        fromTile.insert({k.rank, k.scrambleX, k.scrambleY});
        EXPECT_LT(k.offset, 1u << s.levels);  // ranking bits below the top level only
        offsets.insert(k.offset);
    }
    EXPECT_EQ(fromPool, fromTile);
    EXPECT_GT(offsets.size(), size_t(1) << (s.levels - 1));  // it ranked
    SobolBlueNoiseOptimizer other = s;
    other.seed += 1;
    EXPECT_NE(optimizeSobolBlueNoiseKeys(other).key, a.key);
}

// Low-frequency power (rings 1..size/8, white = 1) of a tile's error image
// at `spp`, straight from its keys, for `f` seen through a digital shift.
template <class F>
double tileLowFrequencyPower(const SobolBlueNoiseKeys& tile, int spp, uint64_t shift, F f) {
    std::vector<double> image(tile.key.size());
    for (size_t p = 0; p < image.size(); ++p) {
        double sum = 0;
        for (int i = 0; i < spp; ++i) {
            const uint64_t xy = sobolBlueNoisePair(tile.key[p], uint32_t(i)) ^ shift;
            sum += f(Vec2f{fixedPointToFloat(uint32_t(xy)), fixedPointToFloat(uint32_t(xy >> 32))});
        }
        image[p] = sum / spp;
    }
    const std::vector<double> power = radialPowerSpectrum(image, tile.size, tile.size);
    double low = 0;
    for (int r = 1; r <= tile.size / 8; ++r) low += power[size_t(r)];
    return low / (tile.size / 8);
}

double disk(Vec2f p) {
    return (p.x - 0.45) * (p.x - 0.45) + (p.y - 0.55) * (p.y - 0.55) < 0.1 ? 1.0 : 0.0;
}

TEST(SobolBlueNoise, RankingMakesEveryPrefixBlue) {
    // The ranking bits are what make the 2^j-sample prefixes (j below the
    // top level) blue: the same tile with its offsets cleared keeps the
    // arrangement of the full sets but takes arbitrary halves of them.
    SobolBlueNoiseOptimizer s = smallSettings();
    s.size = 32;
    const SobolBlueNoiseKeys ranked = optimizeSobolBlueNoiseKeys(s);
    SobolBlueNoiseKeys unranked = ranked;
    for (SobolBlueNoiseKey& k : unranked.key) k.offset = 0;
    for (int j = 0; j < s.levels; ++j) {
        double blue = 0, plain = 0;
        for (uint64_t shift : {0ull, 0x243f6a8885a308d3ull, 0x13198a2e03707344ull}) {
            blue += tileLowFrequencyPower(ranked, 1 << j, shift, disk);
            plain += tileLowFrequencyPower(unranked, 1 << j, shift, disk);
        }
        std::printf("%d spp: low-frequency power %.3f ranked, %.3f unranked\n", 1 << j, blue / 3,
                    plain / 3);
        EXPECT_LT(blue, 0.7 * plain) << (1 << j) << " spp";
    }
}

TEST(SobolBlueNoise, CacheIsWrittenOnceReadAndRepaired) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("pathlab-sbn-test-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    const auto file = dir / "keys.bin";
    const SobolBlueNoiseOptimizer s = smallSettings();
    const auto first = loadOrCreateSobolBlueNoiseKeys(file, s);
    ASSERT_TRUE(std::filesystem::exists(file));
    const auto written = std::filesystem::last_write_time(file);
    EXPECT_EQ(loadOrCreateSobolBlueNoiseKeys(file, s)->key, first->key);
    EXPECT_EQ(std::filesystem::last_write_time(file), written);  // read, not rewritten
    int entries = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir)) (void)e, ++entries;
    EXPECT_EQ(entries, 1);  // no temporary left behind
    // A key that is not the pool's (one flipped bit of the last key's seed):
    // rejected, the tile optimised again.
    {
        std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(-1, std::ios::end);
        f.put(char(0x5a));
    }
    EXPECT_EQ(loadOrCreateSobolBlueNoiseKeys(file, s)->key, first->key);
    EXPECT_NE(std::filesystem::last_write_time(file), written);
    // Truncated, or made with other settings: the same.
    std::filesystem::resize_file(file, 30);
    EXPECT_EQ(loadOrCreateSobolBlueNoiseKeys(file, s)->key, first->key);
    SobolBlueNoiseOptimizer other = s;
    other.passes += 1;
    EXPECT_NE(loadOrCreateSobolBlueNoiseKeys(file, other)->key, first->key);
    EXPECT_THROW(loadOrCreateSobolBlueNoiseKeys(file, SobolBlueNoiseOptimizer{.size = 12}),
                 std::invalid_argument);
    std::filesystem::remove_all(dir);
}

bool samePoints(const std::vector<Vec2f>& a, const std::vector<Vec2f>& b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (a[i].x != b[i].x || a[i].y != b[i].y) return false;
    return true;
}

TEST(SobolBlueNoise, FallbackDimensionsAreSobolOwensBitForBit) {
    // Pairs (2D draws where the layout has them, else two 1D draws) that
    // touch no optimised dimension.
    for (auto [i, j] : {std::pair{2, 5}, std::pair{8, 9}, std::pair{10, 11}, std::pair{13, 14},
                        std::pair{40, 41}})
        EXPECT_TRUE(samePoints(drawPoints("sobol-bluenoise", 32, i, j, 3, {9, 4}, {16, 16}),
                               drawPoints("sobol-owen", 32, i, j, 3, {9, 4}, {16, 16})))
            << "dims " << i << "," << j;
    for (int d : {0, 3, 6})
        EXPECT_FALSE(samePoints(drawPoints("sobol-bluenoise", 32, d, d + 1, 3, {9, 4}, {16, 16}),
                                drawPoints("sobol-owen", 32, d, d + 1, 3, {9, 4}, {16, 16})))
            << "dims " << d;
}

double gaussian(Vec2f p) {
    return std::exp(-((p.x - 0.5) * (p.x - 0.5) + (p.y - 0.3) * (p.y - 0.3)) / (2 * 0.2 * 0.2));
}

TEST(SobolBlueNoise, OnePixelSampleIsUnbiasedOverSeeds) {
    // I = ∫∫ gaussian over the square, by a fine midpoint rule.
    double integral = 0;
    for (int y = 0; y < 1024; ++y)
        for (int x = 0; x < 1024; ++x) integral += gaussian({(x + 0.5f) / 1024, (y + 0.5f) / 1024});
    integral /= 1024.0 * 1024.0;
    constexpr int kSeeds = 2048;
    for (int d : {0, 3, 6}) {
        double sum = 0, squares = 0;
        for (int seed = 0; seed < kSeeds; ++seed) {
            const double f = gaussian(
                drawPoints("sobol-bluenoise", 1, d, d + 1, uint64_t(seed), {5, 77}, {128, 128})[0]);
            sum += f, squares += f * f;
        }
        const double mean = sum / kSeeds, se = std::sqrt((squares / kSeeds - mean * mean) / kSeeds);
        EXPECT_LE(std::abs(mean - integral), 3 * se + 1e-6) << "dims " << d;
    }
}

// The error image over the 128 × 128 tile of an N-spp estimate of `f` in
// dims (d, d+1): its ring-averaged power at low frequencies (rings 1–16 of
// 64), relative to white noise's 1.
template <class F>
double lowFrequencyPower(const std::string& sampler, int spp, int d, uint64_t seed, F f) {
    constexpr int kSize = 128;
    AnySampler any = makeSampler(sampler, SamplerConfig{spp, seed, {kSize, kSize}});
    std::vector<double> image(size_t(kSize) * kSize);
    std::visit(
        [&](auto& s) {
            for (int y = 0; y < kSize; ++y)
                for (int x = 0; x < kSize; ++x) {
                    double sum = 0;
                    for (int i = 0; i < spp; ++i)
                        sum += f(sampleDimensions(s, {x, y}, i, d, d + 1));
                    image[size_t(y) * kSize + x] = sum / spp;
                }
        },
        any);
    const std::vector<double> power = radialPowerSpectrum(image, kSize, kSize);
    double low = 0;
    for (int r = 1; r <= kSize / 8; ++r) low += power[size_t(r)];
    return low / (kSize / 8);
}

TEST(SobolBlueNoise, ErrorIsBlueNoiseAtOneAndFourSpp) {
    // Integrands the optimiser never saw: a disk and a smooth Gaussian.
    for (int spp : {1, 4})
        for (int d : {0, 3}) {
            double blue = 0, owen = 0;
            for (uint64_t seed : {1, 2}) {
                blue += lowFrequencyPower("sobol-bluenoise", spp, d, seed, disk) / 4;
                blue += lowFrequencyPower("sobol-bluenoise", spp, d, seed, gaussian) / 4;
                owen += lowFrequencyPower("sobol-owen", spp, d, seed, disk) / 4;
                owen += lowFrequencyPower("sobol-owen", spp, d, seed, gaussian) / 4;
            }
            std::printf("%d spp, dims %d,%d: low-frequency error power %.3f (sobol-owen %.3f)\n",
                        spp, d, d + 1, blue, owen);
            EXPECT_LT(blue, 0.85 * owen) << spp << " spp, dims " << d;
        }
}

}  // namespace
}  // namespace pathlab
