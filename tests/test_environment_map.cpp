// Image environment maps: the equal-area octahedral mapping (round trip,
// equal areas), the piecewise-constant distribution and the map's direction
// sampling against their densities (chi-square), the pbrt-v4 reader, and
// importance sampling paying off on a map with a small bright sun.
#include <gtest/gtest.h>

#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>

#include "chi_square.h"
#include "core/equal_area.h"
#include "core/image.h"
#include "core/rng.h"
#include "render/environment_light.h"
#include "render/lights.h"
#include "render/renderer.h"
#include "scene/json_scene.h"
#include "scene/pbrt/importer.h"
#include "scene_test_util.h"

namespace pathlab {
namespace {

TEST(EqualAreaMapping, RoundTripsAndGivesUnitVectors) {
    const int n = 101;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const Vec2f p{(float(i) + 0.5f) / n, (float(j) + 0.5f) / n};
            const Vec3f w = equalAreaSquareToSphere(p);
            ASSERT_NEAR(length(w), 1.0f, 1e-5f);
            const Vec2f q = equalAreaSphereToSquare(w);
            ASSERT_NEAR(q.x, p.x, 2e-5f) << p.x << " " << p.y;
            ASSERT_NEAR(q.y, p.y, 2e-5f) << p.x << " " << p.y;
        }
    // The centre is the pole +z, the corners the pole −z.
    EXPECT_NEAR(equalAreaSquareToSphere({0.5f, 0.5f}).z, 1.0f, 1e-6f);
    EXPECT_NEAR(equalAreaSquareToSphere({0, 0}).z, -1.0f, 1e-6f);
    EXPECT_NEAR(equalAreaSquareToSphere({1, 1}).z, -1.0f, 1e-6f);
}

// Uniform points of the square land uniformly on the sphere: the mapping
// preserves area (chi-square against the uniform density 1/4π).
TEST(EqualAreaMapping, PreservesArea) {
    Pcg32 rng(5, 0);
    const auto result = testing::chiSquareTest(
        [&](int) -> std::optional<Vec3f> {
            const float u = rng.nextFloat();
            return equalAreaSquareToSphere({u, rng.nextFloat()});
        },
        [](Vec3f) { return 1 / (4 * M_PI); }, 400000);
    EXPECT_GT(result.pValue, 0.01) << result.detail;
}

// A 16×16 map: a sky brighter towards light-space +z and a 2×2 sun of
// `sun` times the sky's radiance.
EnvironmentImage skyWithSun(float sun, int size = 16) {
    EnvironmentImage env;
    env.width = env.height = size;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const Vec3f w =
                equalAreaSquareToSphere({(float(x) + 0.5f) / size, (float(y) + 0.5f) / size});
            Vec3f L = Vec3f(0.3f, 0.4f, 0.6f) * (1.2f + w.z);
            if (x >= size / 4 && x < size / 4 + 2 && y >= size / 3 && y < size / 3 + 2)
                L = Vec3f(1, 0.9f, 0.7f) * sun;
            env.texels.push_back(L);
        }
    return env;
}

// The texel a direction falls in, in the map's own frame.
int texelOf(const EnvironmentImage& env, Vec3f w) {
    const Vec2f uv = equalAreaSphereToSquare(w);
    const int x = std::clamp(int(uv.x * float(env.width)), 0, env.width - 1);
    const int y = std::clamp(int(uv.y * float(env.height)), 0, env.height - 1);
    return y * env.width + x;
}

// Every texel subtends the same solid angle, so texel i must be drawn with
// probability Y_i / ΣY exactly: chi-square over the texels, with a sun of
// 200 times the sky.
TEST(EnvironmentLight, ChoosesTexelsInProportionToLuminance) {
    const EnvironmentImage env = skyWithSun(200);
    const EnvironmentLight light(env);
    double total = 0;
    for (const Vec3f& t : env.texels) total += luminance(t);
    const int samples = 500000;
    std::vector<double> observed(env.texels.size(), 0.0);
    Pcg32 rng(9, 0);
    for (int s = 0; s < samples; ++s) {
        const float u = rng.nextFloat();
        const auto ls = light.sample({u, rng.nextFloat()});
        ASSERT_TRUE(ls);
        observed[size_t(texelOf(env, ls->wi))] += 1;
        // The reported density is the texel's share over its solid angle.
        const double share = luminance(env.texels[size_t(texelOf(env, ls->wi))]) / total;
        ASSERT_NEAR(ls->pdf, share * double(env.texels.size()) / (4 * M_PI), 1e-3 * ls->pdf);
    }
    double chi2 = 0;
    for (size_t i = 0; i < observed.size(); ++i) {
        const double expected = luminance(env.texels[i]) / total * samples;
        chi2 += (observed[i] - expected) * (observed[i] - expected) / expected;
    }
    const boost::math::chi_squared dist(double(observed.size() - 1));
    EXPECT_GT(1 - boost::math::cdf(dist, chi2), 0.01) << chi2;
}

// The sampled directions follow pdf(w) over the sphere (a milder sun, so
// that the numerical integral of the piecewise-constant density per bin is
// accurate), in a rotated light frame.
TEST(EnvironmentLight, SampledDirectionsFollowPdf) {
    EnvironmentImage env = skyWithSun(6);
    // Light +z towards world +y: the frame (x, y, z) → (x, z, −y)... as columns.
    env.toWorld[0] = {1, 0, 0}, env.toWorld[1] = {0, 0, -1}, env.toWorld[2] = {0, 1, 0};
    env.toLight[0] = {1, 0, 0}, env.toLight[1] = {0, 0, 1}, env.toLight[2] = {0, -1, 0};
    const EnvironmentLight light(env);
    Pcg32 rng(13, 0);
    const auto result = testing::chiSquareTest(
        [&](int) -> std::optional<Vec3f> {
            const float u = rng.nextFloat();
            const auto s = light.sample({u, rng.nextFloat()});
            if (!s) return std::nullopt;
            return s->wi;
        },
        [&](Vec3f w) { return double(light.pdf(w)); }, 300000, 16, 32, 100);
    EXPECT_GT(result.pValue, 0.01) << result.detail;
    // The sun's texels face world +y's side: radiance and pdf agree on it.
    Pcg32 rng2(17, 0);
    for (int s = 0; s < 1000; ++s) {
        const float u = rng2.nextFloat();
        const auto ls = light.sample({u, rng2.nextFloat()});
        ASSERT_TRUE(ls);
        EXPECT_EQ(light.radiance(ls->wi).x, ls->radiance.x);
        EXPECT_NEAR(light.pdf(ls->wi), ls->pdf, 1e-4f * ls->pdf);
    }
}

// A diffuse sphere on a floor under the sky with a small sun: at 16 spp,
// importance sampling the map must beat uniform sphere sampling of it by 10×
// in MSE against a reference rendered with importance sampling.
SceneDescription sunScene(bool uniform) {
    SceneDescription s;
    s.materials.push_back(Material{"grey", MaterialType::Diffuse, Vec3f(0.6f)});
    Mesh floor;
    floor.positions = {{-5, 0, -5}, {-5, 0, 5}, {5, 0, 5}, {5, 0, -5}};
    floor.indices = {0, 1, 2, 0, 2, 3};
    s.meshes.push_back(floor);
    s.spheres.push_back(Sphere{{0, 1, 0}, 1, 0});
    EnvironmentImage env = skyWithSun(3000, 32);  // the sun: 4 of 1024 texels
    env.toWorld[0] = {1, 0, 0}, env.toWorld[1] = {0, 0, -1}, env.toWorld[2] = {0, 1, 0};
    env.toLight[0] = {1, 0, 0}, env.toLight[1] = {0, 0, 1}, env.toLight[2] = {0, -1, 0};
    env.uniformSampling = uniform;
    s.environmentMap = env;
    s.camera = Camera{{0, 2, 5}, {0, 0.7f, 0}, {0, 1, 0}, 45};
    s.resolution = {16, 12};
    return s;
}

double mse(const Image& a, const Image& b) {
    double sum = 0;
    for (size_t i = 0; i < a.rgb.size(); ++i)
        sum += double(a.rgb[i] - b.rgb[i]) * (a.rgb[i] - b.rgb[i]);
    return sum / double(a.rgb.size());
}

TEST(EnvironmentLight, ImportanceSamplingBeatsUniformTenfold) {
    RenderSettings settings;
    settings.maxDepth = 3;
    settings.threads = 2;
    settings.samplesPerPixel = 2048;
    const Image reference = render(RenderScene(sunScene(false)), settings).image;
    settings.samplesPerPixel = 16;
    settings.seed = 7;
    const Image importance = render(RenderScene(sunScene(false)), settings).image;
    const Image uniform = render(RenderScene(sunScene(true)), settings).image;
    const double a = mse(importance, reference), b = mse(uniform, reference);
    EXPECT_GT(b, 10 * a) << "importance " << a << ", uniform " << b;
    // Both estimate the same image: their means agree with the reference's.
    double mr = 0, mi = 0;
    for (size_t i = 0; i < reference.rgb.size(); ++i)
        mr += reference.rgb[i], mi += importance.rgb[i];
    EXPECT_NEAR(mi / mr, 1.0, 0.05);
}

TEST(EnvironmentLightPbrt, ReadsTheMapInTheLightsFrame) {
    test::ScratchDir dir;
    Image img(4, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) img.set(x, y, Vec3f(float(x), float(y), 1));
    writeImage((dir.path() / "sky.exr").string(), img);
    writeImage((dir.path() / "wide.exr").string(), Image(4, 2));
    const auto load = [&](const std::string& light) {
        return pbrt::importPbrtText("WorldBegin\n" + light + "\nShape \"sphere\"\n",
                                    (dir.path() / "t.pbrt").string(), dir.path().string());
    };
    const auto r = load(
        "Rotate -90 1 0 0\nLightSource \"infinite\" \"string filename\" "
        "\"sky.exr\" \"float scale\" 2");
    const EnvironmentImage& env = r.scene.environmentMap;
    ASSERT_EQ(env.width, 4);
    EXPECT_EQ(env.texels[size_t(2 * 4 + 3)].x, 6.0f);  // texel (3, 2), scaled by 2
    EXPECT_EQ(env.texels[size_t(2 * 4 + 3)].y, 4.0f);
    // Rotate −90° about x takes light +z to world +y.
    EXPECT_NEAR(env.toWorld[2].y, 1.0f, 1e-6f);
    EXPECT_NEAR(env.toLight[1].z, 1.0f, 1e-6f);  // world +y back to light +z
    const std::string file = (dir.path() / "t.pbrt").string();
    EXPECT_EQ(test::inputErrorOf(
                  [&] { load("LightSource \"infinite\" \"string filename\" \"wide.exr\""); }),
              file +
                  ":2:1: LightSource \"infinite\": 'wide.exr' is 4x2, not square: not an "
                  "equal-area octahedral map");
    EXPECT_EQ(
        test::inputErrorOf([&] {
            load("LightSource \"infinite\" \"string filename\" \"sky.exr\" \"rgb L\" [1 1 1]");
        }),
        file + ":2:1: LightSource \"infinite\": give either L or filename, not both");
    EXPECT_EQ(test::inputErrorOf([&] {
                  load(
                      "LightSource \"infinite\" \"string filename\" \"sky.exr\" \"point3 portal\" "
                      "[0 0 0 1 0 0 1 1 0 0 1 0]");
              }),
              file +
                  ":2:1: infinite light portals is not supported (--lenient substitutes no "
                  "portal)");
}

TEST(EnvironmentLightJson, ReadsTheMapAndItsSampling) {
    test::ScratchDir dir;
    Image img(2, 2);
    img.set(1, 0, Vec3f(4, 5, 6));
    writeImage((dir.path() / "sky.pfm").string(), img);
    const std::string head = R"({"camera": {"eye": [0, 1, 5], "target": [0, 1, 0], "fovY": 40},
      "materials": {"m": {"type": "diffuse"}},
      "spheres": [{"center": [0, 0, 0], "radius": 1, "material": "m"}], "environmentMap": )";
    const SceneDescription s = parseJsonScene(
        head + R"({"file": "sky.pfm", "scale": 2, "sampling": "uniform"}})", dir.path(), "s.json");
    ASSERT_EQ(s.environmentMap.width, 2);
    EXPECT_EQ(s.environmentMap.texels[1].z, 12.0f);
    EXPECT_TRUE(s.environmentMap.uniformSampling);
    EXPECT_EQ(
        test::inputErrorOf([&] {
            parseJsonScene(head + R"({"file": "sky.pfm", "sampling": "cosine"}})", dir.path(),
                           "s.json");
        }),
        "s.json: environmentMap.sampling: must be \"luminance\" or \"uniform\", got 'cosine'");
}

}  // namespace
}  // namespace pathlab
