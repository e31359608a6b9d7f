#include "spectral/sampled_wavelengths.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace pathlab::spectral {
namespace {

// The density's shape, sech²(a (λ − centre)): its antiderivative is
// tanh(a (λ − centre)) / a, which gives the CDF and its inverse in closed form.
constexpr double kVisibleA = 0.0072, kVisibleCentre = 538.0;

double tanhAt(double lambdaNm) {
    return std::tanh(kVisibleA * (lambdaNm - kVisibleCentre));
}

struct VisibleBounds {
    double tanhMin, tanhMax;
};
const VisibleBounds& visibleBounds() {
    static const VisibleBounds b{tanhAt(kLambdaMin), tanhAt(kLambdaMax)};
    return b;
}

// u_i = (u + i/N) mod 1: N strata of [0,1) from one sample.
float stratum(float u, int i) {
    float ui = u + float(i) / kSpectrumSamples;
    if (ui >= 1.f) ui -= 1.f;
    return ui;
}

}  // namespace

WavelengthSampling parseWavelengthSampling(const std::string& text, const std::string& option) {
    if (text == "visible") return WavelengthSampling::Visible;
    if (text == "hero") return WavelengthSampling::Hero;
    throw InputError(option + " must be visible or hero, got '" + text + "'");
}

const char* wavelengthSamplingName(WavelengthSampling mode) {
    return mode == WavelengthSampling::Hero ? "hero" : "visible";
}

double visibleWavelengthPdf(double lambdaNm) {
    if (lambdaNm < kLambdaMin || lambdaNm > kLambdaMax) return 0;
    const VisibleBounds& b = visibleBounds();
    const double c = std::cosh(kVisibleA * (lambdaNm - kVisibleCentre));
    return kVisibleA / ((b.tanhMax - b.tanhMin) * c * c);
}

double visibleWavelengthCdf(double lambdaNm) {
    const VisibleBounds& b = visibleBounds();
    const double l = std::clamp<double>(lambdaNm, kLambdaMin, kLambdaMax);
    return (tanhAt(l) - b.tanhMin) / (b.tanhMax - b.tanhMin);
}

double sampleVisibleWavelength(double u) {
    const VisibleBounds& b = visibleBounds();
    const double t = b.tanhMin + u * (b.tanhMax - b.tanhMin);
    const double lambda = kVisibleCentre + std::atanh(t) / kVisibleA;
    return std::clamp<double>(lambda, kLambdaMin, kLambdaMax);
}

SampledWavelengths SampledWavelengths::sampleVisible(float u) {
    SampledWavelengths w;
    for (int i = 0; i < kSpectrumSamples; ++i) {
        const double lambda = sampleVisibleWavelength(stratum(u, i));
        w.lambda_[size_t(i)] = float(lambda);
        w.pdf_[size_t(i)] = float(visibleWavelengthPdf(lambda));
    }
    return w;
}

SampledWavelengths SampledWavelengths::sampleUniform(float u) {
    SampledWavelengths w;
    for (int i = 0; i < kSpectrumSamples; ++i) {
        w.lambda_[size_t(i)] = kLambdaMin + stratum(u, i) * (kLambdaMax - kLambdaMin);
        w.pdf_[size_t(i)] = 1.f / (kLambdaMax - kLambdaMin);
    }
    return w;
}

SampledWavelengths SampledWavelengths::sampleHero(float u) {
    constexpr float range = kLambdaMax - kLambdaMin;
    SampledWavelengths w;
    const float hero = u * range;
    for (int i = 0; i < kSpectrumSamples; ++i) {
        float offset = hero + float(i) * (range / kSpectrumSamples);
        if (offset >= range) offset -= range;
        w.lambda_[size_t(i)] = kLambdaMin + offset;
        w.pdf_[size_t(i)] = 1.f / range;
    }
    return w;
}

void SampledWavelengths::terminateSecondary() {
    if (secondaryTerminated()) return;
    for (int i = 1; i < kSpectrumSamples; ++i) pdf_[size_t(i)] = 0;
    pdf_[0] /= kSpectrumSamples;
}

bool SampledWavelengths::secondaryTerminated() const {
    for (int i = 1; i < kSpectrumSamples; ++i)
        if (pdf_[size_t(i)] != 0) return false;
    return true;
}

}  // namespace pathlab::spectral
