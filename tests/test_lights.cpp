// Light sampling: the directions LightSet::sample produces follow the density
// it reports (chi-square), parallelogram detection, and power-proportional choice.
#include <gtest/gtest.h>

#include "chi_square.h"
#include "core/rng.h"
#include "render/lights.h"
#include "render/sampling_routines.h"

namespace pathlab {
namespace {

Mesh quad(Vec3f a, Vec3f b, Vec3f c, Vec3f d, Vec3f emission) {
    Mesh m;
    m.positions = {a, b, c, d};
    m.indices = {0, 1, 2, 0, 2, 3};
    m.emission = emission;
    return m;
}

Mesh triangle(Vec3f a, Vec3f b, Vec3f c, Vec3f emission) {
    Mesh m;
    m.positions = {a, b, c};
    m.indices = {0, 1, 2};
    m.emission = emission;
    return m;
}

// Distance along o + t·w to light l, or a negative value when it misses.
float hitLight(const AreaLight& l, Vec3f o, Vec3f w) {
    const float denom = dot(l.n, w);
    if (denom == 0) return -1;
    const float t = dot(l.p0 - o, l.n) / denom;
    if (t <= 0) return -1;
    const Vec3f q = o + w * t - l.p0;
    // Solve q = a·e1 + b·e2 in the light's plane.
    const float e11 = dot(l.e1, l.e1), e12 = dot(l.e1, l.e2), e22 = dot(l.e2, l.e2);
    const float q1 = dot(q, l.e1), q2 = dot(q, l.e2);
    const float det = e11 * e22 - e12 * e12;
    const float a = (q1 * e22 - q2 * e12) / det, b = (q2 * e11 - q1 * e12) / det;
    const bool inside = l.parallelogram ? (a >= 0 && a <= 1 && b >= 0 && b <= 1)
                                        : (a >= 0 && b >= 0 && a + b <= 1);
    return inside ? t : -1;
}

SceneDescription twoLightsAndSky() {
    SceneDescription s;
    // A downward-facing square key light above, a small triangle fill light to the side.
    s.meshes.push_back(quad({-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1}, Vec3f(5.0f)));
    s.meshes.push_back(triangle({3, 0, -0.5f}, {3, 0, 0.5f}, {3, 1, 0.5f}, Vec3f(20, 10, 5)));
    s.environment = Vec3f(0.02f);
    return s;
}

TEST(LightSet, MergesTrianglePairsIntoParallelograms) {
    const LightSet lights(twoLightsAndSky(), Vec3f(0.0f));
    ASSERT_EQ(lights.areaLightCount(), 2u);
    EXPECT_TRUE(lights.areaLight(0).parallelogram);
    EXPECT_FLOAT_EQ(lights.areaLight(0).area, 4.0f);
    EXPECT_FALSE(lights.areaLight(1).parallelogram);
    EXPECT_FLOAT_EQ(lights.areaLight(1).area, 0.5f);
    EXPECT_EQ(lights.lightOfTriangle(0, 0), 0);
    EXPECT_EQ(lights.lightOfTriangle(0, 1), 0);
    EXPECT_EQ(lights.lightOfTriangle(1, 0), 1);
    // The quad's vertices wind so that (p1−p0)×(p2−p0) points down.
    EXPECT_LT(lights.areaLight(0).n.y, -0.99f);
}

TEST(LightSet, SampledDirectionsFollowReportedPdf) {
    const LightSet lights(twoLightsAndSky(), Vec3f(0.0f));
    const Vec3f ref{0.2f, 0.1f, 0.3f};
    Pcg32 rng(21, 0);
    const auto result = testing::chiSquareTest(
        [&](int) -> std::optional<Vec3f> {
            const float uc = rng.nextFloat();
            const float u0 = rng.nextFloat();
            const auto s = lights.sample(ref, uc, {u0, rng.nextFloat()});
            if (!s) return std::nullopt;
            return s->wi;
        },
        [&](Vec3f w) {
            double pdf = lights.pdfEnvironment();
            for (int l = 0; l < int(lights.areaLightCount()); ++l) {
                const AreaLight& light = lights.areaLight(l);
                const float t = hitLight(light, ref, w);
                if (t > 0 && !isBlack(light.emitted(-w)))
                    pdf += lights.pdfAreaLight(l, ref, ref + w * t);
            }
            return pdf;
        },
        1000000, 16, 32, 160);
    EXPECT_GT(result.pValue, 0.01) << result.detail;
}

TEST(LightSet, ChoosesLightsInProportionToPower) {
    SceneDescription s;
    s.meshes.push_back(quad({-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1}, Vec3f(1.0f)));
    s.meshes.push_back(quad({-1, 3, -1}, {1, 3, -1}, {1, 3, 1}, {-1, 3, 1}, Vec3f(3.0f)));
    const LightSet lights(s, Vec3f(0.0f));
    const Vec3f ref{0, 0, 0};
    // Both lights subtend the whole sampled area; compare choice via the pdf.
    const float pdf0 = lights.pdfAreaLight(0, ref, {0, 2, 0}) * 4.0f / 4.0f;
    const float pdf1 = lights.pdfAreaLight(1, ref, {0, 3, 0}) * 4.0f / 9.0f;
    EXPECT_NEAR(pdf1 / pdf0, 3.0f, 1e-4f);
    int first = 0;
    for (int i = 0; i < 1000; ++i)
        if (auto ls = lights.sample(ref, (i + 0.5f) / 1000, {0.5f, 0.5f}); ls && ls->distance < 2.5f)
            ++first;
    EXPECT_EQ(first, 250);
}

}  // namespace
}  // namespace pathlab

namespace pathlab {
namespace {

// The environment is chosen with the share of irradiance it gives the focus
// point: a 2×2 light of radiance 1 straight above at distance 2 gives ≈ 1·4/4 = 1,
// an environment of radiance 1/π gives π·(1/π) = 1, so each gets half.
TEST(LightSet, EnvironmentShareFollowsIrradianceAtFocus) {
    SceneDescription s;
    s.meshes.push_back(quad({-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1}, Vec3f(1.0f)));
    s.environment = Vec3f(1.0f / kPi);
    const LightSet lights(s, Vec3f(0.0f));
    EXPECT_NEAR(lights.pdfEnvironment() / uniformSpherePdf(), 0.5f, 1e-5f);
}

}  // namespace
}  // namespace pathlab
