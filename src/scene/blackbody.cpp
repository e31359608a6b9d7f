#include "scene/blackbody.h"

#include <algorithm>
#include <cmath>

namespace pathlab {

double planck(double nanometres, double kelvin) {
    // c = speed of light, h = Planck's constant, kB = Boltzmann's (CODATA 2018, exact).
    constexpr double c = 299792458.0, h = 6.62607015e-34, kB = 1.380649e-23;
    const double l = nanometres * 1e-9;
    return 2 * h * c * c / (l * l * l * l * l * (std::exp(h * c / (l * kB * kelvin)) - 1));
}

namespace {

// The fit's piecewise Gaussian: width s1 below the mean, s2 above.
double lobe(double x, double mean, double s1, double s2) {
    const double t = (x - mean) / (x < mean ? s1 : s2);
    return std::exp(-0.5 * t * t);
}

}  // namespace

Xyz cieXyzFit(double l) {
    return {1.056 * lobe(l, 599.8, 37.9, 31.0) + 0.362 * lobe(l, 442.0, 16.0, 26.7) -
                0.065 * lobe(l, 501.1, 20.4, 26.2),
            0.821 * lobe(l, 568.8, 46.9, 40.5) + 0.286 * lobe(l, 530.9, 16.3, 31.1),
            1.217 * lobe(l, 437.0, 11.8, 36.0) + 0.681 * lobe(l, 459.0, 26.0, 13.8)};
}

Xyz blackbodyXyz(double kelvin) {
    // pbrt-v4 integrates its spectra at 1 nm steps over 360–830 nm.
    Xyz sum;
    for (int l = 360; l <= 830; ++l) {
        const double b = planck(l, kelvin);
        const Xyz m = cieXyzFit(l);
        sum.x += b * m.x, sum.y += b * m.y, sum.z += b * m.z;
    }
    return {sum.x / sum.y, 1.0, sum.z / sum.y};
}

Vec3f blackbodyRgb(double kelvin) {
    const Xyz c = blackbodyXyz(kelvin);
    const double r = 3.2404542 * c.x - 1.5371385 * c.y - 0.4985314 * c.z;
    const double g = -0.9692660 * c.x + 1.8760108 * c.y + 0.0415560 * c.z;
    const double b = 0.0556434 * c.x - 0.2040259 * c.y + 1.0572252 * c.z;
    return {float(std::max(r, 0.0)), float(std::max(g, 0.0)), float(std::max(b, 0.0))};
}

}  // namespace pathlab
