// Spectra of RGB colours (Jakob & Hanika 2019, "A Low-Dimensional Function
// Space for Efficient Spectral Upsampling", Computer Graphics Forum 38(2)):
// a reflectance is the sigmoid of a quadratic polynomial in λ,
//   s(λ) = S(c₀λ² + c₁λ + c₂),  S(x) = ½ + x / (2√(1 + x²))   (paper eq. 3–4),
// bounded in [0, 1] and smooth, with coefficients chosen so that s under the
// colour space's illuminant has the colour's XYZ. The coefficients come from
// a table made by pathlab's own optimiser (rgb_spectrum_table.h).
#pragma once

#include "core/math.h"
#include "spectral/sampled_wavelengths.h"

namespace pathlab::spectral {

struct SigmoidPolynomial {
    float c0 = 0, c1 = 0, c2 = 0;  // of λ², λ, 1 with λ in nm

    static float sigmoid(float x) {
        if (std::isinf(x)) return x > 0 ? 1.f : 0.f;
        return 0.5f + x / (2 * std::sqrt(1 + x * x));
    }
    float operator()(float lambdaNm) const { return sigmoid((c0 * lambdaNm + c1) * lambdaNm + c2); }
    // The largest value over [kLambdaMin, kLambdaMax]: at an end or at the
    // polynomial's vertex (S is increasing).
    float maxValue() const;
};

// The sigmoid polynomial of a linear sRGB reflectance; rgb clamped to [0,1]³.
SigmoidPolynomial rgbToSigmoid(Vec3f rgb);

// Reflectance (pbrt-v4's RGBAlbedoSpectrum): values in [0, 1].
SampledSpectrum albedoSpectrum(Vec3f rgb, const SampledWavelengths& w);
// Any rgb ≥ 0 (pbrt-v4's RGBUnboundedSpectrum): m = max component, scale 2m,
// the sigmoid of rgb / (2m) (a colour of maximum ½, so with room for the
// optimiser both ways) times 2m.
SampledSpectrum unboundedSpectrum(Vec3f rgb, const SampledWavelengths& w);
// Emission (pbrt-v4's RGBIlluminantSpectrum): unboundedSpectrum times linear
// sRGB's illuminant, D65 normalised to Y = 1. White (1,1,1) is D65 itself.
SampledSpectrum illuminantSpectrum(Vec3f rgb, const SampledWavelengths& w);

}  // namespace pathlab::spectral
