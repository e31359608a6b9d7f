// Light sampling: the directions LightSet::sample produces follow the density
// it reports (chi-square), that density integrates to one and agrees with
// pdfAreaLight, solid-angle sampling of rectangles beats area sampling,
// parallelogram detection, and power-proportional choice.
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
    const bool inside =
        l.parallelogram ? (a >= 0 && a <= 1 && b >= 0 && b <= 1) : (a >= 0 && b >= 0 && a + b <= 1);
    return inside ? t : -1;
}

// Solid angle of the square [−1,1]² at height h, seen from below its centre.
float solidAngleOfSquare(float h) {
    return 4 * std::atan(1 / (h * std::sqrt(2 + h * h)));
}

SceneDescription oneLight(Mesh light) {
    SceneDescription s;
    s.meshes.push_back(std::move(light));
    return s;
}

// A 1.5×0.8 rectangle, tilted and rotated out of every axis, facing roughly −y.
Mesh tiltedRectangle(bool twoSided = false) {
    const Vec3f c{0.3f, 1.2f, -0.2f};
    const Vec3f a = normalize(Vec3f(1, 0.3f, 0.2f));
    const Vec3f b = normalize(cross(a, Vec3f(0.1f, 1, -0.3f)));
    const Vec3f ex = a * 1.5f, ey = b * 0.8f;
    Mesh m = quad(c, c + ex, c + ex + ey, c + ey, Vec3f(3.0f));
    m.twoSided = twoSided;
    return m;
}

// Receivers at several distances and orientations, with and without a normal.
struct Receiver {
    Vec3f p, ns;
};
const Receiver kReceivers[] = {
    {{0.1f, 0.0f, 0.1f}, normalize(Vec3f(0.2f, 1, 0.1f))},   // below, facing up
    {{1.0f, 0.9f, 0.3f}, normalize(Vec3f(-1, 0.2f, 0.5f))},  // close and oblique
    {{0.9f, 1.05f, 0.1f}, normalize(Vec3f(0, 1, 0))},        // very close: a large solid angle
    {{-2.0f, -1.0f, 1.5f}, Vec3f(0.0f)},                     // no normal: no cosine warp
};

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
    const Vec3f ref{0.2f, 0.1f, 0.3f}, ns = normalize(Vec3f(0.3f, 1, 0.2f));
    Pcg32 rng(21, 0);
    const auto result = testing::chiSquareTest(
        [&](int) -> std::optional<Vec3f> {
            const float uc = rng.nextFloat();
            const float u0 = rng.nextFloat();
            const auto s = lights.sample(ref, ns, uc, {u0, rng.nextFloat()});
            if (!s) return std::nullopt;
            return s->wi;
        },
        [&](Vec3f w) {
            double pdf = lights.pdfEnvironment();
            for (int l = 0; l < int(lights.areaLightCount()); ++l) {
                const AreaLight& light = lights.areaLight(l);
                const float t = hitLight(light, ref, w);
                if (t > 0 && !isBlack(light.emitted(-w)))
                    pdf += lights.pdfAreaLight(l, ref, ns, ref + w * t);
            }
            return pdf;
        },
        1000000, 16, 32, 160);
    EXPECT_GT(result.pValue, 0.01) << result.detail;
}

// Chi-square for one light, at the Šidák level for `tests` tests. The bins are
// integrated finely (64² points): the pdf jumps at the light's silhouette.
void expectDirectionsFollowPdf(const LightSet& lights, Receiver r, uint64_t seed, int tests) {
    Pcg32 rng(seed, 0);
    const auto result = testing::chiSquareTest(
        [&](int) -> std::optional<Vec3f> {
            const float uc = rng.nextFloat(), u0 = rng.nextFloat();
            const auto s = lights.sample(r.p, r.ns, uc, {u0, rng.nextFloat()});
            if (!s) return std::nullopt;
            return s->wi;
        },
        [&](Vec3f w) -> double {
            const float t = hitLight(lights.areaLight(0), r.p, w);
            if (t <= 0 || isBlack(lights.areaLight(0).emitted(-w))) return 0;
            return lights.pdfAreaLight(0, r.p, r.ns, r.p + w * t);
        },
        500000, 32, 64, 64);
    EXPECT_GT(result.pValue, testing::sidakSignificance(0.01, tests))
        << result.detail << " receiver (" << r.p.x << "," << r.p.y << "," << r.p.z << ")";
}

TEST(LightSet, RectangleSamplingFollowsReportedPdf) {
    const LightSet lights(oneLight(tiltedRectangle()), Vec3f(0.0f), LightSampling::SolidAngle);
    ASSERT_TRUE(lights.areaLight(0).rectangle);
    int seed = 0;
    for (const Receiver& r : kReceivers) expectDirectionsFollowPdf(lights, r, ++seed, 6);
    // A two-sided light seen from behind; a parallelogram that is no rectangle
    // (sampled by area).
    const LightSet twoSided(oneLight(tiltedRectangle(true)), Vec3f(0.0f),
                            LightSampling::SolidAngle);
    expectDirectionsFollowPdf(twoSided, {{0.5f, 2.5f, 0.0f}, {0, -1, 0}}, 11, 6);
    const LightSet sheared(
        oneLight(quad({-1, 2, -1}, {1, 2, -1}, {1.8f, 2, 1}, {-0.2f, 2, 1}, Vec3f(1.0f))),
        Vec3f(0.0f), LightSampling::SolidAngle);
    ASSERT_TRUE(sheared.areaLight(0).parallelogram);
    ASSERT_FALSE(sheared.areaLight(0).rectangle);
    expectDirectionsFollowPdf(sheared, kReceivers[0], 12, 6);
}

// ∫ pdf dω over the light is 1, integrated over its area with dω = cosθ'/r² dA.
TEST(LightSet, RectanglePdfIntegratesToOne) {
    const LightSet lights(oneLight(tiltedRectangle()), Vec3f(0.0f), LightSampling::SolidAngle);
    const AreaLight& l = lights.areaLight(0);
    for (const Receiver& r : kReceivers) {
        double sum = 0;
        const int n = 600;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                const Vec3f p = l.p0 + l.e1 * ((i + 0.5f) / n) + l.e2 * ((j + 0.5f) / n);
                const Vec3f d = p - r.p;
                const double r2 = dot(d, d), cosLight = std::abs(dot(l.n, d)) / std::sqrt(r2);
                sum += lights.pdfAreaLight(0, r.p, r.ns, p) * cosLight / r2 * l.area / (n * n);
            }
        EXPECT_NEAR(sum, 1.0, 2e-3) << "receiver (" << r.p.x << "," << r.p.y << "," << r.p.z << ")";
    }
}

// The density a sample reports is the one pdfAreaLight gives its point, and the
// point lies on the light.
TEST(LightSet, SamplePdfEqualsPdfAreaLight) {
    const LightSet lights(oneLight(tiltedRectangle()), Vec3f(0.0f), LightSampling::SolidAngle);
    const AreaLight& l = lights.areaLight(0);
    Pcg32 rng(5, 0);
    for (const Receiver& r : kReceivers)
        for (int i = 0; i < 2000; ++i) {
            const float u0 = rng.nextFloat();
            const auto s = lights.sample(r.p, r.ns, 0.5f, {u0, rng.nextFloat()});
            ASSERT_TRUE(s);
            const Vec3f p = r.p + s->wi * s->distance;
            EXPECT_NEAR(dot(p - l.p0, l.n), 0.0f, 1e-5f);
            const float a = dot(p - l.p0, l.xAxis) / l.width, b = dot(p - l.p0, l.yAxis) / l.height;
            EXPECT_TRUE(a > -1e-5f && a < 1 + 1e-5f && b > -1e-5f && b < 1 + 1e-5f)
                << a << " " << b;
            EXPECT_NEAR(lights.pdfAreaLight(0, r.p, r.ns, p) / s->pdf, 1.0f, 2e-3f);
        }
}

// Receivers that see a rectangle at a tiny solid angle or from (nearly) its
// plane sample it by area: the density is then dist² / (A cosθ').
TEST(LightSet, TinyOrGrazingRectanglesAreSampledByArea) {
    const LightSet lights(oneLight(quad({-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1}, Vec3f(1))),
                          Vec3f(0.0f), LightSampling::SolidAngle);
    const Vec3f p{0.3f, 2, 0.2f};
    for (const Vec3f ref : {Vec3f(0, -500, 0), Vec3f(3, 2 - 1e-6f, 0)}) {
        const Vec3f d = p - ref;
        const float expected = dot(d, d) / (4 * std::abs(d.y) / length(d));
        EXPECT_NEAR(lights.pdfAreaLight(0, ref, Vec3f(0, 1, 0), p) / expected, 1.0f, 1e-4f);
    }
    // Just outside those bounds the density is the spherical one, ≠ area's.
    const Vec3f ref{0, -1, 0};
    const Vec3f d = p - ref;
    const float area = dot(d, d) / (4 * std::abs(d.y) / length(d));
    EXPECT_GT(std::abs(lights.pdfAreaLight(0, ref, Vec3f(0.0f), p) / area - 1), 0.01f);
}

// The point of sampling by solid angle with the cosine warp: the estimate of
// the irradiance E = ∫ L |cosθ| dω at a receiver close to a large light has far
// less variance than with uniform area sampling, and the same mean.
TEST(LightSet, SolidAngleSamplingReducesDirectLightingVariance) {
    const LightSet lights(oneLight(quad({-2, 1, -2}, {2, 1, -2}, {2, 1, 2}, {-2, 1, 2}, Vec3f(1))),
                          Vec3f(0.0f), LightSampling::SolidAngle);
    const AreaLight& l = lights.areaLight(0);
    const Vec3f ref{1.0f, 0.3f, 0.5f}, ns = normalize(Vec3f(0.4f, 1, 0));
    Pcg32 rng(9, 0);
    double sumA = 0, sumA2 = 0, sumS = 0, sumS2 = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
        const Vec2f u{rng.nextFloat(), rng.nextFloat()};
        // Area sampling, by hand.
        const Vec3f p = l.samplePoint(u), d = p - ref;
        const float r2 = dot(d, d), r = std::sqrt(r2);
        const double fa = std::abs(dot(ns, d) / r) * std::abs(dot(l.n, d) / r) * l.area / r2;
        sumA += fa, sumA2 += fa * fa;
        const auto s = lights.sample(ref, ns, 0.5f, u);
        ASSERT_TRUE(s);
        const double fs = std::abs(dot(ns, s->wi)) / s->pdf;
        sumS += fs, sumS2 += fs * fs;
    }
    const double meanA = sumA / n, varA = sumA2 / n - meanA * meanA;
    const double meanS = sumS / n, varS = sumS2 / n - meanS * meanS;
    EXPECT_NEAR(meanS, meanA, 4 * std::sqrt((varA + varS) / n));
    EXPECT_LT(varS, 0.1 * varA) << "variance " << varS << " vs area sampling " << varA;
}

// The default strategy samples even a rectangle uniformly by area: the density
// of every sample is dist² / (A |cosθ_light|), whatever the receiver normal.
TEST(LightSet, DefaultSamplesRectanglesByArea) {
    const LightSet lights(oneLight(tiltedRectangle()), Vec3f(0.0f));
    const AreaLight& l = lights.areaLight(0);
    ASSERT_TRUE(l.rectangle);
    EXPECT_FALSE(l.solidAngleSampling);
    const Vec3f ref = l.p0 + l.n * 0.7f + l.e1 * 0.2f, ns = normalize(Vec3f(0.3f, -1, 0.2f));
    Pcg32 rng(4, 0);
    for (int i = 0; i < 200; ++i) {
        const auto s = lights.sample(ref, ns, 0.5f, {rng.nextFloat(), rng.nextFloat()});
        ASSERT_TRUE(s);
        const float cosLight = std::abs(dot(l.n, s->wi));
        EXPECT_NEAR(s->pdf, s->distance * s->distance / (l.area * cosLight), 1e-3f * s->pdf);
    }
}

TEST(LightSet, ChoosesLightsInProportionToPower) {
    SceneDescription s;
    s.meshes.push_back(quad({-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1}, Vec3f(1.0f)));
    s.meshes.push_back(quad({-1, 3, -1}, {1, 3, -1}, {1, 3, 1}, {-1, 3, 1}, Vec3f(3.0f)));
    const LightSet lights(s, Vec3f(0.0f), LightSampling::SolidAngle);
    const Vec3f ref{0, 0, 0};
    // Without a receiver normal a rectangle is sampled uniformly in solid
    // angle, so pdf·Ω is the probability of choosing the light.
    const Vec3f none(0.0f);
    const float pdf0 = lights.pdfAreaLight(0, ref, none, {0, 2, 0}) * solidAngleOfSquare(2);
    const float pdf1 = lights.pdfAreaLight(1, ref, none, {0, 3, 0}) * solidAngleOfSquare(3);
    EXPECT_NEAR(pdf1 / pdf0, 3.0f, 1e-4f);
    int first = 0;
    for (int i = 0; i < 1000; ++i)
        if (auto ls = lights.sample(ref, none, (i + 0.5f) / 1000, {0.5f, 0.5f});
            ls && ls->distance < 2.5f)
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
