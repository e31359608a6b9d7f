#include "spectral/blackbody_spectrum.h"

#include <cmath>

namespace pathlab::spectral {
namespace {

constexpr double kPlanck = 6.62607015e-34;            // J·s
constexpr double kLightSpeed = 299792458.0;           // m/s
constexpr double kBoltzmann = 1.380649e-23;           // J/K
constexpr double kWienDisplacement = 2.897771955e-3;  // m·K

}  // namespace

double planckRadiance(double lambdaNm, double kelvin) {
    if (kelvin <= 0 || lambdaNm <= 0) return 0;
    const double l = lambdaNm * 1e-9;
    const double exponent = kPlanck * kLightSpeed / (l * kBoltzmann * kelvin);
    return 2 * kPlanck * kLightSpeed * kLightSpeed / (std::pow(l, 5) * std::expm1(exponent));
}

BlackbodySpectrum::BlackbodySpectrum(double kelvin)
    : kelvin_(kelvin),
      normalisation_(1 / planckRadiance(kWienDisplacement / kelvin * 1e9, kelvin)) {}

double BlackbodySpectrum::peakWavelength() const {
    return kWienDisplacement / kelvin_ * 1e9;
}

double BlackbodySpectrum::operator()(double lambdaNm) const {
    return planckRadiance(lambdaNm, kelvin_) * normalisation_;
}

SampledSpectrum BlackbodySpectrum::sample(const SampledWavelengths& w) const {
    SampledSpectrum s;
    for (int i = 0; i < kSpectrumSamples; ++i) s[i] = float((*this)(w.lambda(i)));
    return s;
}

}  // namespace pathlab::spectral
