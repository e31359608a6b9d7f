// From the radiance a path carries at its wavelengths to the film's colour:
// the Monte Carlo estimate of XYZ = ∫ L(λ) (x̄, ȳ, z̄)(λ) dλ / ∫ ȳ (pbrt-v4's
// SampledSpectrum::ToXYZ, PBRT 4th ed. §4.6.1): each lane's L x̄ / p(λ),
// averaged over the lanes, over CIE_Y_integral. Dividing by ∫ ȳ makes an
// emitter of luminance 1 (a normalised illuminant) come out with Y = 1.
#pragma once

#include "core/math.h"
#include "spectral/sampled_wavelengths.h"

namespace pathlab::spectral {

Vec3f spectrumToXyz(const SampledSpectrum& radiance, const SampledWavelengths& w);
// spectrumToXyz through linear sRGB's XYZ → RGB matrix (colour_space.h), D65
// white: illuminantSpectrum(rgb) comes back as rgb in expectation.
Vec3f spectrumToLinearSrgb(const SampledSpectrum& radiance, const SampledWavelengths& w);

}  // namespace pathlab::spectral
