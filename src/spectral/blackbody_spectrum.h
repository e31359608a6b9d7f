// The emission of a blackbody (pbrt-v4's BlackbodySpectrum, PBRT 4th ed.
// §4.4.1): Planck's law B(λ, T) divided by its value at the peak λ_max = b / T
// (Wien's displacement law, b = 2.897771955 × 10⁻³ m·K), so that the
// spectrum's maximum over all wavelengths is 1 whatever the temperature.
// (pbrt-v4 lights then divide by the spectrum's luminance, as the RGB path's
// scene/blackbody.h does.)
#pragma once

#include "spectral/sampled_wavelengths.h"

namespace pathlab::spectral {

// Planck's law: spectral radiance in W·sr⁻¹·m⁻³ at λ in nm, T in kelvin
// (CODATA 2018 constants h, c, k_B).
double planckRadiance(double lambdaNm, double kelvin);

class BlackbodySpectrum {
  public:
    explicit BlackbodySpectrum(double kelvin);  // kelvin > 0
    double operator()(double lambdaNm) const;
    SampledSpectrum sample(const SampledWavelengths& w) const;
    double kelvin() const { return kelvin_; }
    double peakWavelength() const;  // nm

  private:
    double kelvin_, normalisation_;
};

}  // namespace pathlab::spectral
