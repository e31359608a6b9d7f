#include "spectral/colour_space.h"

#include <cmath>

#include "spectral/cie_functions.h"
#include "spectral/named_illuminants.h"

namespace pathlab::spectral {

Vec3d multiply(const Mat3d& m, const Vec3d& v) {
    Vec3d r{};
    for (int i = 0; i < 3; ++i) r[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
    return r;
}

Mat3d multiply(const Mat3d& a, const Mat3d& b) {
    Mat3d r{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            r[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
    return r;
}

Mat3d inverse(const Mat3d& m) {
    // The adjugate over the determinant (3×3, well conditioned here).
    Mat3d r{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const int i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
            r[i][j] = m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1];
        }
    const double det = m[0][0] * r[0][0] + m[0][1] * r[1][0] + m[0][2] * r[2][0];
    for (auto& row : r)
        for (double& x : row) x /= det;
    return r;
}

Vec3d spectrumXyz(const PiecewiseLinearSpectrum& s) {
    const Quadrature& q = fineQuadrature();
    Vec3d xyz{};
    for (size_t k = 0; k < q.lambda.size(); ++k) {
        const double l = q.lambda[k], ws = q.weight[k] * s(l);
        xyz[0] += ws * cieX(l);
        xyz[1] += ws * cieY(l);
        xyz[2] += ws * cieZ(l);
    }
    for (double& c : xyz) c /= cieYIntegral();
    return xyz;
}

RgbColourSpace makeRgbColourSpace(std::array<double, 2> r, std::array<double, 2> g,
                                  std::array<double, 2> b,
                                  const PiecewiseLinearSpectrum& illuminant) {
    RgbColourSpace cs;
    cs.illuminant = &illuminant;
    cs.whiteXyz = spectrumXyz(illuminant);
    // Columns: the primaries' XYZ at Y = 1, then scaled so that (1,1,1) is white.
    auto xyzOf = [](std::array<double, 2> xy) {
        return Vec3d{xy[0] / xy[1], 1.0, (1 - xy[0] - xy[1]) / xy[1]};
    };
    const Vec3d pr = xyzOf(r), pg = xyzOf(g), pb = xyzOf(b);
    const Mat3d primaries{{{pr[0], pg[0], pb[0]}, {pr[1], pg[1], pb[1]}, {pr[2], pg[2], pb[2]}}};
    const Vec3d scale = multiply(inverse(primaries), cs.whiteXyz);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) cs.rgbToXyz[i][j] = primaries[i][j] * scale[j];
    cs.xyzToRgb = inverse(cs.rgbToXyz);
    return cs;
}

const RgbColourSpace& linearSrgb() {
    static const RgbColourSpace cs = makeRgbColourSpace({0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06},
                                                        *namedIlluminant("stdillum-D65"));
    return cs;
}

Vec3d xyzToLab(const Vec3d& xyz, const Vec3d& whiteXyz) {
    constexpr double delta = 6.0 / 29.0;
    auto f = [&](double t) {
        return t > delta * delta * delta ? std::cbrt(t) : t / (3 * delta * delta) + 4.0 / 29.0;
    };
    const double fx = f(xyz[0] / whiteXyz[0]), fy = f(xyz[1] / whiteXyz[1]),
                 fz = f(xyz[2] / whiteXyz[2]);
    return {116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)};
}

}  // namespace pathlab::spectral
