#include "spectral/rgb_spectrum.h"

#include "spectral/colour_space.h"
#include "spectral/rgb_spectrum_table.h"

namespace pathlab::spectral {

float SigmoidPolynomial::maxValue() const {
    float m = std::max((*this)(kLambdaMin), (*this)(kLambdaMax));
    const float vertex = c0 != 0 ? -c1 / (2 * c0) : kLambdaMin;
    if (vertex > kLambdaMin && vertex < kLambdaMax) m = std::max(m, (*this)(vertex));
    return m;
}

SigmoidPolynomial rgbToSigmoid(Vec3f rgb) {
    // To [0, 1], NaN to 0 (the table's indices are integers made from these).
    auto unit = [](float v) { return v > 0 ? std::min(v, 1.f) : 0.f; };
    const Vec3f clamped(unit(rgb.x), unit(rgb.y), unit(rgb.z));
    return defaultRgbToSpectrumTable().lookup(clamped);
}

SampledSpectrum albedoSpectrum(Vec3f rgb, const SampledWavelengths& w) {
    return sampleSigmoid(rgbToSigmoid(rgb), w);
}

SampledSpectrum unboundedSpectrum(Vec3f rgb, const SampledWavelengths& w) {
    const float m = std::max(maxComponent(rgb), 0.f);
    if (m == 0) return SampledSpectrum(0.f);
    const float scale = 2 * m;
    return scale * sampleSigmoid(rgbToSigmoid(rgb / scale), w);
}

SampledSpectrum illuminantSpectrum(Vec3f rgb, const SampledWavelengths& w) {
    return unboundedSpectrum(rgb, w) * linearSrgb().illuminant->sample(w);
}

}  // namespace pathlab::spectral
