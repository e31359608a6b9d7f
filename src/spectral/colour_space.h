// Linear sRGB as pbrt-v4's RGBColorSpace builds it: the primaries of
// IEC 61966-2-1 (ITU-R BT.709) and the white of the D65 *spectrum* (its XYZ
// through the tabulated CIE functions), so that the spectrum of RGB white —
// the illuminant — maps back to exactly (1, 1, 1).
#pragma once

#include <array>

#include "spectral/piecewise_linear_spectrum.h"

namespace pathlab::spectral {

using Vec3d = std::array<double, 3>;
using Mat3d = std::array<Vec3d, 3>;  // rows

Vec3d multiply(const Mat3d& m, const Vec3d& v);
Mat3d multiply(const Mat3d& a, const Mat3d& b);
Mat3d inverse(const Mat3d& m);  // m must be invertible

struct RgbColourSpace {
    Mat3d rgbToXyz, xyzToRgb;
    Vec3d whiteXyz;                             // of the illuminant, Y = 1
    const PiecewiseLinearSpectrum* illuminant;  // normalised to Y = 1
};

// The colour space whose primaries have chromaticities r, g, b and whose
// white is `illuminant`'s (SMPTE RP 177-1993's derivation of the matrix).
RgbColourSpace makeRgbColourSpace(std::array<double, 2> r, std::array<double, 2> g,
                                  std::array<double, 2> b,
                                  const PiecewiseLinearSpectrum& illuminant);

// Linear sRGB with pbrt-v4's "stdillum-D65".
const RgbColourSpace& linearSrgb();

// XYZ of a spectrum s(λ) seen as emission: ∫ s x̄, ∫ s ȳ, ∫ s z̄ over
// 360–830 nm, divided by ∫ ȳ (pbrt-v4's SpectrumToXYZ).
Vec3d spectrumXyz(const PiecewiseLinearSpectrum& s);

// CIE 1976 L*a*b* of `xyz` relative to `whiteXyz` (CIE 15:2004 §8.2.1).
Vec3d xyzToLab(const Vec3d& xyz, const Vec3d& whiteXyz);

}  // namespace pathlab::spectral
