// A spectrum given as values at wavelengths, linearly interpolated between
// them and 0 outside (pbrt-v4's PiecewiseLinearSpectrum): the named
// illuminants and pbrt-v4's tabulated `spectrum` parameters.
#pragma once

#include <vector>

#include "spectral/sampled_wavelengths.h"

namespace pathlab::spectral {

class PiecewiseLinearSpectrum {
  public:
    PiecewiseLinearSpectrum() = default;
    // `lambdaNm` strictly increasing, as many values; throws InputError if not.
    PiecewiseLinearSpectrum(std::vector<double> lambdaNm, std::vector<double> values);
    // pbrt-v4's interleaved form (λ₀ v₀ λ₁ v₁ …), as a `spectrum` parameter holds it.
    static PiecewiseLinearSpectrum fromInterleaved(const std::vector<double>& pairs);

    double operator()(double lambdaNm) const;
    SampledSpectrum sample(const SampledWavelengths& w) const;
    double maxValue() const;

    void scale(double factor);
    // ∫ s(λ) ȳ(λ) dλ / ∫ ȳ(λ) dλ over 360–830 nm: the luminance Y of the
    // spectrum as an emitter (1 for pbrt-v4's normalised illuminants).
    double luminance() const;
    // Scaled so that luminance() is 1: pbrt-v4's normalisation of named
    // illuminants (its FromInterleaved with normalize = true).
    void normaliseToUnitLuminance();

    const std::vector<double>& wavelengths() const { return lambda_; }
    const std::vector<double>& values() const { return value_; }

  private:
    // The interval of λ: hi, the first knot above λ (std::upper_bound's).
    size_t upperKnot(double lambdaNm) const;
    std::vector<double> lambda_, value_;
    // Knots on a uniform grid (λ_i = λ_0 + i·step exactly, as the tabulated
    // illuminants are): the interval is found from the grid index, then
    // checked against the knots, rather than by binary search; 0 otherwise.
    double step_ = 0;
};

}  // namespace pathlab::spectral
