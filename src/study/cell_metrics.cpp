#include "study/cell_metrics.h"

#include <algorithm>
#include <cmath>

#include "metrics/bias.h"
#include "metrics/error_spectrum.h"
#include "metrics/flip.h"
#include "metrics/image_metrics.h"

namespace pathlab {
namespace {

// The 8-bit view a PNG of the image shows, as values in [0,1].
Image toneMapped(const Image& image, float exposure) {
    Image out = image;
    const float scale = std::exp2(exposure);
    for (float& v : out.rgb)
        v = std::round(linearToSrgb(std::clamp(v * scale, 0.0f, 1.0f)) * 255.0f) / 255.0f;
    return out;
}

flip::Options studyFlipOptions() {
    flip::Options options;
    options.mode = flip::Mode::Hdr;
    return options;
}

}  // namespace

CellMeter::CellMeter(const Image& reference, float exposure, const StudySpec& spec,
                     const std::vector<uint8_t>* edgeMask)
    : reference_(reference), edgeMask_(edgeMask), exposure_(exposure), spec_(spec) {
    if (spec.wants("flip")) flip_.emplace(reference, studyFlipOptions());
}

CellMetrics CellMeter::measure(const Image& test) const {
    return measureCell(reference_, test, exposure_, spec_, flip_ ? &*flip_ : nullptr, edgeMask_);
}

CellMetrics measureCell(const Image& reference, const Image& test, float exposure,
                        const StudySpec& spec, const flip::PreparedReference* prepared,
                        const std::vector<uint8_t>* edgeMask) {
    CellMetrics m;
    m.mse = meanSquaredError(reference, test);
    m.rmse = std::sqrt(m.mse);
    m.bias = signedBias(reference, test).relative;
    m.errorSpectrum = errorSpectrum(reference, test);
    if (const double f = m.errorSpectrum.lowFrequencyFraction(); !std::isnan(f))
        m.lowFrequencyFraction = f;
    if (edgeMask) {
        const RegionMse regions = meanSquaredErrorByRegion(reference, test, *edgeMask);
        m.mseEdge = regions.inside;
        m.mseRest = regions.outside;
    }
    if (spec.wants("relmse")) m.relmse = relativeMeanSquaredError(reference, test);
    if (spec.wants("psnr")) {
        const double psnr =
            peakSignalToNoiseRatio(toneMapped(reference, exposure), toneMapped(test, exposure));
        if (std::isfinite(psnr)) m.psnr = psnr;  // identical views have no finite PSNR
    }
    if (spec.wants("flip")) {
        flip::Result r = prepared ? prepared->evaluate(test)
                                  : flip::evaluate(reference, test, studyFlipOptions());
        m.flip = r.stats.mean;
        m.flipMedian = r.stats.weightedMedian;
        m.flipMap = std::move(r.errorMap);
    }
    return m;
}

NoiseFloor referenceNoise(const Image& reference, const Image& varianceOfMean,
                          const std::vector<uint8_t>* edgeMask) {
    NoiseFloor n;
    const size_t count = varianceOfMean.rgb.size();
    if (count == 0) return n;
    double edge = 0, rest = 0;
    size_t edgeValues = 0;
    for (size_t i = 0; i < count; ++i) {
        const double var = varianceOfMean.rgb[i], r = reference.rgb[i];
        n.mse += var;
        n.relmse += var / (r * r + kRelMseEpsilon);
        if (edgeMask && (*edgeMask)[i / 3]) {
            edge += var;
            ++edgeValues;
        } else {
            rest += var;
        }
    }
    n.mse /= double(count);
    n.relmse /= double(count);
    if (edgeMask) {
        if (edgeValues) n.mseEdge = edge / double(edgeValues);
        if (edgeValues < count) n.mseRest = rest / double(count - edgeValues);
    }
    return n;
}

float viewingExposure(const Image& reference) {
    std::vector<float> luminance;
    luminance.reserve(reference.pixelCount());
    for (size_t i = 0; i < reference.pixelCount(); ++i) {
        const float* p = &reference.rgb[3 * i];
        const float y = 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
        if (std::isfinite(y)) luminance.push_back(y);
    }
    if (luminance.empty()) return 0.0f;
    const size_t k = std::min(luminance.size() - 1, size_t(0.95 * double(luminance.size())));
    std::nth_element(luminance.begin(), luminance.begin() + long(k), luminance.end());
    const float p95 = luminance[k];
    return p95 > 0 ? std::log2(0.9f / p95) : 0.0f;
}

std::vector<float> relativeSquaredErrorMap(const Image& reference, const Image& test) {
    std::vector<float> out(reference.pixelCount());
    for (size_t i = 0; i < out.size(); ++i) {
        double sum = 0;
        for (int c = 0; c < 3; ++c) {
            const double r = reference.rgb[3 * i + c], d = test.rgb[3 * i + c] - r;
            sum += d * d / (r * r + kRelMseEpsilon);
        }
        const double e = std::max(sum / 3.0, 1e-30);
        out[i] = float(std::clamp((std::log10(e) + 4.0) / 5.0, 0.0, 1.0));
    }
    return out;
}

}  // namespace pathlab
