// A spectral quantity at the wavelengths one path carries (pbrt-v4's
// SampledSpectrum, Pharr, Jakob & Humphreys, "Physically Based Rendering",
// 4th ed., §4.5.4): one value per wavelength of a SampledWavelengths, all
// arithmetic elementwise. The spectral counterpart of the RGB Vec3f.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

namespace pathlab::spectral {

// Wavelengths carried per path (pbrt-v4's NSpectrumSamples).
inline constexpr int kSpectrumSamples = 4;
// The range over which wavelengths are sampled and spectra tabulated, in nm:
// that of the CIE 1931 colour-matching functions (CIE 15:2004).
inline constexpr float kLambdaMin = 360.f, kLambdaMax = 830.f;

struct SampledSpectrum {
    std::array<float, kSpectrumSamples> v{};

    constexpr SampledSpectrum() = default;
    // Every lane set to `c`.
    constexpr explicit SampledSpectrum(float c) { v.fill(c); }

    constexpr float& operator[](int i) { return v[size_t(i)]; }
    constexpr float operator[](int i) const { return v[size_t(i)]; }

    template <typename Op>
    constexpr SampledSpectrum& apply(const SampledSpectrum& o, Op op) {
        for (int i = 0; i < kSpectrumSamples; ++i) v[size_t(i)] = op(v[size_t(i)], o.v[size_t(i)]);
        return *this;
    }
    constexpr SampledSpectrum& operator+=(const SampledSpectrum& o) {
        return apply(o, [](float a, float b) { return a + b; });
    }
    constexpr SampledSpectrum& operator-=(const SampledSpectrum& o) {
        return apply(o, [](float a, float b) { return a - b; });
    }
    constexpr SampledSpectrum& operator*=(const SampledSpectrum& o) {
        return apply(o, [](float a, float b) { return a * b; });
    }
    // Division by a zero lane gives 0 in that lane, not inf or NaN: a lane
    // whose pdf is 0 (a terminated secondary wavelength) contributes nothing.
    constexpr SampledSpectrum& operator/=(const SampledSpectrum& o) {
        return apply(o, [](float a, float b) { return b != 0 ? a / b : 0.f; });
    }
    constexpr SampledSpectrum& operator+=(float s) { return *this += SampledSpectrum(s); }
    constexpr SampledSpectrum& operator-=(float s) { return *this -= SampledSpectrum(s); }
    constexpr SampledSpectrum& operator*=(float s) { return *this *= SampledSpectrum(s); }
    constexpr SampledSpectrum& operator/=(float s) { return *this /= SampledSpectrum(s); }
    constexpr SampledSpectrum operator-() const { return SampledSpectrum(0.f) -= *this; }

    constexpr float maxComponent() const { return *std::max_element(v.begin(), v.end()); }
    constexpr float minComponent() const { return *std::min_element(v.begin(), v.end()); }
    constexpr float average() const {
        float sum = 0;
        for (float x : v) sum += x;
        return sum / kSpectrumSamples;
    }
    constexpr bool isBlack() const {
        return std::all_of(v.begin(), v.end(), [](float x) { return x == 0; });
    }
    bool hasNaN() const {
        return std::any_of(v.begin(), v.end(), [](float x) { return std::isnan(x); });
    }
};

#define PATHLAB_SPECTRUM_BINARY(op)                                                      \
    constexpr SampledSpectrum operator op(SampledSpectrum a, const SampledSpectrum& b) { \
        return a op## = b;                                                               \
    }                                                                                    \
    constexpr SampledSpectrum operator op(SampledSpectrum a, float s) {                  \
        return a op## = s;                                                               \
    }                                                                                    \
    constexpr SampledSpectrum operator op(float s, const SampledSpectrum& b) {           \
        return SampledSpectrum(s) op## = b;                                              \
    }
PATHLAB_SPECTRUM_BINARY(+)
PATHLAB_SPECTRUM_BINARY(-)
PATHLAB_SPECTRUM_BINARY(*)
PATHLAB_SPECTRUM_BINARY(/)
#undef PATHLAB_SPECTRUM_BINARY

constexpr bool operator==(const SampledSpectrum& a, const SampledSpectrum& b) {
    return a.v == b.v;
}

// Elementwise functions the integrator needs.
inline SampledSpectrum exp(SampledSpectrum s) {
    for (float& x : s.v) x = std::exp(x);
    return s;
}
inline SampledSpectrum sqrt(SampledSpectrum s) {
    for (float& x : s.v) x = std::sqrt(x);
    return s;
}
constexpr SampledSpectrum clampZero(SampledSpectrum s) {
    for (float& x : s.v) x = std::max(x, 0.f);
    return s;
}

}  // namespace pathlab::spectral
