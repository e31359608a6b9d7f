// Spectra of RGB colours (Jakob & Hanika 2019, "A Low-Dimensional Function
// Space for Efficient Spectral Upsampling", Computer Graphics Forum 38(2)):
// a reflectance is the sigmoid of a quadratic polynomial in λ,
//   s(λ) = S(c₀λ² + c₁λ + c₂),  S(x) = ½ + x / (2√(1 + x²))   (paper eq. 3–4),
// bounded in [0, 1] and smooth, with coefficients chosen so that s under the
// colour space's illuminant has the colour's XYZ. The coefficients come from
// a table made by pathlab's own optimiser (rgb_spectrum_table.h).
#pragma once

#include <immintrin.h>

#include <cstring>

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

// The polynomial at a path's four wavelengths: operator() lane by lane, the
// same IEEE operations in the same order, four at a time (SSE's square root
// and division round as the scalar ones do), so the same bits. A path meets a
// reflectance at every vertex; scalar, the four dependent square roots and
// divisions were a latency chain.
inline SampledSpectrum sampleSigmoid(const SigmoidPolynomial& s, const SampledWavelengths& w) {
    static_assert(kSpectrumSamples == 4, "one SSE register of wavelengths");
    using F = float __attribute__((vector_size(16)));
    using I = int __attribute__((vector_size(16)));
    const F lambda{w.lambda(0), w.lambda(1), w.lambda(2), w.lambda(3)};
    const F x = (s.c0 * lambda + s.c1) * lambda + s.c2;
    const F value = 0.5f + x / (2 * F(_mm_sqrt_ps(__m128(1 + x * x))));
    const F infinity = F{} + __builtin_inff();
    const I isInf = (x == infinity) | (x == -infinity);
    const F limit = x > 0 ? F{} + 1.0f : F{};  // S(±∞)
    const F out = isInf ? limit : value;
    SampledSpectrum spectrum;
    std::memcpy(spectrum.v.data(), &out, sizeof out);
    return spectrum;
}

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
