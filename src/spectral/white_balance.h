// The white balance of pbrt-v4's "cie1931" pixel sensor (pbrt-v4 film.h,
// PixelSensor; PBRT 4th ed. §5.4.2): Film "whitebalance" T adapts the image
// from the white of a CIE daylight illuminant of temperature T to the colour
// space's white, by a von Kries scaling in the Bradford cone space (pbrt-v4's
// WhiteBalance, util/color.h). The sensor's RGB is then XYZ, so the film's
// output is xyzToRgb · WB · XYZ per sample; a linear-sRGB sample becomes that
// through xyzToRgb · WB · rgbToXyz (whiteBalanceRgbMatrix), which is how
// pathlab applies it in both RGB and spectral mode.
#pragma once

#include <array>

#include "core/math.h"
#include "spectral/colour_space.h"

namespace pathlab::spectral {

using Vec2d = std::array<double, 2>;

// XYZ → LMS cone responses of the Bradford transform (Lam 1985, as tabulated
// by Lindbloom and in pbrt-v4's LMSFromXYZ).
const Mat3d& bradfordLmsFromXyz();

// The chromaticity (x, y) of an XYZ triple.
Vec2d chromaticity(const Vec3d& xyz);

// The XYZ → XYZ matrix that maps a colour seen under a white of chromaticity
// `sourceWhite` to the one seen under `targetWhite` (both at Y = 1):
// M⁻¹ · diag(LMS_target / LMS_source) · M, M = bradfordLmsFromXyz().
// pbrt-v4 multiplies by a 6-digit rounding of M⁻¹; this is the exact inverse.
Mat3d bradfordWhiteBalance(Vec2d sourceWhite, Vec2d targetWhite);

// pbrt-v4's Spectra::D: the CIE daylight illuminant S0 + M1·S1 + M2·S2 (CIE
// 15:2004 §3.1, the chromaticity of the daylight locus from the correlated
// colour temperature) of temperature `kelvin` × 1.4388/1.4380 (the D series
// was defined with the older second radiation constant), or, below 4000 K,
// where the series is not defined, a blackbody of that temperature. Unscaled
// (only its chromaticity is used). kelvin > 0.
PiecewiseLinearSpectrum daylightIlluminant(double kelvin);

// The matrix on linear RGB of `cs` that white-balances a sensor for
// `kelvin` (Film "whitebalance"): cs.xyzToRgb · WB · cs.rgbToXyz with WB
// from the chromaticity of daylightIlluminant(kelvin) to that of cs's white.
Mat3d whiteBalanceRgbMatrix(double kelvin, const RgbColourSpace& cs);

// That matrix for linear sRGB in float, ready to multiply every sample by;
// identity() when kelvin is 0 (no white balance, pbrt-v4's default).
struct RgbBalance {
    bool identity = true;
    float m[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    Vec3f operator()(Vec3f c) const {
        return {m[0][0] * c.x + m[0][1] * c.y + m[0][2] * c.z,
                m[1][0] * c.x + m[1][1] * c.y + m[1][2] * c.z,
                m[2][0] * c.x + m[2][1] * c.y + m[2][2] * c.z};
    }
};
// Throws InputError unless kelvin is 0 or a finite positive temperature.
RgbBalance linearSrgbWhiteBalance(double kelvin);

}  // namespace pathlab::spectral
