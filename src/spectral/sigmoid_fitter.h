// The optimiser behind the RGB-to-spectrum table (Jakob & Hanika 2019, §3–4):
// Gauss–Newton on the coefficients of a sigmoid polynomial so that its
// reflectance spectrum, lit by the colour space's illuminant, has the target
// colour. The residual is the difference in CIE 1976 L*a*b* (as in the paper:
// perceptually uniform, so no colour dominates the fit), and the spectrum's
// colour is integrated with Simpson's 3/8 rule on the CIE tables' 5-nm knots.
//
// Coefficients here are of a polynomial in x = (λ − 360) / (830 − 360) ∈ [0,1],
// where the problem is well conditioned; toNanometres converts them.
#pragma once

#include <vector>

#include "spectral/colour_space.h"
#include "spectral/rgb_spectrum.h"

namespace pathlab::spectral {

using SigmoidCoefficients = std::array<double, 3>;  // of x², x, 1

class SigmoidFitter {
  public:
    explicit SigmoidFitter(const RgbColourSpace& space);

    // The RGB of the reflectance S(c₀x² + c₁x + c₂) under the illuminant, and
    // (when asked) its derivatives ∂rgb_i/∂c_j.
    Vec3d rgbOf(const SigmoidCoefficients& c, Mat3d* jacobian = nullptr) const;

    // Gauss–Newton from `c` (the previous solution, for continuation) towards
    // `rgb`; returns the remaining ΔE (CIE 1976 distance in L*a*b*).
    double fit(const Vec3d& rgb, SigmoidCoefficients& c) const;

  private:
    std::vector<double> x_;     // the quadrature's nodes, normalised
    std::vector<Vec3d> basis_;  // weight × illuminant × RGB of the CMFs, per node
    Mat3d rgbToXyz_;
    Vec3d whiteXyz_;
};

// The polynomial in λ (nm) equal to c₀x² + c₁x + c₂ at x = (λ − 360) / 470.
SigmoidPolynomial toNanometres(const SigmoidCoefficients& c);

}  // namespace pathlab::spectral
