// The stratification that defines each sequence.
#include <gtest/gtest.h>

#include <cmath>

#include "sampler_test_util.h"
#include "sampling/lowdiscrepancy.h"

namespace pathlab {
namespace {

using testing::drawPoints;

// True if every elementary interval [i/2^a, (i+1)/2^a) × [j/2^b, (j+1)/2^b)
// with a + b = log2 N holds exactly one point: a (0, m, 2)-net in base 2.
::testing::AssertionResult isZeroMTwoNet(const std::vector<Vec2f>& pts) {
    const int n = int(pts.size());
    const int m = log2Ceil(uint64_t(n));
    for (int a = 0; a <= m; ++a) {
        const int b = m - a;
        std::vector<int> count(size_t(n), 0);
        for (const Vec2f& p : pts) {
            const int i = int(std::floor(double(p.x) * (1 << a)));
            const int j = int(std::floor(double(p.y) * (1 << b)));
            if (++count[size_t(j) * (1 << a) + i] > 1)
                return ::testing::AssertionFailure()
                       << "two points in interval " << i << "/2^" << a << " x " << j << "/2^" << b;
        }
    }
    return ::testing::AssertionSuccess();
}

TEST(SamplerStratification, SobolOwenSobolAndPmj02AreZeroMTwoNets) {
    for (const char* name : {"sobol", "sobol-xor", "sobol-global-owen", "sobol-owen", "zsobol",
                             "sobol-bluenoise", "pmj02"})
        for (int m = 1; m <= 10; ++m)
            for (uint64_t seed : {0, 1, 2}) {
                const int n = 1 << m;
                // Pixel dimensions of a one-pixel image, and a BSDF-direction
                // pair of an image pixel (dims 6,7 = bounceBase(0) + 4, + 5).
                EXPECT_TRUE(isZeroMTwoNet(drawPoints(name, n, 0, 1, seed)))
                    << name << " dims 0,1 N=" << n << " seed " << seed;
                if (std::string(name).starts_with("sobol") && name != std::string("sobol-owen") &&
                    name != std::string("sobol-bluenoise"))
                    continue;  // global sequences: a pixel's points are not a net there
                EXPECT_TRUE(isZeroMTwoNet(drawPoints(name, n, 6, 7, seed, {5, 9}, {64, 64})))
                    << name << " dims 6,7 N=" << n << " seed " << seed;
                EXPECT_TRUE(isZeroMTwoNet(drawPoints(name, n, 17, 18, seed, {5, 9}, {64, 64})))
                    << name << " dims 17,18 N=" << n << " seed " << seed;
            }
}

TEST(SamplerStratification, GlobalSobolDimensionsAreStratifiedAfterScrambling) {
    // Every Sobol' dimension is a (0,1)-sequence: the first 2^k points put one
    // in each interval [i/2^k, (i+1)/2^k). A digital shift and a nested (Owen)
    // scramble permute those intervals, so the scrambled samplers keep it, in
    // every dimension (here of a one-pixel image: every index is the pixel's).
    for (const char* name : {"sobol", "sobol-xor", "sobol-global-owen"})
        for (uint64_t seed : {0, 3}) {
            for (int d = 2; d < 80; d += 7) {
                const auto pair = drawPoints(name, 1024, d, d + 1, seed);
                for (int k = 1; k <= 10; ++k) {
                    std::vector<int> xs(size_t(1) << k, 0), ys(size_t(1) << k, 0);
                    for (int i = 0; i < (1 << k); ++i) {
                        ++xs[size_t(std::floor(double(pair[size_t(i)].x) * (1 << k)))];
                        ++ys[size_t(std::floor(double(pair[size_t(i)].y) * (1 << k)))];
                    }
                    for (int c = 0; c < (1 << k); ++c)
                        ASSERT_TRUE(xs[size_t(c)] == 1 && ys[size_t(c)] == 1)
                            << name << " seed " << seed << " dims " << d << "," << d + 1
                            << " k=" << k << " interval " << c;
                }
            }
        }
}

TEST(SamplerStratification, ProgressivePrefixesStayNets) {
    // The first 2^k of 2^10 samples of a pixel are themselves a (0,k,2)-net.
    // ZSobol permutes base-4 digits, so only its 4^k prefixes are nets.
    for (const std::string name : {"sobol-owen", "pmj02", "zsobol", "sobol-bluenoise"}) {
        const auto pts = drawPoints(name, 1024, 6, 7, 4, {3, 3}, {16, 16});
        for (int k = name == "zsobol" ? 2 : 1; k <= 10; k += name == "zsobol" ? 2 : 1)
            EXPECT_TRUE(isZeroMTwoNet({pts.begin(), pts.begin() + (1 << k)})) << name << " k=" << k;
    }
}

TEST(SamplerStratification, OwenHaltonHasOnePointPerBaseStratum) {
    // N = b^k consecutive samples put one point into every 1/b^k interval of
    // the dimension whose base is b (each dimension on its own).
    const int* primes = primeTable();
    for (const std::string name : {"halton", "halton-rd", "halton-owen"})
        for (int d = 2; d < 8; ++d) {
            const int b = primes[d];
            for (int k = 1; b <= 64 && std::pow(b, k) <= 1024; ++k) {
                const int n = int(std::lround(std::pow(b, k)));
                for (Vec2i res : {Vec2i{1, 1}, Vec2i{8, 8}}) {
                    const auto pts = drawPoints(name, n, d, d + 1 == 3 ? 4 : d + 1, 3, {3, 5}, res);
                    std::vector<int> count(size_t(n), 0);
                    // Unscrambled points sit exactly on stratum boundaries,
                    // which float rounding may put a hair below: allow it.
                    const double tolerance = name == "halton" ? 1 + 2e-7 : 1;
                    for (const Vec2f& p : pts)
                        ++count[size_t(std::floor(double(p.x) * n * tolerance))];
                    for (int c : count) ASSERT_EQ(c, 1) << name << " dim " << d << " N=" << n;
                }
            }
        }
}

TEST(SamplerStratification, StratifiedHasOnePointPerStratum) {
    for (int n : {1, 4, 8, 16, 36, 64, 100, 128}) {
        SamplerConfig config{n, 9, {8, 8}};
        StratifiedSampler sampler(config);
        const int nx = sampler.xStrata(), ny = sampler.yStrata();
        ASSERT_EQ(nx * ny, n);
        for (auto [i, j] : {std::pair{0, 1}, std::pair{3, 4}, std::pair{6, 7}}) {
            const auto pts = drawPoints("stratified", n, i, j, 9, {1, 2}, {8, 8});
            std::vector<int> count(size_t(n), 0);
            for (const Vec2f& p : pts)
                ++count[size_t(std::floor(double(p.y) * ny)) * nx +
                        size_t(std::floor(double(p.x) * nx))];
            for (int c : count) ASSERT_EQ(c, 1) << "N=" << n << " dims " << i << "," << j;
        }
        // 1D draws (light choice, dimension 2): one point in each of N intervals.
        const auto pts = drawPoints("stratified", n, 2, 5, 9, {1, 2}, {8, 8});
        std::vector<int> count(size_t(n), 0);
        for (const Vec2f& p : pts) ++count[size_t(std::floor(double(p.x) * n))];
        for (int c : count) ASSERT_EQ(c, 1) << "1D N=" << n;
    }
}

}  // namespace
}  // namespace pathlab
