// Wavelength sampling for spectral mode: pbrt-v4's visible density is a
// normalised pdf whose inverse CDF draws it (chi-square), one u gives one
// wavelength in each quarter of the CDF, the uniform and hero variants, and
// the termination of secondary wavelengths at dispersive interfaces.
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <set>

#include "core/rng.h"
#include "spectral/sampled_wavelengths.h"

namespace pathlab::spectral {
namespace {

TEST(SpectralWavelengths, VisiblePdfIntegratesToOne) {
    // Composite Simpson on 0.1-nm panels; the pdf is smooth, so the rule is
    // accurate far beyond the tolerance.
    const int panels = 4700;
    const double h = (kLambdaMax - kLambdaMin) / panels;
    double sum = 0;
    for (int i = 0; i < panels; ++i) {
        // The last end clamped: kLambdaMin + panels·h may round past kLambdaMax.
        const double a = kLambdaMin + i * h, b = std::min<double>(a + h, kLambdaMax);
        sum += (b - a) / 6 *
               (visibleWavelengthPdf(a) + 4 * visibleWavelengthPdf((a + b) / 2) +
                visibleWavelengthPdf(b));
    }
    EXPECT_NEAR(sum, 1.0, 1e-9);
    EXPECT_EQ(visibleWavelengthPdf(kLambdaMin - 1), 0);
    EXPECT_EQ(visibleWavelengthPdf(kLambdaMax + 1), 0);
    // pbrt-v4's density peaks at 538 nm, its constant there 0.0039398042.
    EXPECT_NEAR(visibleWavelengthPdf(538), 0.0039398042, 1e-8);
}

TEST(SpectralWavelengths, InverseCdfAndPdfAgree) {
    for (double u = 0; u < 1; u += 1.0 / 64) {
        const double lambda = sampleVisibleWavelength(u);
        EXPECT_NEAR(visibleWavelengthCdf(lambda), u, 1e-9) << u;
        // The pdf is the CDF's derivative.
        const double h = 1e-4;
        if (lambda > kLambdaMin + h && lambda < kLambdaMax - h) {
            EXPECT_NEAR(
                (visibleWavelengthCdf(lambda + h) - visibleWavelengthCdf(lambda - h)) / (2 * h),
                visibleWavelengthPdf(lambda), 1e-7);
        }
    }
    EXPECT_NEAR(sampleVisibleWavelength(0), kLambdaMin, 1e-9);
    EXPECT_NEAR(sampleVisibleWavelength(1), kLambdaMax, 1e-6);
}

// Pearson's chi-square of every lane's λ against the pdf over 47 bins of 10 nm.
TEST(SpectralWavelengths, SampledVisibleWavelengthsFollowThePdf) {
    const int bins = 47, draws = 50000;
    std::vector<double> observed(bins, 0);
    Pcg32 rng(7, 0);
    for (int d = 0; d < draws; ++d) {
        const SampledWavelengths w = SampledWavelengths::sampleVisible(rng.nextFloat());
        for (int i = 0; i < kSpectrumSamples; ++i) {
            ASSERT_GE(w.lambda(i), kLambdaMin);
            ASSERT_LE(w.lambda(i), kLambdaMax);
            EXPECT_NEAR(w.pdf(i), visibleWavelengthPdf(w.lambda(i)), 1e-5 * w.pdf(i));
            observed[size_t(std::min(bins - 1, int((w.lambda(i) - kLambdaMin) / 10)))] += 1;
        }
    }
    const double total = double(draws) * kSpectrumSamples;
    double chi2 = 0;
    for (int b = 0; b < bins; ++b) {
        const double expected = total * (visibleWavelengthCdf(kLambdaMin + 10.0 * (b + 1)) -
                                         visibleWavelengthCdf(kLambdaMin + 10.0 * b));
        chi2 += (observed[size_t(b)] - expected) * (observed[size_t(b)] - expected) / expected;
    }
    const boost::math::chi_squared distribution(bins - 1);
    EXPECT_GT(boost::math::cdf(boost::math::complement(distribution, chi2)), 1e-3) << chi2;
}

TEST(SpectralWavelengths, OneWavelengthInEachQuarterOfTheCdf) {
    Pcg32 rng(11, 0);
    for (int d = 0; d < 2000; ++d) {
        const float u = rng.nextFloat();
        const SampledWavelengths w = SampledWavelengths::sampleVisible(u);
        std::set<int> quarters;
        for (int i = 0; i < kSpectrumSamples; ++i) {
            const double c = visibleWavelengthCdf(w.lambda(i));
            quarters.insert(std::min(kSpectrumSamples - 1, int(c * kSpectrumSamples + 1e-6)));
        }
        EXPECT_EQ(quarters.size(), size_t(kSpectrumSamples)) << u;
        // Lane 0 is the sample u itself.
        EXPECT_NEAR(visibleWavelengthCdf(w.lambda(0)), u, 1e-5);
    }
}

TEST(SpectralWavelengths, UniformAndHeroCoverTheRangeInStrata) {
    constexpr float range = kLambdaMax - kLambdaMin;
    Pcg32 rng(13, 0);
    for (int d = 0; d < 1000; ++d) {
        const float u = rng.nextFloat();
        const SampledWavelengths uniform = SampledWavelengths::sampleUniform(u);
        const SampledWavelengths hero = SampledWavelengths::sampleHero(u);
        EXPECT_NEAR(hero.lambda(0), kLambdaMin + u * range, 1e-3);
        std::set<int> quarters;
        for (int i = 0; i < kSpectrumSamples; ++i) {
            EXPECT_FLOAT_EQ(uniform.pdf(i), 1 / range);
            EXPECT_FLOAT_EQ(hero.pdf(i), 1 / range);
            EXPECT_NEAR(uniform.lambda(i), hero.lambda(i), 1e-3);
            // Consecutive hero lanes are a quarter of the range apart, cyclically.
            const float next = hero.lambda((i + 1) % kSpectrumSamples);
            EXPECT_NEAR(std::fmod(next - hero.lambda(i) + range, range), range / 4, 1e-3);
            quarters.insert(int((uniform.lambda(i) - kLambdaMin) / range * 4));
        }
        EXPECT_EQ(quarters.size(), size_t(kSpectrumSamples));
    }
}

TEST(SpectralWavelengths, TerminatingSecondaryKeepsLaneZeroAtAQuarterOfItsPdf) {
    SampledWavelengths w = SampledWavelengths::sampleVisible(0.3f);
    const SampledWavelengths before = w;
    EXPECT_FALSE(w.secondaryTerminated());
    w.terminateSecondary();
    EXPECT_TRUE(w.secondaryTerminated());
    EXPECT_FLOAT_EQ(w.pdf(0), before.pdf(0) / kSpectrumSamples);
    EXPECT_EQ(w.lambda(0), before.lambda(0));
    for (int i = 1; i < kSpectrumSamples; ++i) EXPECT_EQ(w.pdf(i), 0);
    w.terminateSecondary();  // a second dispersive interface changes nothing
    EXPECT_FLOAT_EQ(w.pdf(0), before.pdf(0) / kSpectrumSamples);
}

TEST(SpectralWavelengths, SpectrumArithmeticIsElementwise) {
    SampledSpectrum a, b(2.f);
    a.v = {1, 2, 3, 4};
    EXPECT_EQ((a + b).v, (std::array<float, 4>{3, 4, 5, 6}));
    EXPECT_EQ((a * b).v, (std::array<float, 4>{2, 4, 6, 8}));
    EXPECT_EQ((1.f - a).v, (std::array<float, 4>{0, -1, -2, -3}));
    EXPECT_EQ((a / SampledSpectrum(0.f)).v, (std::array<float, 4>{0, 0, 0, 0}));
    EXPECT_EQ(a.maxComponent(), 4);
    EXPECT_EQ(a.average(), 2.5f);
    EXPECT_FALSE(a.isBlack());
    EXPECT_TRUE(SampledSpectrum(0.f).isBlack());
}

}  // namespace
}  // namespace pathlab::spectral
