// The BSDFs: sampling matches the density (chi-square), sample() agrees with
// f()/pdf(), no BSDF creates energy, Fresnel and refraction match closed forms.
#include <gtest/gtest.h>

#include <complex>

#include "chi_square.h"
#include "core/rng.h"
#include "render/bsdf.h"
#include "render/sampling_routines.h"

namespace pathlab {
namespace {

Vec3f directionFromAngle(float thetaDegrees, float phiDegrees = 30) {
    const float t = thetaDegrees * kPi / 180, p = phiDegrees * kPi / 180;
    return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

struct NamedBsdf {
    const char* name;
    Bsdf bsdf;
};

std::vector<NamedBsdf> glossyAndDiffuse() {
    const Vec3f gold_eta{0.143f, 0.374f, 1.442f}, gold_k{3.983f, 2.385f, 1.603f};
    return {{"diffuse", Bsdf::diffuse(Vec3f(0.5f, 0.6f, 0.7f))},
            {"ggx-0.1", Bsdf::conductor(gold_eta, gold_k, 0.1f)},
            {"ggx-0.3", Bsdf::conductor(gold_eta, gold_k, 0.3f)},
            {"ggx-0.8", Bsdf::conductor(gold_eta, gold_k, 0.8f)}};
}

const float kIncidentAngles[] = {0.0f, 30.0f, 60.0f, 85.0f, 120.0f};

TEST(BsdfSampling, ChiSquareAgainstPdf) {
    const int tests = int(glossyAndDiffuse().size() * std::size(kIncidentAngles));
    const double alpha = testing::sidakSignificance(0.01, tests);
    for (const NamedBsdf& nb : glossyAndDiffuse()) {
        for (float angle : kIncidentAngles) {
            const Vec3f wo = directionFromAngle(angle);
            Pcg32 rng(7, 0);
            const auto result = testing::chiSquareTest(
                [&](int) -> std::optional<Vec3f> {
                    const float uLobe = rng.nextFloat();
                    const float u0 = rng.nextFloat();
                    const auto s = nb.bsdf.sample(wo, uLobe, {u0, rng.nextFloat()});
                    if (!s) return std::nullopt;
                    return s->wi;
                },
                [&](Vec3f wi) { return double(nb.bsdf.pdf(wo, wi)); }, 400000);
            EXPECT_GT(result.pValue, alpha)
                << nb.name << " at " << angle << " degrees: " << result.detail;
        }
    }
}

TEST(BsdfSampling, SampleAgreesWithEvalAndPdf) {
    for (const NamedBsdf& nb : glossyAndDiffuse()) {
        Pcg32 rng(3, 0);
        for (int i = 0; i < 20000; ++i) {
            const Vec3f wo = sampleUniformSphere({rng.nextFloat(), rng.nextFloat()});
            const float uLobe = rng.nextFloat();
            const float u0 = rng.nextFloat();
            const auto s = nb.bsdf.sample(wo, uLobe, {u0, rng.nextFloat()});
            if (!s) continue;
            ASSERT_FALSE(s->specular);
            const float pdf = nb.bsdf.pdf(wo, s->wi);
            ASSERT_NEAR(s->pdf, pdf, 1e-3f * std::max(1.0f, pdf)) << nb.name;
            const Vec3f f = nb.bsdf.f(wo, s->wi);
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(s->f[c], f[c], 1e-3f * std::max(1.0f, f[c])) << nb.name;
        }
    }
}

// ∫ f(wo,wi)|cosθi| dωi ≤ 1 for every wo, estimated by uniform sphere sampling
// (independent of each BSDF's own sampling routine).
TEST(BsdfEnergy, NoBsdfCreatesEnergy) {
    for (const NamedBsdf& nb : glossyAndDiffuse()) {
        for (float angle : kIncidentAngles) {
            const Vec3f wo = directionFromAngle(angle);
            Pcg32 rng(11, 0);
            const int n = 400000;
            double sum[3] = {0, 0, 0};
            for (int i = 0; i < n; ++i) {
                const Vec3f wi = sampleUniformSphere({rng.nextFloat(), rng.nextFloat()});
                const Vec3f v = nb.bsdf.f(wo, wi) * (absCosTheta(wi) / uniformSpherePdf());
                for (int c = 0; c < 3; ++c) sum[c] += v[c];
            }
            for (int c = 0; c < 3; ++c)
                EXPECT_LE(sum[c] / n, 1.01) << nb.name << " at " << angle << " channel " << c;
        }
    }
    // The diffuse albedo is reproduced exactly in expectation.
    const Bsdf d = Bsdf::diffuse(Vec3f(0.5f));
    Pcg32 rng(5, 0);
    double sum = 0;
    for (int i = 0; i < 200000; ++i) {
        const Vec3f wi = sampleUniformSphere({rng.nextFloat(), rng.nextFloat()});
        sum += d.f(Vec3f(0, 0, 1), wi).x * absCosTheta(wi) / uniformSpherePdf();
    }
    EXPECT_NEAR(sum / 200000, 0.5, 0.01);
}

TEST(BsdfSpecular, DielectricSplitsEnergyByFresnel) {
    const Bsdf glass = Bsdf::dielectric(1.5f);
    const Vec3f wo = directionFromAngle(40);
    const float R = fresnelDielectric(wo.z, 1.5f);
    int reflected = 0;
    const int n = 100000;
    Pcg32 rng(1, 0);
    for (int i = 0; i < n; ++i) {
        const auto s = glass.sample(wo, rng.nextFloat(), {0.5f, 0.5f});
        ASSERT_TRUE(s);
        ASSERT_TRUE(s->specular);
        if (s->wi.z > 0) {
            ++reflected;
            EXPECT_NEAR(s->wi.x, -wo.x, 1e-6f);
            // Weight f·cos/pdf of the chosen lobe is 1 for reflection.
            EXPECT_NEAR(s->weight().x, 1.0f, 1e-5f);
        } else {
            // Snell's law: sinθt = sinθi / η.
            const float sinI = std::sqrt(1 - wo.z * wo.z), sinT = std::sqrt(1 - s->wi.z * s->wi.z);
            EXPECT_NEAR(sinT, sinI / 1.5f, 1e-5f);
            EXPECT_NEAR(s->weight().x, 1 / (1.5f * 1.5f), 1e-5f);
        }
    }
    EXPECT_NEAR(double(reflected) / n, R, 0.005);
}

TEST(Fresnel, DielectricMatchesClosedForms) {
    // Normal incidence: ((η−1)/(η+1))².
    EXPECT_NEAR(fresnelDielectric(1.0f, 1.5f), 0.04f, 1e-6f);
    // Total internal reflection beyond the critical angle from inside.
    const float critical = std::asin(1 / 1.5f);
    EXPECT_EQ(fresnelDielectric(-std::cos(critical + 0.01f), 1.5f), 1.0f);
    EXPECT_LT(fresnelDielectric(-std::cos(critical - 0.01f), 1.5f), 1.0f);
    // Brewster's angle: the parallel component vanishes, R = r⊥²/2.
    const float brewster = std::atan(1.5f);
    const float ci = std::cos(brewster), ct = std::cos(std::asin(std::sin(brewster) / 1.5f));
    const float rPerp = (ci - 1.5f * ct) / (ci + 1.5f * ct);
    EXPECT_NEAR(fresnelDielectric(ci, 1.5f), rPerp * rPerp / 2, 1e-6f);
    // A conductor with k = 0 is a dielectric.
    EXPECT_NEAR(fresnelComplex(0.7f, 1.5f, 0.0f), fresnelDielectric(0.7f, 1.5f), 1e-6f);
}

TEST(Fresnel, ConductorMatchesTheComplexFresnelEquations) {
    // The reflectances r = (η̃ cosθi − cosθt) / (η̃ cosθi + cosθt) and
    // (cosθi − η̃ cosθt) / (cosθi + η̃ cosθt) with complex η̃ = η + ik and
    // cosθt = √(1 − sin²θi / η̃²), in double precision, against the real
    // closed form, over grazing to normal incidence and metal-like indices.
    using C = std::complex<double>;
    for (double eta : {0.2, 0.27, 1.1, 1.5, 3.0})
        for (double k : {0.0, 0.5, 2.4, 3.9})
            for (double cosI : {0.001, 0.05, 0.3, 0.5, 0.7071, 0.9, 1.0}) {
                const C n(eta, k);
                const C cosT = std::sqrt(1.0 - (1 - cosI * cosI) / (n * n));
                const C rPar = (n * cosI - cosT) / (n * cosI + cosT);
                const C rPerp = (cosI - n * cosT) / (cosI + n * cosT);
                const double expected = (std::norm(rPar) + std::norm(rPerp)) / 2;
                EXPECT_NEAR(fresnelComplex(float(cosI), float(eta), float(k)), expected, 2e-6)
                    << "eta " << eta << " k " << k << " cos " << cosI;
            }
    // Grazing incidence reflects everything.
    EXPECT_FLOAT_EQ(fresnelComplex(0.0f, 0.27f, 2.8f), 1.0f);
}

TEST(Ggx, DistributionIsNormalisedOverProjectedArea) {
    // ∫ D(wm) cosθm dωm = 1 (microfacet projected area equals the macro area).
    for (float alpha : {0.1f, 0.4f, 0.9f}) {
        const GgxDistribution ggx{alpha};
        Pcg32 rng(9, 0);
        double sum = 0;
        const int n = 2000000;
        for (int i = 0; i < n; ++i) {
            Vec3f wm = sampleCosineHemisphere({rng.nextFloat(), rng.nextFloat()});
            if (wm.z <= 0) continue;
            sum += ggx.D(wm) * wm.z / cosineHemispherePdf(wm.z);
        }
        EXPECT_NEAR(sum / n, 1.0, 0.03) << "alpha " << alpha;
    }
}

}  // namespace
}  // namespace pathlab

namespace pathlab {
namespace {

TEST(SamplingRoutines, QuarterPiCosSinMatchesLibmToAFewUlp) {
    double worst = 0;
    for (int i = -100000; i <= 100000; ++i) {
        const float x = float(kPi / 4 * i / 100000.0);
        const Vec2f cs = cosSinQuarterPi(x);
        // In units of the float spacing near 1 (cos ≥ 0.7, |sin| ≤ 0.71).
        worst = std::max({worst, std::abs(cs.x - std::cos(double(x))) / 0x1p-24,
                          std::abs(cs.y - std::sin(double(x))) / 0x1p-24});
    }
    EXPECT_LT(worst, 2.0);
}

TEST(SamplingRoutines, TurnCosSinMatchesLibmOverTheWholeCircle) {
    double worst = 0;
    for (int i = 0; i <= 400000; ++i) {
        const float t = i == 400000 ? 1.0f : float(i / 400000.0);
        const Vec2f cs = cosSinTurn(t);
        const double angle = 2 * M_PI * double(t);
        worst = std::max({worst, std::abs(cs.x - std::cos(angle)) / 0x1p-24,
                          std::abs(cs.y - std::sin(angle)) / 0x1p-24});
    }
    // A few float spacings near 1: the remainder's angle is rounded once.
    EXPECT_LT(worst, 4.0);
    // Just below 1 is a sliver of a turn before the start, not after it.
    EXPECT_LT(cosSinTurn(0x1.fffffep-1f).y, 0.0f);
    EXPECT_GT(cosSinTurn(0x1p-20f).y, 0.0f);
}

TEST(SamplingRoutines, ConcentricDiskKeepsRadiusAndWedgeAngle) {
    // The mapping's definition (Shirley & Chiu 1997): square ring max(|x|,|y|)
    // = r goes to the circle of radius r, and each wedge's position along the
    // ring to the angle (π/4)·(ratio) measured from the wedge's axis.
    Pcg32 rng(5, 0);
    for (int i = 0; i < 100000; ++i) {
        const Vec2f u{rng.nextFloat(), rng.nextFloat()};
        const double ox = 2.0 * u.x - 1, oy = 2.0 * u.y - 1;
        const Vec2f d = sampleConcentricDisk(u);
        const double r = std::max(std::abs(ox), std::abs(oy));
        const double theta =
            std::abs(ox) > std::abs(oy) ? kPi / 4 * (oy / ox) : kPi / 2 - kPi / 4 * (ox / oy);
        const double scale = std::abs(ox) > std::abs(oy) ? ox : oy;
        ASSERT_NEAR(std::hypot(d.x, d.y), r, 1e-6);
        ASSERT_NEAR(d.x, scale * std::cos(theta), 1e-6) << u.x << "," << u.y;
        ASSERT_NEAR(d.y, scale * std::sin(theta), 1e-6) << u.x << "," << u.y;
    }
}

}  // namespace
}  // namespace pathlab
