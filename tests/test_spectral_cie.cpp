// The CIE data spectral mode reads from colord-data: the colour-matching
// functions at published values (CIE 15:2004 table T.4) and interpolated
// linearly between them, the standard illuminants at unit luminance with their
// published chromaticities, and linear sRGB built on D65 with the primaries
// and matrix of IEC 61966-2-1.
#include <gtest/gtest.h>

#include "core/error.h"
#include "spectral/cie_functions.h"
#include "spectral/colour_space.h"
#include "spectral/named_illuminants.h"

namespace pathlab::spectral {
namespace {

TEST(SpectralCie, MatchingFunctionsHaveTheirPublishedValues) {
    // CIE 15:2004, table T.4 (CIE 1931 standard colorimetric observer).
    EXPECT_NEAR(cieY(555), 1.0, 1e-9);
    EXPECT_NEAR(cieX(600), 1.0622, 1e-9);
    EXPECT_NEAR(cieZ(450), 1.77211, 1e-9);
    EXPECT_NEAR(cieX(445), 0.34806, 1e-9);
    EXPECT_NEAR(cieY(700), 0.004102, 1e-9);
    // Linear between the 5-nm samples, 0 outside the tabulated range.
    EXPECT_NEAR(cieY(557.5), 0.5 * (1.0 + 0.995), 1e-9);
    EXPECT_EQ(cieX(359), 0);
    EXPECT_EQ(cieZ(831), 0);
}

TEST(SpectralCie, YIntegralIsCloseToPbrtsOneNanometreSum) {
    // pbrt-v4's CIE_Y_integral (its 1-nm table summed) is 106.856895; the
    // 5-nm table's trapezoid differs only by interpolation.
    EXPECT_NEAR(cieYIntegral(), 106.856895, 0.1);
    // The fine quadrature integrates the interpolated table exactly.
    const Quadrature& q = fineQuadrature();
    double y = 0;
    for (size_t k = 0; k < q.lambda.size(); ++k) y += q.weight[k] * cieY(q.lambda[k]);
    EXPECT_NEAR(y, cieYIntegral(), 1e-9);
}

std::array<double, 2> chromaticity(const Vec3d& xyz) {
    const double sum = xyz[0] + xyz[1] + xyz[2];
    return {xyz[0] / sum, xyz[1] / sum};
}

TEST(SpectralCie, IlluminantsHaveUnitLuminanceAndTheirChromaticities) {
    // Chromaticities of CIE 15:2004 table T.3 (2° observer).
    const struct {
        const char* name;
        double x, y;
    } published[] = {{"stdillum-A", 0.44757, 0.40745},
                     {"stdillum-D50", 0.34567, 0.35850},
                     {"stdillum-D65", 0.31272, 0.32903},
                     {"stdillum-F2", 0.37208, 0.37529},
                     {"stdillum-F11", 0.38052, 0.37713}};
    for (const auto& p : published) {
        const PiecewiseLinearSpectrum* s = namedIlluminant(p.name);
        ASSERT_NE(s, nullptr) << p.name;
        EXPECT_NEAR(s->luminance(), 1.0, 1e-9) << p.name;
        const auto xy = chromaticity(spectrumXyz(*s));
        EXPECT_NEAR(xy[0], p.x, 5e-4) << p.name;
        EXPECT_NEAR(xy[1], p.y, 5e-4) << p.name;
    }
    for (int f = 1; f <= 12; ++f)
        EXPECT_NE(namedIlluminant("stdillum-F" + std::to_string(f)), nullptr) << f;
    EXPECT_EQ(namedIlluminant("stdillum-D66"), nullptr);
    EXPECT_NE(namedIlluminantList().find("stdillum-D65"), std::string::npos);
}

TEST(SpectralCie, LinearSrgbMatrixIsTheStandardOne) {
    // IEC 61966-2-1's XYZ → linear sRGB matrix (4 decimals); ours has the
    // white of the D65 table, which rounds the same way.
    const double standard[3][3] = {
        {3.2406, -1.5372, -0.4986}, {-0.9689, 1.8758, 0.0415}, {0.0557, -0.2040, 1.0570}};
    const RgbColourSpace& cs = linearSrgb();
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) EXPECT_NEAR(cs.xyzToRgb[i][j], standard[i][j], 2e-3);
    // The illuminant's XYZ is white, (1, 1, 1), exactly.
    const Vec3d white = multiply(cs.xyzToRgb, cs.whiteXyz);
    for (double c : white) EXPECT_NEAR(c, 1.0, 1e-12);
    const Mat3d identity = multiply(cs.xyzToRgb, cs.rgbToXyz);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) EXPECT_NEAR(identity[i][j], i == j ? 1 : 0, 1e-12);
}

TEST(SpectralCie, TabulatedSpectraInterpolateAndRejectBadInput) {
    const PiecewiseLinearSpectrum s = PiecewiseLinearSpectrum::fromInterleaved({400, 1, 500, 3});
    EXPECT_DOUBLE_EQ(s(450), 2);
    EXPECT_DOUBLE_EQ(s(400), 1);
    EXPECT_DOUBLE_EQ(s(500), 3);
    EXPECT_EQ(s(399), 0);
    EXPECT_EQ(s(501), 0);
    EXPECT_THROW(PiecewiseLinearSpectrum::fromInterleaved({400, 1, 500}), InputError);
    EXPECT_THROW(PiecewiseLinearSpectrum::fromInterleaved({500, 1, 400, 2}), InputError);
    EXPECT_THROW(PiecewiseLinearSpectrum({}, {}), InputError);
}

}  // namespace
}  // namespace pathlab::spectral
