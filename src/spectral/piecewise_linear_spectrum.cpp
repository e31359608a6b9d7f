#include "spectral/piecewise_linear_spectrum.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "spectral/cie_functions.h"

namespace pathlab::spectral {

PiecewiseLinearSpectrum::PiecewiseLinearSpectrum(std::vector<double> lambdaNm,
                                                 std::vector<double> values)
    : lambda_(std::move(lambdaNm)), value_(std::move(values)) {
    if (lambda_.size() != value_.size() || lambda_.empty())
        throw InputError("spectrum: needs as many wavelengths as values, at least one");
    for (size_t i = 0; i < lambda_.size(); ++i) {
        if (!std::isfinite(lambda_[i]) || !std::isfinite(value_[i]))
            throw InputError("spectrum: wavelengths and values must be finite numbers");
        if (i > 0 && !(lambda_[i] > lambda_[i - 1]))
            throw InputError("spectrum: wavelengths must increase strictly (" +
                             std::to_string(lambda_[i]) + " nm follows " +
                             std::to_string(lambda_[i - 1]) + " nm)");
    }
    if (lambda_.size() < 2) return;
    const double step = lambda_[1] - lambda_[0];
    for (size_t i = 0; i < lambda_.size(); ++i)
        if (lambda_[i] != lambda_[0] + double(i) * step) return;
    step_ = step;
}

size_t PiecewiseLinearSpectrum::upperKnot(double lambdaNm) const {
    if (step_ == 0 || std::isnan(lambdaNm))
        return size_t(std::upper_bound(lambda_.begin(), lambda_.end(), lambdaNm) - lambda_.begin());
    // The grid's guess, moved to the first knot above λ: the same index as
    // the binary search, so the same interpolation and the same bits (the
    // spectral renderer samples the illuminant at every path's wavelengths).
    const size_t n = lambda_.size();
    size_t hi = std::min(size_t((lambdaNm - lambda_[0]) / step_) + 1, n);
    while (hi > 0 && lambda_[hi - 1] > lambdaNm) --hi;
    while (hi < n && lambda_[hi] <= lambdaNm) ++hi;
    return hi;
}

PiecewiseLinearSpectrum PiecewiseLinearSpectrum::fromInterleaved(const std::vector<double>& pairs) {
    if (pairs.size() % 2 != 0)
        throw InputError("spectrum: expected wavelength-value pairs, got an odd count of " +
                         std::to_string(pairs.size()) + " numbers");
    std::vector<double> lambda, values;
    for (size_t i = 0; i < pairs.size(); i += 2) {
        lambda.push_back(pairs[i]);
        values.push_back(pairs[i + 1]);
    }
    return PiecewiseLinearSpectrum(std::move(lambda), std::move(values));
}

double PiecewiseLinearSpectrum::operator()(double lambdaNm) const {
    if (lambda_.empty() || lambdaNm < lambda_.front() || lambdaNm > lambda_.back()) return 0;
    const size_t hi = upperKnot(lambdaNm);
    if (hi >= lambda_.size()) return value_.back();
    const size_t lo = hi - 1;
    const double t = (lambdaNm - lambda_[lo]) / (lambda_[hi] - lambda_[lo]);
    return (1 - t) * value_[lo] + t * value_[hi];
}

SampledSpectrum PiecewiseLinearSpectrum::sample(const SampledWavelengths& w) const {
    SampledSpectrum s;
    for (int i = 0; i < kSpectrumSamples; ++i) s[i] = float((*this)(w.lambda(i)));
    return s;
}

double PiecewiseLinearSpectrum::maxValue() const {
    return value_.empty() ? 0 : *std::max_element(value_.begin(), value_.end());
}

void PiecewiseLinearSpectrum::scale(double factor) {
    for (double& v : value_) v *= factor;
}

double PiecewiseLinearSpectrum::luminance() const {
    const Quadrature& q = fineQuadrature();
    double y = 0;
    for (size_t k = 0; k < q.lambda.size(); ++k)
        y += q.weight[k] * (*this)(q.lambda[k]) * cieY(q.lambda[k]);
    return y / cieYIntegral();
}

void PiecewiseLinearSpectrum::normaliseToUnitLuminance() {
    const double y = luminance();
    if (y > 0) scale(1 / y);
}

}  // namespace pathlab::spectral
