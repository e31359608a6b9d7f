#include "spectral/film_xyz.h"

#include "spectral/cie_functions.h"
#include "spectral/colour_space.h"

namespace pathlab::spectral {

Vec3f spectrumToXyz(const SampledSpectrum& radiance, const SampledWavelengths& w) {
    static const float invYIntegral = float(1 / cieYIntegral());
    Vec3f xyz;
    for (int i = 0; i < kSpectrumSamples; ++i) {
        if (w.pdf(i) == 0) continue;  // a terminated secondary wavelength
        xyz += cieXyzMatching(w.lambda(i)) * (radiance[i] / w.pdf(i));
    }
    return xyz * (invYIntegral / kSpectrumSamples);
}

Vec3f spectrumToLinearSrgb(const SampledSpectrum& radiance, const SampledWavelengths& w) {
    static const auto m = [] {
        const Mat3d& d = linearSrgb().xyzToRgb;
        std::array<Vec3f, 3> rows;
        for (int i = 0; i < 3; ++i)
            rows[size_t(i)] = {float(d[i][0]), float(d[i][1]), float(d[i][2])};
        return rows;
    }();
    const Vec3f xyz = spectrumToXyz(radiance, w);
    return {dot(m[0], xyz), dot(m[1], xyz), dot(m[2], xyz)};
}

}  // namespace pathlab::spectral
