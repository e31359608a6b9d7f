// Exact known values, the [0,1) range, determinism and seeding of every sampler.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "core/error.h"
#include "render/path_integrator.h"
#include "sampler_test_util.h"
#include "sampling/lowdiscrepancy.h"
#include "sampling/sampler_cost.h"

namespace pathlab {
namespace {

using testing::allSamplerNames;
using testing::drawPoints;

double referenceRadicalInverse(uint64_t a, int base) {
    double value = 0, weight = 1.0 / base;
    for (; a; a /= base, weight /= base) value += double(a % base) * weight;
    return value;
}

TEST(SamplerValues, ListsTheFifteenSamplersInOrder) {
    const std::vector<std::string> expected = {
        "standard",    "halton",     "halton-rd",       "halton-owen", "blue-noise",
        "independent", "stratified", "sobol",           "sobol-xor",   "sobol-global-owen",
        "sobol-owen",  "zsobol",     "sobol-bluenoise", "pmj02",       "cascaded-sobol"};
    EXPECT_EQ(allSamplerNames(), expected);
    EXPECT_THROW(makeSampler("no-such-sampler", SamplerConfig{}), InputError);
}

TEST(SamplerValues, MinimalStandardTenThousandthOutput) {
    // Park & Miller 1988: x_10000 = 1043618065 from the seed 1 (the C++ default).
    MinimalStandardEngine engine;
    engine.discard(9999);
    EXPECT_EQ(engine(), 1043618065u);
}

TEST(SamplerValues, StandardLaneValuesAreTheDistributionsFloats) {
    // StandardSampler::canonicalFloat, which the lane draws use, against
    // std::uniform_real_distribution<float> on the engine whose next output is
    // x: every output whose float rounds into the clamp (the top 2^8), the
    // bottom, and a spread between. The engine seeded with s outputs
    // 16807·s mod (2^31 − 1), so s = x·16807^-1.
    constexpr uint64_t m = 2147483647, inverse = 1407677000;  // 16807·inverse ≡ 1
    ASSERT_EQ(16807 * inverse % m, 1u);
    std::uniform_real_distribution<float> distribution(0.0f, 1.0f);
    auto expectSame = [&](uint32_t x) {
        MinimalStandardEngine engine(uint32_t(x * inverse % m));
        const float v = distribution(engine);
        ASSERT_EQ(StandardSampler::canonicalFloat(x), v < kOneMinusEpsilon ? v : kOneMinusEpsilon)
            << "engine output " << x;
    };
    for (uint32_t x = 1; x < 4096; ++x) expectSame(x);
    for (uint32_t x = uint32_t(m) - 1; x > uint32_t(m) - 4096; --x) expectSame(x);
    std::mt19937 rng(5);
    for (int i = 0; i < 200000; ++i) expectSame(1 + rng() % uint32_t(m - 1));
}

TEST(SamplerValues, StandardSeedStatesAreTheHashModuloTheStateCount) {
    // The division-free x mod (2^31 − 2) that picks a sample's seed state,
    // against `%`: around every multiple of the modulus and of 2^30 up to
    // 2^64, and on random 64-bit hashes.
    constexpr uint64_t n = 2147483646;
    auto expectSame = [](uint64_t x) {
        ASSERT_EQ(StandardSampler::moduloStateCount(x), x % n) << "x = " << x;
    };
    for (uint64_t x = 0; x < 5000; ++x) expectSame(x);
    for (uint64_t k = 1; k < 64; ++k)
        for (uint64_t base : {uint64_t(1) << k, n * ((uint64_t(1) << k) / n)})
            for (uint64_t d = 0; d < 8; ++d) expectSame(base + d), expectSame(base - d);
    for (uint64_t d = 0; d < 5000; ++d) expectSame(~uint64_t(0) - d);
    std::mt19937_64 rng(9);
    for (int i = 0; i < 1000000; ++i) expectSame(rng());
}

TEST(SamplerValues, HaltonPixelDimensionsAreRadicalInversesInBases2And3) {
    const auto pts = drawPoints("halton", 200, 0, 1);
    for (int i = 0; i < 200; ++i) {
        EXPECT_FLOAT_EQ(pts[i].x, float(referenceRadicalInverse(i, 2))) << i;
        EXPECT_FLOAT_EQ(pts[i].y, float(referenceRadicalInverse(i, 3))) << i;
    }
    // Higher dimensions use the next primes: dimension 2 base 5, 3 base 7.
    const auto high = drawPoints("halton", 50, 2, 3);
    for (int i = 0; i < 50; ++i) {
        EXPECT_FLOAT_EQ(high[i].x, float(referenceRadicalInverse(i, 5))) << i;
        EXPECT_FLOAT_EQ(high[i].y, float(referenceRadicalInverse(i, 7))) << i;
    }
}

TEST(SamplerValues, SobolStartsWithTheKnownPoints) {
    const auto pts = drawPoints("sobol", 4, 0, 1);
    const float expected[4][2] = {{0, 0}, {0.5f, 0.5f}, {0.75f, 0.25f}, {0.25f, 0.75f}};
    for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(pts[i].x, expected[i][0]) << i;
        EXPECT_EQ(pts[i].y, expected[i][1]) << i;
    }
    // Direction numbers of the third dimension (x^2 + x + 1, m = 1, 3):
    // v = 1/2, 3/4, then m_3 = 2·3 ⊕ 4·1 ⊕ 1 = 3 → 3/8.
    const uint32_t* c = sobolMatrices() + 2 * kSobolMatrixColumns;
    EXPECT_EQ(c[0], 0x80000000u);
    EXPECT_EQ(c[1], 0xc0000000u);
    EXPECT_EQ(c[2], 0x60000000u);
}

TEST(SamplerValues, ImagePlaneMappingPutsEverySampleInsideItsPixel) {
    // Global sequences: every pixel's samples are the sequence points whose
    // first two coordinates lie inside the pixel, and pixels never share them.
    const Vec2i res{13, 7};
    const uint32_t* m = sobolMatrices();
    const SobolImageMapping sobolMap(m, res);
    const HaltonImageMapping haltonMap(res);
    std::vector<uint64_t> seen;
    for (int y = 0; y < res.y; ++y)
        for (int x = 0; x < res.x; ++x)
            for (int i = 0; i < 8; ++i) {
                const uint64_t g = sobolMap.index(m, {x, y}, i);
                seen.push_back(g);
                EXPECT_EQ(int(sobolBits(m, g, 0) >> (32 - sobolMap.log2Scale)), x);
                EXPECT_EQ(int(sobolBits(m, g, 1) >> (32 - sobolMap.log2Scale)), y);
                const uint64_t h = haltonMap.index({x, y}, i);
                EXPECT_EQ(int(std::floor(referenceRadicalInverse(h, 2) * haltonMap.baseScales[0])),
                          x);
                EXPECT_EQ(int(std::floor(referenceRadicalInverse(h, 3) * haltonMap.baseScales[1])),
                          y);
            }
    std::sort(seen.begin(), seen.end());
    EXPECT_EQ(std::adjacent_find(seen.begin(), seen.end()), seen.end());
}

TEST(SamplerValues, EveryValueIsInTheUnitIntervalForManyDimensions) {
    for (const std::string& name : allSamplerNames()) {
        AnySampler sampler = makeSampler(name, SamplerConfig{16, 7, {32, 32}});
        std::visit(
            [&](auto& s) {
                for (Vec2i p : {Vec2i{0, 0}, Vec2i{31, 17}})
                    for (int i = 0; i < 16; ++i) {
                        s.startPixelSample(p, i, 0);
                        const Vec2f px = s.getPixel2D();
                        ASSERT_TRUE(px.x >= 0 && px.x < 1 && px.y >= 0 && px.y < 1) << name;
                        for (int d = 2; d < 202;) {
                            if (d % 3 == 0) {
                                const Vec2f u = s.get2D();
                                ASSERT_TRUE(u.x >= 0 && u.x < 1 && u.y >= 0 && u.y < 1) << name;
                                d += 2;
                            } else {
                                const float u = s.get1D();
                                ASSERT_TRUE(u >= 0 && u < 1) << name << " dim " << d;
                                ++d;
                            }
                        }
                    }
            },
            sampler);
    }
    // Far past the native dimensions too (Halton wraps after 1000 bases,
    // Sobol' after 3667 dimensions).
    for (const std::string& name : allSamplerNames())
        for (int d : {998, 999, 3665, 3666, 3667, 5000})
            for (const Vec2f& u : drawPoints(name, 8, d, d + 1, 3))
                ASSERT_TRUE(u.x >= 0 && u.x < 1 && u.y >= 0 && u.y < 1) << name << " dim " << d;
}

TEST(SamplerValues, SameSeedSameOutputAndSeedChangesRandomizedSamplers) {
    for (const std::string& name : allSamplerNames()) {
        for (auto [i, j] : {std::pair{0, 1}, std::pair{3, 4}, std::pair{6, 7}, std::pair{2, 8}}) {
            const auto a = drawPoints(name, 16, i, j, 5, {2, 3}, {8, 8});
            const auto b = drawPoints(name, 16, i, j, 5, {2, 3}, {8, 8});
            const auto c = drawPoints(name, 16, i, j, 6, {2, 3}, {8, 8});
            bool same = true, differs = false;
            for (int k = 0; k < 16; ++k) {
                same = same && a[k].x == b[k].x && a[k].y == b[k].y;
                differs = differs || a[k].x != c[k].x || a[k].y != c[k].y;
            }
            EXPECT_TRUE(same) << name;
            // The global Halton/Sobol' samplers leave the pixel dimensions
            // unscrambled (they decide which pixel a point belongs to).
            const bool pixelDims = i == 0;
            const bool globalMapped = name.rfind("halton", 0) == 0 || name.rfind("sobol", 0) == 0;
            if (testing::isRandomized(name) &&
                !(pixelDims && globalMapped && name != "sobol-owen")) {
                EXPECT_TRUE(differs) << name << " dims " << i << "," << j;
            }
            if (!testing::isRandomized(name)) {
                EXPECT_FALSE(differs) << name;
            }
        }
    }
}

TEST(SamplerValues, SamplesDoNotDependOnWhatWasDrawnBefore) {
    // startPixelSample(p, i, d) must give dimension d's value however many
    // draws came before it — the renderer restarts at every bounce.
    for (const std::string& name : allSamplerNames()) {
        AnySampler a = makeSampler(name, SamplerConfig{4, 1, {4, 4}});
        AnySampler b = a;
        std::visit(
            [&](auto& s) {
                auto& t = std::get<std::decay_t<decltype(s)>>(b);
                s.startPixelSample({1, 2}, 3, 0);
                (void)s.getPixel2D();
                for (int k = 0; k < 7; ++k) (void)s.get1D();
                const float u = s.get1D();  // dimension 9
                t.startPixelSample({1, 2}, 3, 9);
                EXPECT_EQ(u, t.get1D()) << name;
            },
            a);
    }
}

TEST(SamplerValues, VertexDrawsSkipDimensionsWithoutChangingThem) {
    // A path vertex draws only the dimensions it uses (VertexDimensions in the
    // integrator); each must be the value drawing the vertex's whole block in
    // order gives, whichever draws were skipped before it.
    struct Pattern {
        bool choice, light, lobe, direction, roulette;
    };
    const Pattern patterns[] = {{false, true, false, true, true},     // diffuse, one light
                                {true, true, false, true, false},     // before roulette
                                {false, false, true, false, true},    // glass
                                {false, false, false, false, true}};  // mirror
    for (const std::string& name : allSamplerNames()) {
        const AnySampler prototype = makeSampler(name, SamplerConfig{8, 2, {8, 8}});
        AnySampler whole = prototype, skipping = prototype;
        std::visit(
            [&](auto& s) {
                using S = std::decay_t<decltype(s)>;
                auto& t = std::get<S>(skipping);
                for (const Pattern& use : patterns)
                    for (int depth : {0, 3})
                        for (int index : {0, 5}) {
                            s.startPixelSample({3, 1}, index, dims::bounceBase(depth));
                            const float choice = s.get1D();
                            const Vec2f light = s.get2D();
                            const float lobe = s.get1D();
                            const Vec2f direction = s.get2D();
                            const float roulette = s.get1D();

                            PathCounters counters;
                            VertexDimensions<S> draws(t, {3, 1}, index, depth, counters);
                            uint64_t drawn = 0;
                            auto expectPair = [&](int offset, Vec2f expected) {
                                const Vec2f u = draws.get2D(offset);
                                EXPECT_EQ(u.x, expected.x) << name;
                                EXPECT_EQ(u.y, expected.y) << name;
                                drawn += 2;
                            };
                            if (use.choice) {
                                EXPECT_EQ(draws.get1D(dims::kLightChoice), choice) << name;
                                drawn += 1;
                            }
                            if (use.light) expectPair(dims::kLightPoint, light);
                            if (use.lobe) {
                                EXPECT_EQ(draws.get1D(dims::kBsdfLobe), lobe) << name;
                                drawn += 1;
                            }
                            if (use.direction) expectPair(dims::kBsdfDirection, direction);
                            if (use.roulette) {
                                EXPECT_EQ(draws.get1D(dims::kRoulette), roulette) << name;
                                drawn += 1;
                            }
                            EXPECT_EQ(counters.dimensions, drawn) << name;
                        }
            },
            whole);
    }
}

TEST(SamplerValues, IndependentIsPcg32AtTheSampleAndDimensionOffset) {
    // Whatever order the renderer asks in (forward, backward, new sample, new
    // pixel), dimension d of sample i in pixel p is the PCG32 output at offset
    // i·stride + d of the stream hashed from (p, seed).
    const uint64_t seed = 7;
    IndependentSampler sampler(SamplerConfig{64, seed, {8, 8}});
    std::mt19937 pick(3);
    for (int call = 0; call < 2000; ++call) {
        const Vec2i p{int(pick() % 3), int(pick() % 2)};
        // Every fifth call near the end of the cursor's table of jumps (1024
        // draws), so that draws on both sides of it are checked.
        const int index = int(pick() % 6);
        const int dim = call % 5 == 0 ? 1010 + int(pick() % 20) : int(pick() % 40);
        sampler.startPixelSample(p, index, dim);
        Pcg32 plain(hashValues(p.x, p.y, seed), 0);
        plain.advance(int64_t(index) * IndependentSampler::kStreamStride + dim);
        const int draws = 1 + int(pick() % 4);
        for (int k = 0; k < draws; ++k)
            ASSERT_EQ(sampler.get1D(), plain.nextFloat()) << "call " << call << " draw " << k;
    }
}

TEST(SamplerValues, CachedPositioningMatchesAFreshSampler) {
    // Samplers remember the last pixel sample to restart cheaply at the next
    // vertex (the global Sobol' samplers the last 8 of a pixel, by index mod 8);
    // whatever order requests come in, each value must equal what a fresh
    // sampler gives for the same (pixel, index, dimension). Indices run over
    // all 16 samples, so cached ones are also evicted and reused.
    for (const std::string& name : allSamplerNames()) {
        const AnySampler prototype = makeSampler(name, SamplerConfig{16, 5, {8, 8}});
        AnySampler used = prototype;
        std::mt19937 pick(9);
        for (int call = 0; call < 600; ++call) {
            const Vec2i p{int(pick() % 3), int(pick() % 2)};
            const int index = int(pick() % 16), dim = 2 + int(pick() % 40);
            AnySampler fresh = prototype;
            std::visit(
                [&](auto& s) {
                    auto& f = std::get<std::decay_t<decltype(s)>>(fresh);
                    s.startPixelSample(p, index, dim);
                    f.startPixelSample(p, index, dim);
                    const int draws = 1 + int(pick() % 3);
                    for (int k = 0; k < draws; ++k) ASSERT_EQ(s.get1D(), f.get1D()) << name;
                    const Vec2f a = s.get2D(), b = f.get2D();
                    ASSERT_EQ(a.x, b.x) << name;
                    ASSERT_EQ(a.y, b.y) << name;
                },
                used);
        }
    }
}

TEST(SamplerValues, PrecomputedJumpEqualsStepping) {
    Pcg32 stepped(5, 0), jumped(5, 0);
    for (int k = 0; k < 1000; ++k) stepped.nextUInt();
    jumped.advance(Pcg32::jump(1000));
    EXPECT_EQ(stepped.nextUInt(), jumped.nextUInt());
}

// Records the (sample index, dimension) of every value drawn.
struct RecordingSampler {
    std::vector<std::pair<int, int>> drawn;
    int index = 0, dimension = 0;
    int samplesPerPixel() const { return 16; }
    void startPixelSample(Vec2i, int i, int d) { index = i, dimension = d; }
    float get1D() {
        drawn.push_back({index, dimension++});
        return 0;
    }
    Vec2f get2D() {
        get1D(), get1D();
        return {};
    }
    Vec2f getPixel2D() { return get2D(); }
};

TEST(SamplerCost, DrawsTheDimensionsOfACornellBoxBatch) {
    // The sampler microbenchmark draws what the integrator draws at a diffuse
    // vertex with one light: the pixel (0, 1), then per vertex the light point
    // (+1, +2), the BSDF direction (+4, +5) and roulette (+6) from vertex 2 on.
    RecordingSampler s;
    // Three groups of lanes: 8 + 8 + 3 paths.
    const int depth = 4, first = 64, count = 19;
    static_assert(count <= kBatchSamples);
    drawBatchDimensions(s, {5, 6}, first, count, depth);
    std::multiset<std::pair<int, int>> expected;
    for (int k = 0; k < count; ++k) {
        expected.insert({first + k, 0}), expected.insert({first + k, 1});
        for (int d = 0; d < depth; ++d)
            for (int offset : {1, 2, 4, 5, 6})
                if (offset != 6 || d >= 2)
                    expected.insert({first + k, dims::bounceBase(d) + offset});
    }
    const std::multiset<std::pair<int, int>> drawn(s.drawn.begin(), s.drawn.end());
    EXPECT_EQ(drawn, expected);
    EXPECT_EQ(s.drawn.size(), size_t(count * dimensionsPerPath(depth)));
    // The camera samples of the whole batch come first, as in the renderer.
    for (int k = 0; k < 2 * count; ++k) EXPECT_LT(s.drawn[size_t(k)].second, 2);
    // Then depth by depth over the batch's paths, as estimateRadianceBatch
    // traces them, and within a depth a group of kCameraPacketSamples paths
    // after another.
    for (size_t i = size_t(2 * count) + 1; i < s.drawn.size(); ++i) {
        const int depthBefore = dims::depthOfDimension(s.drawn[i - 1].second);
        const int depthNow = dims::depthOfDimension(s.drawn[i].second);
        EXPECT_LE(depthBefore, depthNow) << "draw " << i;
        if (depthBefore != depthNow) continue;
        EXPECT_LE((s.drawn[i - 1].first - first) / kCameraPacketSamples,
                  (s.drawn[i].first - first) / kCameraPacketSamples)
            << "draw " << i;
    }
}

// drawLanes1D/2D of `lanes` against startPixelSample + get1D/get2D of
// `single`, a second copy of the sampler, lane by lane, bit for bit.
template <typename S>
void expectLanesEqualEachDraw(S& lanes, S& single, Vec2i pixel, const int* indices, int count,
                              int dim, const std::string& name) {
    float x[kCameraPacketSamples];
    Vec2f xy[kCameraPacketSamples];
    drawLanes1D(lanes, pixel, indices, count, dim, x);
    drawLanes2D(lanes, pixel, indices, count, dim, xy);
    for (int j = 0; j < count; ++j) {
        single.startPixelSample(pixel, indices[j], dim);
        EXPECT_EQ(x[j], single.get1D()) << name << " dim " << dim;
        single.startPixelSample(pixel, indices[j], dim);
        const Vec2f expected = single.get2D();
        EXPECT_EQ(xy[j].x, expected.x) << name << " dim " << dim;
        EXPECT_EQ(xy[j].y, expected.y) << name << " dim " << dim;
    }
}

// drawPixelLanes (the camera rays' positions in the pixel) of `lanes` against
// startPixelSample at dimension 0 + getPixel2D of `single`, bit for bit.
template <typename S>
void expectPixelLanesEqualEachDraw(S& lanes, S& single, Vec2i pixel, const int* indices, int count,
                                   const std::string& name) {
    Vec2f xy[kCameraPacketSamples];
    drawPixelLanes(lanes, pixel, indices, count, xy);
    for (int j = 0; j < count; ++j) {
        single.startPixelSample(pixel, indices[j], dims::kPixel);
        const Vec2f expected = single.getPixel2D();
        EXPECT_EQ(xy[j].x, expected.x) << name << " pixel lane " << j;
        EXPECT_EQ(xy[j].y, expected.y) << name << " pixel lane " << j;
    }
}

TEST(SamplerValues, LaneDrawsEqualPerSampleDraws) {
    // drawLanes1D/2D, which the batched integrator uses, against
    // startPixelSample + get1D/get2D of a second copy of the sampler: live
    // lanes of a camera packet (ascending subsets of its samples), pixels
    // revisited, dimensions past the per-pixel caches, spp not a power of two.
    for (const std::string& name : allSamplerNames()) {
        // stratified tabulates its permutations up to 1024 spp.
        const std::vector<int> spps =
            name == "stratified" ? std::vector<int>{64, 24, 2048} : std::vector<int>{64, 24};
        for (int spp : spps) {
            const SamplerConfig config{spp, 7, {32, 16}};
            AnySampler lanes = makeSampler(name, config), single = makeSampler(name, config);
            std::mt19937 rng(spp);
            std::visit(
                [&](auto& a) {
                    auto& b = std::get<std::decay_t<decltype(a)>>(single);
                    for (int round = 0; round < 300; ++round) {
                        const Vec2i pixel{int(rng() % 3), int(rng() % 2) + 5};
                        const int first = int(rng() % unsigned(spp / 8)) * 8;
                        int indices[kCameraPacketSamples], count = 0;
                        for (int k = 0; k < kCameraPacketSamples; ++k)
                            if (rng() % 4 != 0) indices[count++] = first + k;
                        const int depth = int(rng() % 10);
                        const int dim = dims::bounceBase(depth) + int(rng() % 7);
                        expectLanesEqualEachDraw(a, b, pixel, indices, count, dim, name);
                        // The pixel dimensions anywhere in the image: the
                        // Halton samplers' depend on the pixel's residues.
                        const Vec2i anywhere{int(rng() % 32), int(rng() % 16)};
                        expectPixelLanesEqualEachDraw(a, b, anywhere, indices, count, name);
                    }
                },
                lanes);
        }
    }
}

TEST(SamplerValues, LaneDrawsLeavePerSampleDrawsIntact) {
    // One sampler drawing lanes and single samples in turn, as the batched
    // integrator does (lane draws for a group's Lambertian vertices, single
    // draws for the others, of the same samples): every value still equals a
    // fresh draw. Single draws often continue the sample a lane draw began
    // or ended with, a dimension further on, where samplers that keep a
    // per-sample position step on from it instead of starting over.
    for (const std::string& name : allSamplerNames()) {
        const SamplerConfig config{64, 3, {32, 16}};
        AnySampler mixed = makeSampler(name, config), fresh = makeSampler(name, config);
        std::mt19937 rng(11);
        std::visit(
            [&](auto& a) {
                auto& b = std::get<std::decay_t<decltype(a)>>(fresh);
                auto expected = [&](Vec2i p, int index, int dim) {
                    b.startPixelSample(p, index, dim);
                    return b.get2D();
                };
                auto same = [](Vec2f u, Vec2f v) { return u.x == v.x && u.y == v.y; };
                for (int round = 0; round < 400; ++round) {
                    const Vec2i pixel{int(rng() % 2), 4};
                    int indices[kCameraPacketSamples], count = 0;
                    const int first = int(rng() % 8) * 8;
                    for (int k = 0; k < kCameraPacketSamples; ++k)
                        if (rng() % 3 != 0) indices[count++] = first + k;
                    if (count == 0) continue;
                    const int dim = dims::bounceBase(int(rng() % 6)) + 1;
                    Vec2f lanes[kCameraPacketSamples];
                    drawLanes2D(a, pixel, indices, count, dim, lanes);
                    for (int j = 0; j < count; ++j)
                        ASSERT_TRUE(same(lanes[j], expected(pixel, indices[j], dim))) << name;
                    // The first or last lane's sample, or another, further on.
                    const int pick = int(rng() % 3);
                    const int index = pick == 0   ? indices[0]
                                      : pick == 1 ? indices[count - 1]
                                                  : int(rng() % 64);
                    const int later = dim + 2 + int(rng() % 3);
                    a.startPixelSample(pixel, index, later);
                    const Vec2f u = a.get2D(), v = a.get2D();
                    ASSERT_TRUE(same(u, expected(pixel, index, later)))
                        << name << " round " << round;
                    ASSERT_TRUE(same(v, expected(pixel, index, later + 2)))
                        << name << " round " << round;
                }
            },
            mixed);
    }
}

TEST(SamplerValues, LaneDrawsAtTheirLimits) {
    // The lane draws' edges: one and two live lanes (drawn lane by lane),
    // dimensions on both sides of the Halton tables' end (128), and Halton
    // indices on both sides of 2^32 — in a 65536 × 59049 image the stride
    // between a pixel's samples is 2^16 · 3^10 ≈ 3.9 · 10^9, so from sample 1
    // on every index is past 2^32, where the Halton lanes hand over to the
    // scalar loops.
    for (const char* name :
         {"halton", "halton-rd", "halton-owen", "sobol-owen", "zsobol", "stratified"}) {
        // Images one pixel wide or tall: no image-scale digits in that base.
        for (Vec2i resolution :
             {Vec2i{32, 16}, Vec2i{65536, 59049}, Vec2i{32, 1}, Vec2i{1, 16}, Vec2i{1, 1}}) {
            const SamplerConfig config{64, 11, resolution};
            AnySampler lanes = makeSampler(name, config), single = makeSampler(name, config);
            std::visit(
                [&](auto& a) {
                    auto& b = std::get<std::decay_t<decltype(a)>>(single);
                    for (int count = 1; count <= kCameraPacketSamples; ++count) {
                        int indices[kCameraPacketSamples];
                        for (int k = 0; k < count; ++k) indices[k] = k * 3 % 8;
                        for (int dim : {2, 61, 125, 126, 127, 128, 131}) {
                            const Vec2i pixel{count, 3};
                            expectLanesEqualEachDraw(a, b, pixel, indices, count, dim, name);
                        }
                        expectPixelLanesEqualEachDraw(a, b, Vec2i{count, 3}, indices, count, name);
                    }
                },
                lanes);
        }
    }
}

}  // namespace
}  // namespace pathlab
