// The blackbody spectrum of spectral mode: Planck's law (checked against its
// form with the CODATA radiation constants c₁L and c₂, computed independently)
// normalised to 1 at Wien's peak, as pbrt-v4's BlackbodySpectrum.
#include <gtest/gtest.h>

#include <cmath>

#include "spectral/blackbody_spectrum.h"

namespace pathlab::spectral {
namespace {

// B(λ, T) = c₁L / λ⁵ / (exp(c₂ / (λT)) − 1), CODATA 2018: c₁L = 2hc² =
// 1.191042972e-16 W·m²·sr⁻¹, c₂ = hc/k = 1.438776877e-2 m·K.
double planckFromRadiationConstants(double lambdaNm, double kelvin) {
    const double l = lambdaNm * 1e-9;
    return 1.191042972e-16 / std::pow(l, 5) / (std::exp(1.438776877e-2 / (l * kelvin)) - 1);
}

TEST(SpectralBlackbody, PlanckMatchesTheRadiationConstantForm) {
    for (double kelvin : {1000.0, 2856.0, 6500.0, 20000.0})
        for (double lambda : {360.0, 450.0, 555.0, 700.0, 830.0}) {
            const double expected = planckFromRadiationConstants(lambda, kelvin);
            // c₁L and c₂ are published to 10 digits: agreement to 10⁻⁷.
            EXPECT_NEAR(planckRadiance(lambda, kelvin), expected, 1e-7 * expected)
                << lambda << " nm, " << kelvin << " K";
        }
    EXPECT_EQ(planckRadiance(500, 0), 0);
}

TEST(SpectralBlackbody, NormalisedToOneAtWiensPeak) {
    for (double kelvin : {3000.0, 5000.0, 6500.0}) {
        const BlackbodySpectrum b(kelvin);
        const double peak = b.peakWavelength();
        EXPECT_NEAR(peak, 2.897771955e6 / kelvin, 1e-9);
        EXPECT_NEAR(b(peak), 1.0, 1e-12);
        // The maximum: a little to either side is lower.
        EXPECT_LT(b(peak - 1), 1.0);
        EXPECT_LT(b(peak + 1), 1.0);
        // Every other value is Planck's law in the same ratio.
        for (double lambda : {400.0, 600.0, 800.0})
            EXPECT_NEAR(b(lambda), planckRadiance(lambda, kelvin) / planckRadiance(peak, kelvin),
                        1e-12);
    }
    // A hot body's peak lies below the visible range: the visible part is < 1.
    const BlackbodySpectrum hot(20000);
    const SampledSpectrum s = hot.sample(SampledWavelengths::sampleUniform(0.1f));
    for (int i = 0; i < kSpectrumSamples; ++i) {
        EXPECT_GT(s[i], 0);
        EXPECT_LT(s[i], 1);
    }
}

}  // namespace
}  // namespace pathlab::spectral
