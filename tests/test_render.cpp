// The renderer end to end on scenes whose answer is known: the white furnace,
// the max-depth convention, the NaN guard, and thread-count independence.
#include <gtest/gtest.h>

#include <cstring>

#include "core/error.h"
#include "core/float_mode.h"
#include "render/renderer.h"
#include "sampling/registry.h"
#include "scene/builtin_scenes.h"
#include "scene_test_util.h"

namespace pathlab {
namespace {

struct ImageMean {
    double mean, standardError;
};

// Mean of all channels and its standard error from the per-pixel variance.
ImageMean meanOf(const RenderOutput& out) {
    double sum = 0, var = 0;
    const size_t n = out.image.rgb.size();
    for (size_t i = 0; i < n; ++i) sum += out.image.rgb[i], var += out.varianceOfMean.rgb[i];
    return {sum / double(n), std::sqrt(var) / double(n)};
}

TEST(WhiteFurnace, RadianceIsEmissionOverOneMinusAlbedo) {
    const float a = 0.5f, Le = 1.0f;
    const RenderScene scene(furnaceCube(a, Le));
    for (const SamplerInfo& info : samplerInfos()) {
        RenderSettings s;
        s.sampler = info.name;
        s.samplesPerPixel = 64;
        s.maxDepth = 200;
        const ImageMean m = meanOf(render(scene, s));
        // Each channel's per-pixel noise is correlated across channels (grey
        // scene), so allow 5 standard errors plus float round-off.
        EXPECT_NEAR(m.mean, Le / (1 - a), 5 * m.standardError * std::sqrt(3.0) + 1e-3) << info.name;
    }
}

TEST(MaxDepth, CountsLikePbrt) {
    // Without roulette the furnace's radiance after D bounces is Le·(1 − a^{D+1})/(1 − a).
    const float a = 0.6f;
    const RenderScene scene(furnaceCube(a, 1.0f));
    for (int depth : {0, 1, 2, 5}) {
        RenderSettings s;
        s.samplesPerPixel = 32;
        s.maxDepth = depth;
        s.russianRoulette = false;
        const ImageMean m = meanOf(render(scene, s));
        const double expected = (1 - std::pow(a, depth + 1)) / (1 - a);
        EXPECT_NEAR(m.mean, expected, 5 * m.standardError * std::sqrt(3.0) + 1e-4)
            << "max depth " << depth;
    }
}

TEST(RouletteDepth, EndsPathsOnlyAfterItsBouncesAndStaysUnbiased) {
    // Furnace with max depth 5: a path continues from vertices 0…4. Roulette
    // from vertex D may end it only there, so the later it starts the more
    // rays are traced; from vertex 5 on it never fires, which must be the
    // render without roulette bit for bit. Every start depth stays unbiased.
    const float a = 0.6f;
    const int maxDepth = 5;
    const RenderScene scene(furnaceCube(a, 1.0f));
    RenderSettings s;
    s.samplesPerPixel = 32;
    s.maxDepth = maxDepth;
    s.russianRoulette = false;
    const RenderOutput none = render(scene, s);
    s.russianRoulette = true;
    uint64_t previousRays = 0;
    for (int start : {0, 2, 4}) {
        s.rouletteDepth = start;
        const RenderOutput out = render(scene, s);
        EXPECT_GT(out.stats.rays, previousRays) << "roulette depth " << start;
        EXPECT_LT(out.stats.rays, none.stats.rays) << "roulette depth " << start;
        previousRays = out.stats.rays;
        const ImageMean m = meanOf(out);
        const double expected = (1 - std::pow(a, maxDepth + 1)) / (1 - a);
        EXPECT_NEAR(m.mean, expected, 5 * m.standardError * std::sqrt(3.0) + 1e-4)
            << "roulette depth " << start;
    }
    s.rouletteDepth = maxDepth;
    EXPECT_EQ(render(scene, s).image.rgb, none.image.rgb);
    s.rouletteDepth = -1;
    EXPECT_THROW(render(scene, s), InputError);
}

TEST(NonFiniteGuard, NaNSamplesNeverReachTheImage) {
    SceneDescription desc = furnaceCube(0.5f, 1.0f);
    desc.materials[0].albedo = Vec3f(std::nanf(""));
    const RenderScene scene(desc);
    RenderSettings s;
    s.samplesPerPixel = 4;
    const RenderOutput out = render(scene, s);
    EXPECT_GT(out.stats.nonFinite, 0u);
    for (float v : out.image.rgb) ASSERT_TRUE(std::isfinite(v));
}

TEST(Determinism, IdenticalBytesForAnyThreadCount) {
    SceneDescription desc = furnaceCube(0.7f, 1.0f);
    desc.resolution = {37, 29};  // tiles of unequal size
    const RenderScene scene(desc);
    for (const char* sampler : {"independent", "standard"}) {
        std::vector<float> first;
        for (int threads : {1, 2, 8}) {
            RenderSettings s;
            s.sampler = sampler;
            s.samplesPerPixel = 8;
            s.threads = threads;
            s.seed = 42;
            const RenderOutput out = render(scene, s);
            if (first.empty()) {
                first = out.image.rgb;
                continue;
            }
            ASSERT_EQ(0,
                      std::memcmp(first.data(), out.image.rgb.data(), first.size() * sizeof(float)))
                << sampler << " with " << threads << " threads";
        }
    }
}

TEST(Seeds, DifferentSeedsGiveDifferentImages) {
    const RenderScene scene(furnaceCube(0.7f, 1.0f));
    RenderSettings s;
    s.samplesPerPixel = 2;
    const RenderOutput a = render(scene, s);
    s.seed = 1;
    const RenderOutput b = render(scene, s);
    EXPECT_NE(a.image.rgb, b.image.rgb);
}

// Inside the scope a denormal result is flushed to zero (and a denormal operand
// read as zero); after it the thread's previous mode is back.
TEST(FloatMode, ScopedFlushDenormalsFlushesAndRestores) {
    volatile float tiny = 1e-30f, scale = 1e-10f;  // product 1e-40: a denormal
    const float before = tiny * scale;
    EXPECT_GT(before, 0.0f);
    {
        const ScopedFlushDenormals denormals;
        EXPECT_EQ(tiny * scale, 0.0f);
        volatile float denormal = 1e-40f;
        EXPECT_EQ(denormal * 1.0f, 0.0f);
    }
    EXPECT_EQ(tiny * scale, before);
}

// A render sets the mode per tile: the same image whatever mode the caller
// runs in, and the caller's mode untouched afterwards.
TEST(FloatMode, RenderIgnoresAndRestoresTheCallersMode) {
    RenderScene scene(cornellBoxScene());
    RenderSettings s;
    s.sampler = "sobol-owen";
    s.samplesPerPixel = 4;
    s.resolution = {24, 24};
    s.threads = 1;
    const Image plain = render(scene, s).image;
    Image flushed;
    {
        const ScopedFlushDenormals denormals;
        flushed = render(scene, s).image;
    }
    EXPECT_EQ(0, std::memcmp(plain.rgb.data(), flushed.rgb.data(), plain.rgb.size() * 4));
    volatile float tiny = 1e-30f, scale = 1e-10f;
    EXPECT_GT(tiny * scale, 0.0f) << "the render left flush-to-zero on";
}

TEST(RenderSettingsValidation, RejectsOutOfRangeValues) {
    RenderSettings s;
    s.samplesPerPixel = 0;
    EXPECT_THROW(validateRenderSettings(s), InputError);
    s = {};
    s.resolution = {0, 5};
    EXPECT_THROW(validateRenderSettings(s), InputError);
    s = {};
    s.maxDepth = -1;
    EXPECT_THROW(validateRenderSettings(s), InputError);
    s = {};
    s.sampler = "no-such-sampler";
    EXPECT_THROW(validateRenderSettings(s), InputError);
}

// Two independent Cornell-box renders at 1024 and 4096 spp differ only by their
// noise: per pixel and channel z = (a − b)/√(σa² + σb²) has unit variance.
TEST(CornellBox, ConvergesToOneImage) {
    const RenderScene scene(cornellBoxScene());
    RenderSettings s;
    s.resolution = {40, 40};
    s.samplesPerPixel = 1024;
    s.seed = 1;
    const RenderOutput a = render(scene, s);
    s.samplesPerPixel = 4096;
    s.seed = 2;
    const RenderOutput b = render(scene, s);
    double sumZ2 = 0, meanLuminance = 0;
    int within3 = 0;
    const size_t n = a.image.rgb.size();
    for (size_t i = 0; i < n; ++i) {
        ASSERT_TRUE(std::isfinite(a.image.rgb[i]) && std::isfinite(b.image.rgb[i]));
        const double var = double(a.varianceOfMean.rgb[i]) + b.varianceOfMean.rgb[i];
        const double z = (a.image.rgb[i] - b.image.rgb[i]) / std::sqrt(std::max(var, 1e-12));
        sumZ2 += z * z;
        within3 += std::abs(z) < 3;
        meanLuminance += b.image.rgb[i] / double(n);
    }
    EXPECT_GT(meanLuminance, 0.05);  // not black
    EXPECT_NEAR(sumZ2 / double(n), 1.0, 0.2);
    EXPECT_GT(double(within3) / double(n), 0.98);
    // Classic look: the left wall is red, the right wall green.
    const Vec3f left = b.image.at(2, 20), right = b.image.at(37, 20);
    EXPECT_GT(left.x, 2 * left.y);
    EXPECT_GT(right.y, 2 * right.x);
}

// Direct lighting of a diffuse floor by a square light at height h straight
// above, in a scene whose far-away extra triangle makes the ray-offset epsilon
// large (601 · 2e-5 ≈ 0.012): the shadow ray must still reach the light, and
// must stop before it rather than hit it. Returns the mean radiance and the
// expected (albedo/π)·∫ Le cosθ cosθ' / r² dA, integrated numerically.
struct DirectLightingCheck {
    ImageMean measured;
    double expected;
};
DirectLightingCheck renderFloorUnderLight(float h) {
    SceneDescription s;
    s.materials.push_back(Material{"floor", MaterialType::Diffuse, Vec3f(0.5f)});
    Mesh floor;
    floor.positions = {{-10, 0, -10}, {-10, 0, 10}, {10, 0, 10}, {10, 0, -10}};
    floor.indices = {0, 1, 2, 0, 2, 3};
    Mesh light;
    const float Le = 10;
    light.positions = {{-0.5f, h, -0.5f}, {0.5f, h, -0.5f}, {0.5f, h, 0.5f}, {-0.5f, h, 0.5f}};
    light.indices = {0, 1, 2, 0, 2, 3};
    light.emission = Vec3f(Le);
    Mesh far;
    far.positions = {{600, 600, 600}, {601, 600, 600}, {600, 601, 600}};
    far.indices = {0, 1, 2};
    s.meshes = {floor, light, far};
    // Looking straight down from just under the light at the floor below it.
    s.camera = Camera{{0, 0.9f * h, 0.001f}, {0, 0, 0}, {0, 0, 1}, 0.5f};
    s.resolution = {8, 8};
    const RenderScene scene(s);
    RenderSettings settings;
    settings.samplesPerPixel = 256;
    settings.maxDepth = 1;
    const RenderOutput out = render(scene, settings);
    double irradiance = 0;
    const int n = 1000;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const double x = -0.5 + (i + 0.5) / n, z = -0.5 + (j + 0.5) / n;
            const double r2 = x * x + z * z + double(h) * h, cos = h / std::sqrt(r2);
            irradiance += Le * cos * cos / r2 / (double(n) * n);
        }
    return {meanOf(out), 0.5 / M_PI * irradiance};
}

TEST(DirectLighting, MatchesIrradianceIntegralInALargeScene) {
    const auto [m, expected] = renderFloorUnderLight(5);
    EXPECT_NEAR(m.mean, expected, 5 * m.standardError * std::sqrt(3.0) + 1e-3 * expected);
}

// The light 1 unit above the floor, about 80 ray offsets: a shadow ray cast
// along the light direction from the nudged origin runs parallel to the
// segment to the light point, ε off it, and crosses the light's plane up to
// ε/cosθ before the point — it hit the light it was aimed at, and the floor
// came out at 9% of its irradiance. Aimed at the light point itself, it stops
// short of it.
TEST(DirectLighting, ShadowRaysStopShortOfTheLightTheyAimAt) {
    const auto [m, expected] = renderFloorUnderLight(1.0f);
    EXPECT_NEAR(m.mean, expected, 5 * m.standardError * std::sqrt(3.0) + 2e-3 * expected);
}

}  // namespace
}  // namespace pathlab
