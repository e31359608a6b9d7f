// The blue-noise texture generator (void-and-cluster) and its cache.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/rng.h"
#include "sampling/blue_noise.h"
#include "sampling/spectrum.h"

namespace pathlab {
namespace {

// Mean power of rings [lo, hi] of a radially averaged spectrum.
double band(const std::vector<double>& spectrum, int lo, int hi) {
    double sum = 0;
    for (int r = lo; r <= hi; ++r) sum += spectrum[r];
    return sum / (hi - lo + 1);
}

std::vector<double> asDoubles(const BlueNoiseTexture& t) {
    std::vector<double> v(t.rank.size());
    for (size_t i = 0; i < v.size(); ++i) v[i] = t.fixedPoint[i] * 0x1p-32;
    return v;
}

TEST(BlueNoiseGenerator, EveryValueAppearsOnce) {
    const BlueNoiseTexture t = generateBlueNoiseTexture(32, 1);
    const size_t n = t.rank.size();
    std::vector<int> seen(n, 0);
    for (uint32_t r : t.rank) {
        ASSERT_LT(r, n);
        ++seen[r];
    }
    for (int s : seen) ASSERT_EQ(s, 1);
    // Hence a flat histogram of values: 16 bins of exactly n/16.
    std::vector<int> histogram(16, 0);
    for (int y = 0; y < t.size; ++y)
        for (int x = 0; x < t.size; ++x) {
            const float v = t.value(x, y);
            ASSERT_TRUE(v > 0 && v < 1);
            ++histogram[size_t(v * 16)];
        }
    for (int h : histogram) EXPECT_EQ(h, int(n / 16));
}

TEST(BlueNoiseGenerator, SpectrumIsBlue) {
    const int size = 64;
    const BlueNoiseTexture t = generateBlueNoiseTexture(size, 2);
    const std::vector<double> blue = radialPowerSpectrum(asDoubles(t), size, size);
    // White noise for comparison: power ≈ 1 in every ring.
    Pcg32 rng(7, 0);
    std::vector<double> white(size_t(size) * size);
    for (double& v : white) v = rng.nextFloat();
    const std::vector<double> flat = radialPowerSpectrum(white, size, size);
    const double lowBlue = band(blue, 1, size / 8), highBlue = band(blue, size / 4, size / 2);
    const double lowWhite = band(flat, 1, size / 8), highWhite = band(flat, size / 4, size / 2);
    std::printf("low/high band power: void-and-cluster %.4f, white noise %.3f\n",
                lowBlue / highBlue, lowWhite / highWhite);
    EXPECT_LT(lowBlue / highBlue, 0.1);
    EXPECT_GT(lowWhite / highWhite, 0.6);
    EXPECT_NEAR(highWhite, 1.0, 0.25);
}

TEST(BlueNoiseGenerator, IsDeterministicAndSeeded) {
    EXPECT_EQ(generateBlueNoiseTexture(16, 3).rank, generateBlueNoiseTexture(16, 3).rank);
    EXPECT_NE(generateBlueNoiseTexture(16, 3).rank, generateBlueNoiseTexture(16, 4).rank);
}

TEST(BlueNoiseCache, GeneratesOnceThenReadsAndRepairsCorruptFiles) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("pathlab-bn-test-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    const auto file = dir / "bn.bin";
    const auto first = loadOrCreateBlueNoiseTexture(file, 16, 5);
    ASSERT_TRUE(std::filesystem::exists(file));
    const auto written = std::filesystem::last_write_time(file);
    const auto second = loadOrCreateBlueNoiseTexture(file, 16, 5);
    EXPECT_EQ(first->rank, second->rank);
    EXPECT_EQ(std::filesystem::last_write_time(file), written);  // read, not rewritten
    // No temporaries left behind.
    int entries = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir)) (void)e, ++entries;
    EXPECT_EQ(entries, 1);
    // A truncated file is regenerated.
    std::filesystem::resize_file(file, 30);
    const auto third = loadOrCreateBlueNoiseTexture(file, 16, 5);
    EXPECT_EQ(third->rank, first->rank);
    EXPECT_GT(std::filesystem::file_size(file), 30u);
    std::filesystem::remove_all(dir);
}

TEST(BlueNoiseSampler, NeighbouringPixelsGetBlueNoiseValues) {
    // One dimension over a 64 × 64 block of pixels at sample 0 is a shifted
    // piece of the texture, so its spectrum is blue too.
    BlueNoiseSampler sampler(SamplerConfig{1, 0, {128, 128}});
    const int size = 64;
    std::vector<double> values(size_t(size) * size);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            sampler.startPixelSample({x, y}, 0, 6);
            values[size_t(y) * size + x] = sampler.get1D();
        }
    const std::vector<double> s = radialPowerSpectrum(values, size, size);
    EXPECT_LT(band(s, 1, size / 8) / band(s, size / 4, size / 2), 0.3);
}

// The draws keep each dimension's rotation while the sample index stays in
// one block of the texture's size: in any order of pixels, samples and
// dimensions (past the cached ones too, and across blocks) they are the
// lookup computed from scratch.
TEST(BlueNoiseSampler, CachedDrawsEqualTheLookupInAnyOrder) {
    BlueNoiseSampler sampler(SamplerConfig{512, 9, {64, 64}});
    Pcg32 rng(11, 0);
    for (int k = 0; k < 20000; ++k) {
        const Vec2i p{int(rng.nextUInt() % 64), int(rng.nextUInt() % 64)};
        const int index = int(rng.nextUInt() % 512);
        const int d = int(rng.nextUInt() % 72);
        sampler.startPixelSample(p, index, d);
        if (rng.nextUInt() & 1) {
            ASSERT_EQ(sampler.get1D(), sampler.definition(p, uint64_t(index), d));
        } else {
            const Vec2f u = sampler.get2D();
            ASSERT_EQ(u.x, sampler.definition(p, uint64_t(index), d));
            ASSERT_EQ(u.y, sampler.definition(p, uint64_t(index), d + 1));
        }
    }
}

TEST(Spectrum, PointSetSpectraOfGridAndRandomPoints) {
    // Random points: flat spectrum ≈ 1; the DC term equals N.
    Pcg32 rng(3, 0);
    std::vector<Vec2f> pts(1024);
    for (Vec2f& p : pts) p = {rng.nextFloat(), rng.nextFloat()};
    const auto s = radialPowerSpectrum(pts, 32);
    EXPECT_NEAR(s[0], 1024, 1e-6);
    double mean = 0;
    for (int r = 4; r <= 32; ++r) mean += s[r];
    EXPECT_NEAR(mean / 29, 1.0, 0.15);
}

}  // namespace
}  // namespace pathlab
