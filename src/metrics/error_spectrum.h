// Screen-space error: the radially averaged power spectrum of a render's
// signed error and the share of its power at low frequencies. Monte Carlo
// error spread as blue noise (little power at low frequencies) looks less
// noisy at the same MSE (Georgiev & Fajardo 2016; Heitz & Belcour 2019).
#pragma once

#include <string>
#include <vector>

#include "core/image.h"
#include "metrics/power_spectrum.h"

namespace pathlab {

// The signed error test − reference of each pixel, averaged over the three
// channels (row-major, in double). The channels of a path share its random
// decisions, so their errors move together; their mean is the achromatic
// error whose pattern the eye sees, and one transform serves all three.
std::vector<double> signedErrorField(const Image& reference, const Image& test);

// radialPeriodogram of signedErrorField: white noise of variance σ² in the
// error is flat at level σ²; power[0] is the DC term, w·h·(mean error)².
// The images must have the same size (requireComparable).
RadialPowerSpectrum errorSpectrum(const Image& reference, const Image& test);

// The error's power below kLowFrequencyLimit (a quarter of Nyquist) over its
// total power, both without the DC term: π/64 ≈ 0.049 for white noise, less
// for blue noise; NaN for a constant error.
double lowFrequencyErrorFraction(const RadialPowerSpectrum& spectrum);
double lowFrequencyErrorFraction(const Image& reference, const Image& test);

// CSV `frequency,power`, one row per ring from 0 (the DC term) to Nyquist,
// numbers to 17 significant digits (they read back bit for bit).
std::string errorSpectrumCsv(const RadialPowerSpectrum& spectrum);

// Refuses (InputError, one line) an --error-spectrum target that is neither
// .csv nor .png, or that cannot be created.
void checkErrorSpectrumPath(const std::string& path);

// Writes the spectrum atomically: CSV for .csv, the log-scale plot of
// errorSpectrumPlot (metrics/error_spectrum_plot.h) for .png.
void writeErrorSpectrum(const std::string& path, const RadialPowerSpectrum& spectrum);

}  // namespace pathlab
