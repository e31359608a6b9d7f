// Radially averaged power spectra (periodograms) — the standard picture of a
// sampling pattern's frequency content (Ulichney 1987, "Digital Halftoning";
// Heck, Schlömer & Deussen 2013, "Blue Noise Sampling with Controlled
// Aliasing"). Normalised so that white noise has expected power 1 at every
// non-zero frequency: blue noise is below 1 at low frequencies.
#pragma once

#include <vector>

#include "core/math.h"

namespace pathlab {

// Point set in [0,1)²: the periodogram P(f) = |Σ_j exp(−2πi f·x_j)|² / N at
// the integer frequencies f = (fx, fy), −maxFrequency ≤ fx, fy ≤ maxFrequency,
// as a (2·maxFrequency + 1)² grid, row-major from (−F, −F); the zero frequency
// (equal to N) at its centre.
std::vector<double> powerSpectrum(const std::vector<Vec2f>& points, int maxFrequency);

// The grid of powerSpectrum averaged over rings of width 1: element r is the
// mean over round(|f|) = r, r = 0 … maxFrequency.
std::vector<double> radialAverage(const std::vector<double>& power, int maxFrequency);

// Point set in [0,1)²: P(f) = |Σ_j exp(−2πi f·x_j)|² / N over integer frequency
// vectors f with |f| ≤ maxFrequency, averaged over rings of width 1.
// Element r is the ring round(|f|) = r (element 0 is the DC term, equal to N).
std::vector<double> radialPowerSpectrum(const std::vector<Vec2f>& points, int maxFrequency);

// Scalar image (row-major w × h): periodogram of the mean-subtracted values
// divided by their variance, ring-averaged up to the Nyquist radius min(w,h)/2
// (radialPeriodogram in metrics/power_spectrum.h, whose rings it uses);
// element 0 is 0.
std::vector<double> radialPowerSpectrum(const std::vector<double>& image, int w, int h);

}  // namespace pathlab
