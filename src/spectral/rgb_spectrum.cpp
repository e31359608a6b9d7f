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
    const Vec3f clamped(std::clamp(rgb.x, 0.f, 1.f), std::clamp(rgb.y, 0.f, 1.f),
                        std::clamp(rgb.z, 0.f, 1.f));
    return defaultRgbToSpectrumTable().lookup(clamped);
}

namespace {

SampledSpectrum sampleSigmoid(const SigmoidPolynomial& s, const SampledWavelengths& w) {
    SampledSpectrum out;
    for (int i = 0; i < kSpectrumSamples; ++i) out[i] = s(w.lambda(i));
    return out;
}

}  // namespace

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
