// The colour of a blackbody emitter ("blackbody" T in pbrt-v4 files) as
// linear sRGB, normalised as pbrt-v4 normalises a light's spectrum: divided by
// its photometric value, so that the light has luminance Y = 1 (times its
// scale) whatever its temperature, as an RGB light (1, 1, 1) has.
#pragma once

#include "core/math.h"

namespace pathlab {

struct Xyz {
    double x = 0, y = 0, z = 0;
};

// Planck's law: spectral radiance of a blackbody at `kelvin`, wavelength in nm
// (W·sr⁻¹·m⁻³; only ratios matter here).
double planck(double nanometres, double kelvin);

// CIE 1931 2° colour matching functions by the multi-lobe piecewise Gaussian
// fit of Wyman, Sloan & Shirley 2013 ("Simple Analytic Approximations to the
// CIE XYZ Color Matching Functions", JCGT 2(2), eq. 2).
Xyz cieXyzFit(double nanometres);

// CIE XYZ of the blackbody at `kelvin`, integrated over 360–830 nm, scaled to Y = 1.
Xyz blackbodyXyz(double kelvin);

// blackbodyXyz in linear sRGB (IEC 61966-2-1's XYZ → RGB matrix, D65 white):
// pbrt-v4's default colour space. Channels may be slightly negative for very
// hot or cold temperatures outside the gamut; they are clamped to 0.
Vec3f blackbodyRgb(double kelvin);

}  // namespace pathlab
