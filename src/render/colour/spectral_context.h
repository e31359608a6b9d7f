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

#include <optional>

#include "core/math.h"
#include "render/bsdf.h"
#include "render/layered/layered_bsdf.h"
#include "spectral/colour_space.h"
#include "spectral/film_xyz.h"
#include "spectral/piecewise_linear_spectrum.h"
#include "spectral/rgb_spectrum.h"
#include "spectral/sampled_spectrum.h"
#include "spectral/sampled_wavelengths.h"

namespace pathlab {

class SpectralContext;

// Spectral values of a BSDF (spectral_bsdf.cpp): f(wo, wi), and f for a
// sample Bsdf::sample drew (whose direction and pdf are those of every
// wavelength: the indices of refraction are constant).
spectral::SampledSpectrum spectralBsdfF(const Bsdf& bsdf, Vec3f wo, Vec3f wi,
                                        const SpectralContext& ctx);
spectral::SampledSpectrum spectralSampledF(const Bsdf& bsdf, Vec3f wo, const BsdfSample& s,
                                           const SpectralContext& ctx);
// A layered BSDF's walks carrying spectra (spectral_layered.cpp).
spectral::SampledSpectrum spectralLayeredF(const LayeredBsdf& layered, Vec3f wo, Vec3f wi,
                                           WalkNumbers& r, const SpectralContext& ctx);
std::optional<LayeredSampleOf<spectral::SampledSpectrum>> spectralLayeredSample(
    const LayeredBsdf& layered, Vec3f wo, float uc, Vec2f u, WalkNumbers& r,
    const SpectralContext& ctx);

// The last few colours' sigmoid polynomials (rgbToSigmoid), so that a
// scene's handful of constant colours are looked up in the coefficient table
// once per thread (spectral_paths.h) rather than at every vertex. Exact:
// a hit returns what rgbToSigmoid returned for the same bits.
class SigmoidCache {
  public:
    spectral::SigmoidPolynomial operator()(Vec3f rgb) {
        for (int i = 0; i < size_; ++i)
            if (rgb_[i].x == rgb.x && rgb_[i].y == rgb.y && rgb_[i].z == rgb.z) return poly_[i];
        const spectral::SigmoidPolynomial poly = spectral::rgbToSigmoid(rgb);
        rgb_[next_] = rgb, poly_[next_] = poly;
        next_ = (next_ + 1) % kEntries;
        size_ = std::min(size_ + 1, kEntries);
        return poly;
    }

  private:
    static constexpr int kEntries = 8;
    Vec3f rgb_[kEntries];
    spectral::SigmoidPolynomial poly_[kEntries];
    int size_ = 0, next_ = 0;
};

class SpectralContext {
  public:
    using Colour = spectral::SampledSpectrum;
    static constexpr bool kSpectral = true;
    static constexpr int kChannels = spectral::kSpectrumSamples;
    // Unset, to be assigned (an array of a batch's paths' contexts).
    SpectralContext() = default;
    // `cache` outlives the context; the illuminant is sampled once per path.
    SpectralContext(const spectral::SampledWavelengths& lambda, SigmoidCache& cache)
        : lambda_(lambda),
          illuminant_(spectral::linearSrgb().illuminant->sample(lambda)),
          cache_(&cache) {}

    // albedoSpectrum, unboundedSpectrum and illuminantSpectrum of
    // rgb_spectrum.h, the same arithmetic, through the cache.
    Colour reflectance(Vec3f rgb) const { return sampled((*cache_)(rgb)); }
    Colour unbounded(Vec3f rgb) const {
        const float m = std::max(maxComponent(rgb), 0.0f);
        if (m == 0) return Colour(0.0f);
        const float scale = 2 * m;
        return scale * sampled((*cache_)(rgb / scale));
    }
    Colour emission(Vec3f rgb) const { return unbounded(rgb) * illuminant_; }
    Colour f(const Bsdf& bsdf, Vec3f wo, Vec3f wi) const {
        return spectralBsdfF(bsdf, wo, wi, *this);
    }
    Colour sampledF(const Bsdf& bsdf, Vec3f wo, const BsdfSample& s) const {
        return spectralSampledF(bsdf, wo, s, *this);
    }
    Colour layeredF(const LayeredBsdf& l, Vec3f wo, Vec3f wi, WalkNumbers& r) const {
        return spectralLayeredF(l, wo, wi, r, *this);
    }
    std::optional<LayeredSampleOf<Colour>> layeredSample(const LayeredBsdf& l, Vec3f wo, float uc,
                                                         Vec2f u, WalkNumbers& r) const {
        return spectralLayeredSample(l, wo, uc, u, r, *this);
    }
    Vec3f toRgb(const Colour& L) const { return spectral::spectrumToLinearSrgb(L, lambda_); }
    const spectral::SampledWavelengths& wavelengths() const { return lambda_; }

  private:
    Colour sampled(const spectral::SigmoidPolynomial& poly) const {
        return spectral::sampleSigmoid(poly, lambda_);
    }
    spectral::SampledWavelengths lambda_;
    Colour illuminant_;  // the colour space's, D65, at lambda_
    SigmoidCache* cache_ = nullptr;
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
