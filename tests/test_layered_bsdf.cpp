// The stochastic layered BSDF (coateddiffuse, coatedconductor). Its f and
// pdf are estimates and its sample's pdf only proportional to the walk's
// density, so a chi-square test of sample() against pdf() does not apply
// (pdf() is pbrt-v4's approximation, for MIS only). What must hold, and is
// tested: sample()'s weights, binned by direction, estimate the same
// integrals of f·cosθ as f() does (sample and f describe one BSDF); energy is
// conserved where nothing absorbs; f is reciprocal in expectation; an
// index-matched coating of no thickness is the base alone; and in the
// renderer the layered walks read their own dimensions.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "render/layered/layered_bsdf.h"
#include "render/sampling_routines.h"

namespace pathlab {
namespace {

Vec3f direction(float cosTheta, float phi) {
    const float s = std::sqrt(1 - cosTheta * cosTheta);
    return {s * std::cos(phi), s * std::sin(phi), cosTheta};
}

DielectricInterface coatingOf(float eta, float alpha) {
    DielectricInterface d;
    d.eta = eta;
    d.ggx = GgxDistribution(alpha);
    return d;
}

LayeredBsdf coatedDiffuse(float eta, float alpha, Vec3f reflectance, LayerParameters p) {
    return LayeredBsdf(coatingOf(eta, alpha), Bsdf::diffuse(reflectance), p);
}

// Mean and standard error of a running sum.
struct Mean {
    double sum = 0, sum2 = 0;
    long n = 0;
    void add(double x) { sum += x, sum2 += x * x, ++n; }
    double mean() const { return sum / double(n); }
    double error() const {
        const double m = mean();
        return std::sqrt(std::max(0.0, sum2 / double(n) - m * m) / double(n));
    }
};

TEST(LayeredBsdf, IndexMatchedThinCoatingIsTheBase) {
    LayerParameters p;
    p.thickness = 1e-7f;
    const Bsdf bases[] = {Bsdf::diffuse(Vec3f(0.6f, 0.3f, 0.1f)),
                          Bsdf::conductor(Vec3f(0.2f, 0.9f, 1.1f), Vec3f(3.9f, 2.4f, 2.1f), 0.3f)};
    for (const Bsdf& base : bases) {
        const LayeredBsdf layered(coatingOf(1, 0), base, p);
        PcgWalkNumbers r(7);
        for (float co : {0.2f, 0.6f, 0.95f})
            for (float ci : {0.15f, 0.5f, 0.9f}) {
                const Vec3f wo = direction(co, 0.3f), wi = direction(ci, 2.5f);
                const Vec3f expected = base.f(wo, wi), got = layered.f(wo, wi, r);
                for (int c = 0; c < 3; ++c)
                    EXPECT_NEAR(got[c], expected[c], 1e-4f * (1 + expected[c]))
                        << "cos " << co << ", " << ci;
                // Seen from below (two-sided).
                EXPECT_NEAR(layered.f(-wo, -wi, r).x, expected.x, 1e-4f * (1 + expected.x));
            }
    }
}

// The directional albedo ∫ f cosθ dωi, two ways: by sample()'s weights and
// by f() at uniformly distributed directions; and per bin of (cos²θ, φ), so
// that sample() must put its weight where f() has it.
struct AlbedoBins {
    static constexpr int kCos = 4, kPhi = 4;
    Mean bySample[kCos * kPhi], byF[kCos * kPhi];
    Mean totalSample, totalF;
    static int bin(Vec3f w) {
        const int c = std::min(kCos - 1, int(w.z * w.z * kCos));
        float phi = std::atan2(w.y, w.x);
        if (phi < 0) phi += 2 * kPi;
        return c * kPhi + std::min(kPhi - 1, int(phi / (2 * kPi) * kPhi));
    }
};

AlbedoBins albedoBins(const LayeredBsdf& b, Vec3f wo, int n) {
    AlbedoBins a;
    PcgWalkNumbers r(11), u(12);
    for (int i = 0; i < n; ++i) {
        const float uc = u.next();
        const Vec2f uv{u.next(), u.next()};
        const auto s = b.sample(wo, uc, uv, r);
        const bool counts = s && !s->specular && s->wi.z > 0;
        const double w = counts ? double(s->weight().y) : 0.0;
        a.totalSample.add(w);
        const int k = counts ? AlbedoBins::bin(s->wi) : -1;
        for (int j = 0; j < AlbedoBins::kCos * AlbedoBins::kPhi; ++j)
            a.bySample[j].add(j == k ? w : 0.0);
        // Uniform over the upper hemisphere: density 1/(2π).
        const Vec3f wi = direction(u.next(), 2 * kPi * u.next());
        const double fw = double(b.f(wo, wi, r).y) * wi.z * 2 * kPi;
        a.totalF.add(fw);
        const int kf = AlbedoBins::bin(wi);
        for (int j = 0; j < AlbedoBins::kCos * AlbedoBins::kPhi; ++j)
            a.byF[j].add(j == kf ? fw : 0.0);
    }
    return a;
}

void expectAgree(const Mean& a, const Mean& b, const char* what, int i) {
    const double tol = 4.5 * std::hypot(a.error(), b.error()) + 2e-3;
    EXPECT_NEAR(a.mean(), b.mean(), tol) << what << " bin " << i;
}

TEST(LayeredBsdf, SampleWeightsMatchTheValueByDirection) {
    LayerParameters absorbing;
    absorbing.thickness = 0.05f;
    LayerParameters scattering = absorbing;
    scattering.albedo = Vec3f(0.8f);
    scattering.g = 0.4f;
    const LayeredBsdf cases[] = {
        coatedDiffuse(1.5f, 0.3f, Vec3f(0.7f), absorbing),
        coatedDiffuse(1.5f, 0, Vec3f(0.7f), scattering),
        coatedDiffuse(1.33f, 0.5f, Vec3f(0.5f), scattering),
        LayeredBsdf(coatingOf(1.5f, 0.2f),
                    Bsdf::conductor(Vec3f(0.13f, 0.6f, 0.73f), Vec3f(2.6f, 1.6f, 1.4f), 0.4f),
                    absorbing),
    };
    for (const LayeredBsdf& b : cases) {
        const AlbedoBins a = albedoBins(b, direction(0.7f, 0.4f), 40000);
        expectAgree(a.totalSample, a.totalF, "albedo", -1);
        for (int j = 0; j < AlbedoBins::kCos * AlbedoBins::kPhi; ++j)
            expectAgree(a.bySample[j], a.byF[j], "bin", j);
    }
}

TEST(LayeredBsdf, WhiteFurnaceConservesEnergy) {
    // A white base under a smooth clear coating over a non-absorbing medium
    // loses nothing: the directional albedo is 1 (the walk is long enough
    // that its cut at maxDepth is negligible). A rough coating is no such
    // case: GGX single scattering loses energy, most of all from inside the
    // denser medium (up to 30% at α = 0.4), where the walk meets it again and
    // again.
    LayerParameters p;
    p.thickness = 0.1f;
    p.albedo = Vec3f(1.0f);
    p.maxDepth = 2000;
    for (float g : {0.3f, -0.6f}) {
        p.g = g;
        const float alpha = 0;
        const LayeredBsdf b = coatedDiffuse(1.5f, alpha, Vec3f(1.0f), p);
        for (float cosO : {0.3f, 0.9f}) {
            const Vec3f wo = direction(cosO, 1.0f);
            PcgWalkNumbers r(3), u(4);
            Mean bySample;
            for (int i = 0; i < 20000; ++i) {
                const float uc = u.next();
                const auto s = b.sample(wo, uc, {u.next(), u.next()}, r);
                bySample.add(s ? double(s->weight().x) : 0.0);
            }
            EXPECT_NEAR(bySample.mean(), 1.0, 4 * bySample.error() + 2e-3)
                << "g " << g << " cos " << cosO;
        }
    }
    // With an absorbing medium the albedo is below 1.
    p.albedo = Vec3f(0.0f);
    p.thickness = 0.5f;
    const AlbedoBins a =
        albedoBins(coatedDiffuse(1.5f, 0.2f, Vec3f(1.0f), p), direction(0.8f, 0), 20000);
    EXPECT_LT(a.totalSample.mean(), 0.9);
    EXPECT_LT(a.totalF.mean(), 0.9);
}

TEST(LayeredBsdf, ValueIsReciprocalInExpectation) {
    LayerParameters p;
    p.thickness = 0.1f;
    p.albedo = Vec3f(0.9f);
    p.g = -0.3f;
    p.nSamples = 8;
    const LayeredBsdf b = coatedDiffuse(1.5f, 0.35f, Vec3f(0.6f), p);
    const std::pair<Vec3f, Vec3f> pairs[] = {{direction(0.9f, 0), direction(0.3f, 2)},
                                             {direction(0.5f, 1), direction(0.7f, 4)},
                                             {direction(0.2f, 3), direction(0.95f, 3.5f)}};
    for (const auto& [a, c] : pairs) {
        Mean forward, backward;
        PcgWalkNumbers r(21);
        for (int i = 0; i < 3000; ++i) {
            forward.add(b.f(a, c, r).x);
            backward.add(b.f(c, a, r).x);
        }
        EXPECT_NEAR(forward.mean(), backward.mean(),
                    4.5 * std::hypot(forward.error(), backward.error()));
        EXPECT_GT(forward.mean(), 0.0);
    }
}

TEST(LayeredBsdf, PdfIsPositiveAndFollowsTheSampleForAClearCoat) {
    // Index-matched and thin: the walk's exit density is the base's cosine
    // density, and pbrt-v4's estimate is exactly 0.1/(4π) + 0.9·cosθ/π.
    LayerParameters p;
    p.thickness = 1e-7f;
    const LayeredBsdf b = coatedDiffuse(1, 0, Vec3f(0.5f), p);
    PcgWalkNumbers r(5);
    for (float c : {0.1f, 0.5f, 0.99f}) {
        const Vec3f wo = direction(0.6f, 0), wi = direction(c, 1.3f);
        EXPECT_NEAR(b.pdf(wo, wi, r), 0.1f / (4 * kPi) + 0.9f * c / kPi, 1e-4f);
        // Below the surface nothing arrives, but the estimate stays positive.
        EXPECT_NEAR(b.pdf(wo, -wi, r), 0.1f / (4 * kPi), 1e-6f);
    }
}

}  // namespace
}  // namespace pathlab
