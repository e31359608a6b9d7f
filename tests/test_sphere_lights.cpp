// Emitting spheres: the points LightSet samples on them follow the density it
// reports (chi-square), that density integrates to one over what the
// receiver sees, a receiver inside samples by area, the pbrt-v4 loader keeps
// an emitting sphere exact, and a scene lit by a small sphere converges to
// the same image with cone or area sampling, the cone with less error.
#include <gtest/gtest.h>

#include "chi_square.h"
#include "core/rng.h"
#include "render/lights.h"
#include "render/renderer.h"
#include "scene/pbrt/importer.h"

namespace pathlab {
namespace {

Sphere emitter(Vec3f c, float r, Vec3f Le, bool twoSided = false) {
    Sphere s{c, r, 0};
    s.emission = Le;
    s.twoSided = twoSided;
    return s;
}

SceneDescription oneSphere(const Sphere& s) {
    SceneDescription d;
    d.spheres.push_back(s);
    return d;
}

// Distance along o + t·w (w unit) to the sphere's first crossing ahead, or −1.
double hitSphere(const Sphere& s, Vec3f o, Vec3f w) {
    const Vec3f oc = o - s.center;
    const double b = dot(oc, w), c = double(dot(oc, oc)) - double(s.radius) * s.radius;
    const double disc = b * b - c;
    if (disc < 0) return -1;
    const double t0 = -b - std::sqrt(disc), t1 = -b + std::sqrt(disc);
    return t0 > 0 ? t0 : (t1 > 0 ? t1 : -1);
}

// 1 − cos of the angle between a and b, without cancellation:
// |a×b|² / (|a||b| (|a||b| + a·b)).
double oneMinusCos(Vec3f a, Vec3f b) {
    const double ax = a.x, ay = a.y, az = a.z, bx = b.x, by = b.y, bz = b.z;
    const double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
    const double la = std::sqrt(ax * ax + ay * ay + az * az);
    const double lb = std::sqrt(bx * bx + by * by + bz * bz);
    const double d = ax * bx + ay * by + az * bz;
    return (cx * cx + cy * cy + cz * cz) / (la * lb * (la * lb + d));
}

// Chi-square of the directions against the density pdfAreaLight reports.
// They are binned in the frame whose z axis points at the centre, and from a
// receiver outside, the cone cos θ ∈ [cos θmax, 1] is stretched over the whole
// sphere (z′ = 1 − 2 (1 − cos θ)/(1 − cos θmax), the azimuth kept; the density
// times the Jacobian (1 − cos θmax)/2): the bins' numerical integration then
// never cuts the silhouette, which a narrow cone would put inside one bin.
void expectDirectionsFollowPdf(const LightSet& lights, const Sphere& s, Vec3f ref, Vec3f ns,
                               uint64_t seed, int tests) {
    Pcg32 rng(seed, 0);
    const Frame frame(normalize(s.center - ref));
    const double d2 = dot(s.center - ref, s.center - ref), r2 = double(s.radius) * s.radius;
    const bool stretch = d2 > r2;
    const double sin2Max = stretch ? r2 / d2 : 1, omcMax = sin2Max / (1 + std::sqrt(1 - sin2Max));
    const double jacobian = stretch ? omcMax / 2 : 1;
    const auto result = testing::chiSquareTest(
        [&](int) -> std::optional<Vec3f> {
            const float u0 = rng.nextFloat(), u1 = rng.nextFloat();
            const auto ls = lights.sample(ref, ns, 0.5f, {u0, u1});
            if (!ls) return std::nullopt;
            const Vec3f l = frame.toLocal(ls->wi);
            if (!stretch) return l;
            const double z = std::clamp(1 - 2 * oneMinusCos(ls->wi, frame.n) / omcMax, -1.0, 1.0);
            const double rxy = std::hypot(l.x, l.y), sxy = std::sqrt(1 - z * z);
            if (rxy == 0) return Vec3f(0, 0, float(z));
            return Vec3f(float(l.x / rxy * sxy), float(l.y / rxy * sxy), float(z));
        },
        [&](Vec3f q) -> double {
            Vec3f local = q;
            if (stretch) {
                const double omc = (1 - double(q.z)) / 2 * omcMax;
                const double sinT = std::sqrt(omc * (2 - omc)), rxy = std::hypot(q.x, q.y);
                if (rxy == 0) return 0;
                local = Vec3f(float(q.x / rxy * sinT), float(q.y / rxy * sinT), float(1 - omc));
            }
            const Vec3f w = normalize(frame.toWorld(local));
            const double t = hitSphere(s, ref, w);
            if (t <= 0) return 0;
            const Vec3f p = ref + w * float(t);
            if (isBlack(lights.areaLight(0).emittedAt(p, -w))) return 0;
            return lights.pdfAreaLight(0, ref, ns, p) * jacobian;
        },
        400000, 32, 64, 64);
    EXPECT_GT(result.pValue, testing::sidakSignificance(0.01, tests))
        << result.detail << " receiver (" << ref.x << "," << ref.y << "," << ref.z << ")";
}

const Sphere kLight = emitter({0.2f, 1.5f, -0.3f}, 0.5f, Vec3f(2, 3, 4));

TEST(SphereLight, ConeSamplingFollowsReportedPdf) {
    const LightSet lights(oneSphere(kLight), Vec3f(0.0f));
    ASSERT_EQ(lights.areaLightCount(), 1u);
    ASSERT_TRUE(lights.areaLight(0).sphere && lights.areaLight(0).solidAngleSampling);
    EXPECT_EQ(lights.lightOfSphere(0), 0);
    // Far (a narrow cone), near (a wide one), and almost touching.
    expectDirectionsFollowPdf(lights, kLight, {0, -1, 0}, {0, 1, 0}, 1, 4);
    expectDirectionsFollowPdf(lights, kLight, {0.6f, 0.8f, 0.2f}, Vec3f(0.0f), 2, 4);
    expectDirectionsFollowPdf(lights, kLight, {0.2f, 0.98f, -0.3f}, {0, 1, 0}, 3, 4);
    // Area sampling from outside: only near-side points are seen (the far
    // side is its back), so half the samples fail.
    const LightSet byArea(oneSphere(kLight), Vec3f(0.0f), LightSampling::UniformArea);
    expectDirectionsFollowPdf(byArea, kLight, {0.6f, 0.8f, 0.2f}, Vec3f(0.0f), 4, 4);
}

// The cone sample's density is uniform: a sampled point's 1 − cos θ, θ its
// angle from the axis, is uniform in [0, 1 − cos θmax] — checked by a
// chi-square on 1 − 2 (1 − cos θ)/(1 − cos θmax) as cos θ, the azimuth kept.
// At 200 radii the cone is 0.29° wide, where 1 − cos²θ in single precision
// would have kept about two digits.
TEST(SphereLight, NarrowConesAreUniform) {
    const Sphere s = emitter({0, 0, 0}, 0.05f, Vec3f(1));
    const LightSet lights(oneSphere(s), Vec3f(0.0f));
    const Vec3f ref{3, -9, 2};
    const double d2 = dot(ref, ref), sin2Max = 0.05 * 0.05 / d2;
    const double oneMinusCosMax = sin2Max / (1 + std::sqrt(1 - sin2Max));
    const Frame frame(normalize(s.center - ref));
    Pcg32 rng(7, 0);
    const auto result = testing::chiSquareTest(
        [&](int) -> std::optional<Vec3f> {
            const float u0 = rng.nextFloat(), u1 = rng.nextFloat();
            const auto ls = lights.sample(ref, {}, 0.5f, {u0, u1});
            if (!ls) return std::nullopt;
            const Vec3f local = frame.toLocal(ls->wi);
            const double z = 1 - 2 * oneMinusCos(ls->wi, frame.n) / oneMinusCosMax;
            const double rxy = std::hypot(local.x, local.y);
            const double sxy = std::sqrt(std::max(0.0, 1 - z * z));
            return Vec3f(float(local.x / rxy * sxy), float(local.y / rxy * sxy), float(z));
        },
        [](Vec3f) { return 1 / (4 * M_PI); }, 200000, 16, 16, 4);
    EXPECT_GT(result.pValue, 0.01) << result.detail;
    // Every point is on the sphere, on the side facing the receiver.
    for (int i = 0; i < 1000; ++i) {
        const auto ls = lights.sample(ref, {}, 0.5f, {(i + 0.5f) / 1000, rng.nextFloat()});
        ASSERT_TRUE(ls);
        const Vec3f p = ref + ls->wi * ls->distance;
        EXPECT_NEAR(length(p - s.center), s.radius, 1e-3f * s.radius);
        EXPECT_GT(dot(p - s.center, ref - p), 0);
        EXPECT_NEAR(ls->pdf * (2 * M_PI * oneMinusCosMax), 1.0, 1e-5);
        EXPECT_EQ(lights.pdfAreaLight(0, ref, {}, p), ls->pdf);  // what MIS will use
    }
}

// ∫ pdf dω = 1 over the visible part of the sphere, integrated over its
// surface with dω = |cos θ'| / dist² dA: for cone sampling from outside
// (wide and narrow cones), and for area sampling from inside, where the whole
// sphere is seen.
TEST(SphereLight, PdfIntegratesToOne) {
    const Sphere s = emitter({0.2f, 1.5f, -0.3f}, 0.5f, Vec3f(1), true);
    const LightSet lights(oneSphere(s), Vec3f(0.0f));
    for (const Vec3f ref :
         {Vec3f(0, -1, 0), Vec3f(0.6f, 0.8f, 0.2f), Vec3f(40, -30, 20), Vec3f(0.3f, 1.6f, -0.1f)}) {
        const bool inside = length(ref - s.center) < s.radius;
        double sum = 0;
        const int n = 1000;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < 2 * n; ++j) {
                const double z = -1 + (i + 0.5) * 2 / n, phi = (j + 0.5) * M_PI / n;
                const double rxy = std::sqrt(1 - z * z);
                const Vec3f nrm(float(rxy * std::cos(phi)), float(rxy * std::sin(phi)), float(z));
                const Vec3f p = s.center + nrm * s.radius, d = ref - p;
                const double dist2 = dot(d, d), cosLight = dot(nrm, d) / std::sqrt(dist2);
                if (!inside && cosLight <= 0) continue;  // hidden by the sphere
                const double dA = (2.0 / n) * (M_PI / n) * s.radius * s.radius;
                sum += lights.pdfAreaLight(0, ref, {}, p) * std::abs(cosLight) / dist2 * dA;
            }
        EXPECT_NEAR(sum, 1.0, 3e-3) << "receiver (" << ref.x << "," << ref.y << "," << ref.z << ")";
    }
}

// From inside, the density is the area one, dist² / (4πr² |cos θ'|), and the
// directions (of a two-sided sphere, the only kind seen from inside) follow it.
TEST(SphereLight, InsideFallsBackToAreaSampling) {
    const Sphere s = emitter({0.2f, 1.5f, -0.3f}, 0.5f, Vec3f(1), true);
    const LightSet lights(oneSphere(s), Vec3f(0.0f));
    const Vec3f ref{0.3f, 1.6f, -0.1f};
    Pcg32 rng(3, 0);
    for (int i = 0; i < 200; ++i) {
        const auto ls = lights.sample(ref, {}, 0.5f, {rng.nextFloat(), rng.nextFloat()});
        ASSERT_TRUE(ls);
        const Vec3f p = ref + ls->wi * ls->distance;
        const float cosLight = std::abs(dot(normalize(p - s.center), ls->wi));
        const float expected = ls->distance * ls->distance / (4 * kPi * 0.25f * cosLight);
        EXPECT_NEAR(ls->pdf / expected, 1.0f, 1e-3f);
    }
    expectDirectionsFollowPdf(lights, s, ref, {0, 1, 0}, 5, 1);
    // A one-sided sphere emits outwards only: nothing reaches a receiver inside.
    const LightSet oneSided(oneSphere(kLight), Vec3f(0.0f));
    EXPECT_FALSE(oneSided.sample(kLight.center, {}, 0.5f, {0.3f, 0.6f}));
}

TEST(SphereLight, PbrtLoaderKeepsEmittingSpheresExact) {
    const std::string text =
        "LookAt 0 -5 1  0 0 0  0 0 1\nCamera \"perspective\"\nWorldBegin\n"
        "AttributeBegin\nTranslate 1 2 3\nScale 2 2 2\n"
        "AreaLightSource \"diffuse\" \"rgb L\" [1 2 3] \"float power\" 10\n"
        "Shape \"sphere\" \"float radius\" 0.5\nAttributeEnd\n"
        "AttributeBegin\nScale -1 1 1\nAreaLightSource \"diffuse\"\n"
        "Shape \"sphere\"\nAttributeEnd\n";
    const SceneDescription s = pbrt::importPbrtText(text, "test.pbrt", ".", {}).scene;
    ASSERT_EQ(s.spheres.size(), 1u);
    const Vec3f c = s.spheres[0].center;
    EXPECT_TRUE(c.x == 1 && c.y == 2 && c.z == 3);
    EXPECT_FLOAT_EQ(s.spheres[0].radius, 1.0f);
    // pbrt-v4 divides the power by π times the object-space area 4π·0.5²
    // (an RGB L counts as one nit).
    const float k = 10 / (kPi * kPi);
    EXPECT_NEAR(s.spheres[0].emission.x, 1 * k, 1e-4f * k);
    EXPECT_NEAR(s.spheres[0].emission.z, 3 * k, 1e-4f * k);
    // Under a mirror pbrt-v4 flips the normal (it would emit inwards):
    // triangles, which carry that orientation.
    ASSERT_EQ(s.meshes.size(), 1u);
    EXPECT_FALSE(isBlack(s.meshes[0].emission));
}

// A floor, a diffuse ball and a small bright sphere light above them: cone and area
// sampling converge to the same image, the cone with far less error at
// equal samples per pixel.
TEST(SphereLight, SmallSphereLightConvergesWithLessError) {
    SceneDescription d;
    d.materials.push_back(Material{"white", MaterialType::Diffuse, Vec3f(0.6f)});
    Mesh floor;
    floor.positions = {{-3, 0, -3}, {3, 0, -3}, {3, 0, 3}, {-3, 0, 3}};
    floor.indices = {0, 2, 1, 0, 3, 2};
    d.meshes.push_back(floor);
    d.spheres.push_back(Sphere{{0.6f, 0.5f, 0}, 0.5f, 0});
    // Out of the camera's view: seen directly, its edge pixels' noise would
    // be most of either image's error.
    d.spheres.push_back(emitter({-0.5f, 2.6f, 1.0f}, 0.1f, Vec3f(60)));
    d.camera = Camera{{0, 2.5f, 4}, {0, 0.4f, 0}, {0, 1, 0}, 40};
    d.resolution = {24, 24};
    RenderSettings s;
    s.maxDepth = 3;
    s.samplesPerPixel = 2048;
    const Image reference = render(RenderScene(d), s).image;
    s.samplesPerPixel = 16;
    s.seed = 1;
    const RenderOutput cone = render(RenderScene(d), s);
    const RenderOutput area = render(RenderScene(d, LightSampling::UniformArea), s);
    auto mse = [&](const Image& im) {
        double e = 0;
        for (size_t i = 0; i < im.rgb.size(); ++i)
            e += double(im.rgb[i] - reference.rgb[i]) * (im.rgb[i] - reference.rgb[i]);
        return e / double(im.rgb.size());
    };
    // Means within 4 standard errors (from the renders' own variance).
    for (const RenderOutput* out : {&cone, &area}) {
        double diff = 0, var = 0;
        for (size_t i = 0; i < reference.rgb.size(); ++i)
            diff += out->image.rgb[i] - reference.rgb[i], var += out->varianceOfMean.rgb[i];
        EXPECT_LT(std::abs(diff), 4 * std::sqrt(3 * var)) << (out == &cone ? "cone" : "area");
    }
    const double mseCone = mse(cone.image), mseArea = mse(area.image);
    std::printf("MSE at 16 spp against 2048 spp: cone %.4g, area %.4g (ratio %.2f)\n", mseCone,
                mseArea, mseArea / mseCone);
    EXPECT_LT(mseCone, 0.5 * mseArea);
}

}  // namespace
}  // namespace pathlab
