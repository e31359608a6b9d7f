// Spectral mode's colour context (see rgb_context.h for the interface): the
// path carries its radiance at four wavelengths sampled per camera sample
// (pbrt-v4's SampledSpectrum and SampledWavelengths), and the scene's RGB
// parameters become spectra at those wavelengths by Jakob & Hanika 2019's
// sigmoid-polynomial upsampling — reflectances bounded to [0, 1]
// (albedoSpectrum), emission as an unbounded spectrum times the colour
// space's illuminant, D65 for linear sRGB (illuminantSpectrum; pbrt-v4's
// RGBIlluminantSpectrum, so that RGB (1, 1, 1) light on a white film reads
// (1, 1, 1)). That conversion is homogeneous of degree one — a light's RGB
// radiance times a falloff or a distance's inverse square converts to the
// converted radiance times the same factor — so every light's radiance is
// converted where the integrator receives it.
#pragma once

#include "core/math.h"
#include "render/bsdf.h"
#include "spectral/film_xyz.h"
#include "spectral/rgb_spectrum.h"
#include "spectral/sampled_spectrum.h"
#include "spectral/sampled_wavelengths.h"

namespace pathlab {

class SpectralContext;

// Spectral values of an RGB-parameterised BSDF (spectral_bsdf.cpp): f(wo, wi),
// and f for a sample Bsdf::sample drew (whose direction and pdf are those of
// every wavelength: the indices of refraction are constant).
spectral::SampledSpectrum spectralBsdfF(const Bsdf& bsdf, Vec3f wo, Vec3f wi,
                                        const SpectralContext& ctx);
spectral::SampledSpectrum spectralSampledF(const Bsdf& bsdf, Vec3f wo, const BsdfSample& s,
                                           const SpectralContext& ctx);

class SpectralContext {
  public:
    using Colour = spectral::SampledSpectrum;
    static constexpr bool kSpectral = true;
    explicit SpectralContext(const spectral::SampledWavelengths& lambda) : lambda_(lambda) {}

    Colour reflectance(Vec3f rgb) const { return spectral::albedoSpectrum(rgb, lambda_); }
    Colour unbounded(Vec3f rgb) const { return spectral::unboundedSpectrum(rgb, lambda_); }
    Colour emission(Vec3f rgb) const { return spectral::illuminantSpectrum(rgb, lambda_); }
    Colour f(const Bsdf& bsdf, Vec3f wo, Vec3f wi) const {
        return spectralBsdfF(bsdf, wo, wi, *this);
    }
    Colour sampledF(const Bsdf& bsdf, Vec3f wo, const BsdfSample& s) const {
        return spectralSampledF(bsdf, wo, s, *this);
    }
    Vec3f toRgb(const Colour& L) const { return spectral::spectrumToLinearSrgb(L, lambda_); }
    const spectral::SampledWavelengths& wavelengths() const { return lambda_; }

  private:
    spectral::SampledWavelengths lambda_;
};

}  // namespace pathlab

// The integrator's templates test a throughput with isBlack and
// maxComponent; for a spectrum they are found by argument-dependent lookup.
namespace pathlab::spectral {
inline bool isBlack(const SampledSpectrum& s) {
    return s.isBlack();
}
inline float maxComponent(const SampledSpectrum& s) {
    return s.maxComponent();
}
}  // namespace pathlab::spectral
