#include "spectral/white_balance.h"

#include <cmath>
#include <string>

#include "core/error.h"
#include "spectral/blackbody_spectrum.h"
#include "spectral/cie_data.h"

namespace pathlab::spectral {
namespace {

// XYZ at Y = 1 of chromaticity (x, y).
Vec3d xyzOfChromaticity(Vec2d xy) {
    return {xy[0] / xy[1], 1.0, (1 - xy[0] - xy[1]) / xy[1]};
}

// The daylight locus (CIE 15:2004 eqs. 3.3–3.4): x_D from the correlated
// colour temperature, in two ranges, and y_D from x_D.
Vec2d daylightChromaticity(double cct) {
    const double t = cct, t2 = t * t, t3 = t2 * t;
    const double x = cct <= 7000 ? -4.607e9 / t3 + 2.9678e6 / t2 + 0.09911e3 / t + 0.244063
                                 : -2.0064e9 / t3 + 1.9018e6 / t2 + 0.24748e3 / t + 0.23704;
    return {x, -3 * x * x + 2.870 * x - 0.275};
}

}  // namespace

const Mat3d& bradfordLmsFromXyz() {
    static const Mat3d m{{{0.8951, 0.2664, -0.1614},  //
                          {-0.7502, 1.7135, 0.0367},
                          {0.0389, -0.0685, 1.0296}}};
    return m;
}

Vec2d chromaticity(const Vec3d& xyz) {
    const double sum = xyz[0] + xyz[1] + xyz[2];
    return {xyz[0] / sum, xyz[1] / sum};
}

Mat3d bradfordWhiteBalance(Vec2d sourceWhite, Vec2d targetWhite) {
    const Mat3d& lmsFromXyz = bradfordLmsFromXyz();
    const Vec3d source = multiply(lmsFromXyz, xyzOfChromaticity(sourceWhite));
    const Vec3d target = multiply(lmsFromXyz, xyzOfChromaticity(targetWhite));
    Mat3d scaled = lmsFromXyz;  // diag(target / source) · M
    for (int i = 0; i < 3; ++i)
        for (double& v : scaled[size_t(i)]) v *= target[size_t(i)] / source[size_t(i)];
    return multiply(inverse(lmsFromXyz), scaled);
}

PiecewiseLinearSpectrum daylightIlluminant(double kelvin) {
    const double cct = kelvin * 1.4388 / 1.4380;
    std::vector<double> lambda, values;
    if (cct < 4000) {
        // Sampled every nanometre, as pbrt-v4's DenselySampledSpectrum holds it.
        const BlackbodySpectrum blackbody(cct);
        for (int l = int(kLambdaMin); l <= int(kLambdaMax); ++l)
            lambda.push_back(l), values.push_back(blackbody(l));
        return PiecewiseLinearSpectrum(std::move(lambda), std::move(values));
    }
    // CIE 15:2004 eq. 3.5: the weights of S1 and S2 for chromaticity (x, y).
    const auto [x, y] = daylightChromaticity(cct);
    const double m = 0.0241 + 0.2562 * x - 0.7341 * y;
    const double m1 = (-1.3515 - 1.7703 * x + 5.9114 * y) / m;
    const double m2 = (0.0300 - 31.4424 * x + 30.0717 * y) / m;
    for (int i = 0; i < cie_data::kDaylightCount; ++i) {
        lambda.push_back(cie_data::kDaylightFirst + i * cie_data::kDaylightStep);
        values.push_back(0.01 * (cie_data::kDaylightS0[i] + m1 * cie_data::kDaylightS1[i] +
                                 m2 * cie_data::kDaylightS2[i]));
    }
    return PiecewiseLinearSpectrum(std::move(lambda), std::move(values));
}

Mat3d whiteBalanceRgbMatrix(double kelvin, const RgbColourSpace& cs) {
    const Vec2d source = chromaticity(spectrumXyz(daylightIlluminant(kelvin)));
    const Mat3d balance = bradfordWhiteBalance(source, chromaticity(cs.whiteXyz));
    return multiply(cs.xyzToRgb, multiply(balance, cs.rgbToXyz));
}

RgbBalance linearSrgbWhiteBalance(double kelvin) {
    RgbBalance b;
    if (kelvin == 0) return b;
    if (!(std::isfinite(kelvin) && kelvin > 0))
        throw InputError("white balance must be 0 (none) or a temperature in kelvin, got " +
                         std::to_string(kelvin));
    const Mat3d m = whiteBalanceRgbMatrix(kelvin, linearSrgb());
    b.identity = false;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            b.m[i][j] = float(m[size_t(i)][size_t(j)]);
            // So cold a blackbody has no visible light to take a white from.
            if (!std::isfinite(b.m[i][j]))
                throw InputError("white balance " + std::to_string(kelvin) +
                                 " K is too cold to have a white");
        }
    return b;
}

}  // namespace pathlab::spectral
