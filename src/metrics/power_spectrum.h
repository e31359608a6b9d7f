// The periodogram of a real image, computed with FFTW (Frigo & Johnson 2005,
// "The Design and Implementation of FFTW3"), and its radial average: the
// picture of how a screen-space error is spread over spatial frequencies
// (Ulichney 1987, "Digital Halftoning"; Georgiev & Fajardo 2016, "Blue-noise
// Dithered Sampling"; Heitz & Belcour 2019, "Distributing Monte Carlo Errors as
// a Blue Noise in Screen Space", whose figures plot this average).
#pragma once

#include <cstdint>
#include <vector>

namespace pathlab {

// The low-frequency band: frequencies below a quarter of Nyquist (0.5 cycles
// per pixel), as in the low-frequency error fraction below.
inline constexpr double kLowFrequencyLimit = 0.125;  // cycles per pixel

// Periodogram P(k) = |Σ_x e(x) exp(−2πi k·x / (w, h))|² / (w·h) over the w·h
// frequencies k of the image grid. With this normalisation white noise of
// variance σ² has E[P(k)] = σ² at every k (a flat spectrum at level σ²), and
// Σ_k P(k) = Σ_x e(x)² (Parseval).
//
// Rings: with n = min(w, h), frequency k has radius ρ = n·|f| where
// f = (k_x / w, k_y / h) in cycles per pixel (signed, |f_x|, |f_y| ≤ 0.5), and
// belongs to ring round(ρ); ring r sits at r / n cycles per pixel, one ring per
// frequency step of the shorter side. Rings 1..n/2 are kept (up to Nyquist along
// the shorter side); the corners beyond are in the totals only. Ring 0 is the DC
// term alone (P(0) = w·h·mean², the error's mean seen as power); in a non-square
// image the few non-zero frequencies with ρ < 0.5 join ring 1.
struct RadialPowerSpectrum {
    std::vector<double> frequency;  // cycles per pixel: r / n for ring r = 0..n/2
    std::vector<double> power;      // mean of P over each ring; power[0] = P(0)
    std::vector<int64_t> count;     // frequencies of the full plane in each ring
    // (1/(w·h)) Σ_{k≠0} P(k): the image's variance (its mean removed), Parseval.
    double totalPower = 0;
    // (1/(w·h)) Σ_{k≠0, |f|<kLowFrequencyLimit} P(k).
    double lowFrequencyPower = 0;

    // lowFrequencyPower / totalPower, DC excluded from both: for white noise the
    // area of the disc |f| < 1/8 over that of the square |f_x|,|f_y| ≤ 1/2,
    // π/64 ≈ 0.049. NaN when the image is constant (no power at all).
    double lowFrequencyFraction() const;
};

// The spectrum of `values` (row-major, width × height, top row first).
// Deterministic: FFTW plans with FFTW_ESTIMATE (no timing) in 64-byte aligned
// buffers, and the sums run in a fixed order. Safe to call from any thread.
RadialPowerSpectrum radialPeriodogram(const std::vector<double>& values, int width, int height);

}  // namespace pathlab
