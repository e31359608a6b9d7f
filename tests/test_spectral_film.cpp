// The film's side of spectral mode: the Monte Carlo estimate of XYZ from a
// path's wavelengths. An emitter of RGB colour c (illuminantSpectrum) seen
// directly comes out as c in expectation — the white furnace identity, for
// the visible and the uniform wavelength densities and after the secondary
// wavelengths are terminated — and a reflectance of colour c under white
// light (the illuminant) integrates back to c.
#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"
#include "spectral/film_xyz.h"
#include "spectral/rgb_spectrum.h"

namespace pathlab::spectral {
namespace {

using Sampler = SampledWavelengths (*)(float);

// Mean and standard error of spectrumToLinearSrgb(radiance(w)) over n random u.
struct Estimate {
    Vec3f mean, standardError;
};
template <typename Radiance>
Estimate estimate(Sampler sample, Radiance radiance, int n, bool terminate = false) {
    Pcg32 rng(23, 0);
    Vec3f sum, sumSq;
    for (int i = 0; i < n; ++i) {
        SampledWavelengths w = sample(rng.nextFloat());
        if (terminate) w.terminateSecondary();
        const Vec3f c = spectrumToLinearSrgb(radiance(w), w);
        sum += c;
        sumSq += c * c;
    }
    const Vec3f mean = sum / float(n), variance = sumSq / float(n) - mean * mean;
    return {mean, Vec3f(std::sqrt(std::max(variance.x, 0.f) / n),
                        std::sqrt(std::max(variance.y, 0.f) / n),
                        std::sqrt(std::max(variance.z, 0.f) / n))};
}

void expectWithin(const Estimate& e, Vec3f expected, const char* what) {
    for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(e.mean[i], expected[i], 5 * e.standardError[i] + 2e-4f * (1 + expected[i]))
            << what << " channel " << i << " (standard error " << e.standardError[i] << ")";
}

TEST(SpectralFilm, EmitterOfRgbColourIsThatColourInExpectation) {
    const Vec3f colours[] = {Vec3f(1, 1, 1), Vec3f(0.2f, 0.5f, 0.9f), Vec3f(4, 1, 0.25f),
                             Vec3f(0, 0.3f, 0)};
    for (Sampler sample : {&SampledWavelengths::sampleVisible, &SampledWavelengths::sampleUniform})
        for (Vec3f c : colours) {
            auto radiance = [&](const SampledWavelengths& w) { return illuminantSpectrum(c, w); };
            expectWithin(estimate(sample, radiance, 40000), c, "direct");
            expectWithin(estimate(sample, radiance, 40000, true), c, "terminated");
        }
}

TEST(SpectralFilm, ReflectanceUnderWhiteLightIntegratesBackToItsColour) {
    // The expectation over u as an integral: the midpoint rule on 2¹⁴ values
    // of u (65 536 wavelengths, stratified), far finer than the 5-nm tables.
    const int n = 1 << 14;
    const Vec3f colours[] = {Vec3f(0.18f), Vec3f(0.8f, 0.1f, 0.1f), Vec3f(0.1f, 0.6f, 0.2f),
                             Vec3f(0.2f, 0.3f, 0.7f), Vec3f(0.95f, 0.85f, 0.3f)};
    for (Vec3f c : colours) {
        Vec3f sum;
        for (int i = 0; i < n; ++i) {
            const SampledWavelengths w = SampledWavelengths::sampleVisible((i + 0.5f) / n);
            sum +=
                spectrumToLinearSrgb(albedoSpectrum(c, w) * illuminantSpectrum(Vec3f(1.f), w), w);
        }
        const Vec3f mean = sum / float(n);
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(mean[i], c[i], 1e-3) << i;
    }
}

TEST(SpectralFilm, ConstantSpectrumOfLuminanceOneHasYOne) {
    // Y of a flat spectrum 1 over 360–830 nm is ∫ȳ / CIE_Y_integral = 1 in
    // expectation, whatever the density.
    auto flat = [](const SampledWavelengths&) { return SampledSpectrum(1.f); };
    for (Sampler sample :
         {&SampledWavelengths::sampleVisible, &SampledWavelengths::sampleUniform}) {
        Pcg32 rng(29, 0);
        double y = 0;
        const int n = 40000;
        for (int i = 0; i < n; ++i) {
            const SampledWavelengths w = sample(rng.nextFloat());
            y += spectrumToXyz(flat(w), w).y;
        }
        EXPECT_NEAR(y / n, 1.0, 5e-3);
    }
}

}  // namespace
}  // namespace pathlab::spectral
