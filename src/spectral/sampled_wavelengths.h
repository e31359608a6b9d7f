// The wavelengths one camera path carries, with the density each was drawn
// from (pbrt-v4's SampledWavelengths, PBRT 4th ed. §4.5.4–4.5.5).
//
// All kSpectrumSamples wavelengths come from one sample u, stratified in the
// sampling density's CDF: lane i takes u_i = (u + i/N) mod 1, so the N
// wavelengths always cover the N quarters of the CDF. A sampler's one 1D
// dimension thus decides the whole colour sample (docs/spectral.md).
#pragma once

#include <array>
#include <string>

#include "spectral/sampled_spectrum.h"

namespace pathlab::spectral {

// How spectral mode draws a camera sample's wavelengths from its one
// wavelength dimension (`render --wavelengths`, the study key `wavelengths`;
// docs/rendering.md, "Dimension layout"): pbrt-v4's visible density
// (sampleVisible, the default) or Wilkie et al.'s hero rotation (sampleHero).
enum class WavelengthSampling { Visible, Hero };
// "visible" or "hero"; anything else throws InputError naming `option`.
WavelengthSampling parseWavelengthSampling(const std::string& text, const std::string& option);
const char* wavelengthSamplingName(WavelengthSampling mode);

// pbrt-v4's visible-wavelength density (its SampleVisibleWavelengths, fitted
// to the CIE Y curve): p(λ) ∝ sech²(0.0072 (λ − 538 nm)), normalised exactly
// over [kLambdaMin, kLambdaMax]; 0 outside.
double visibleWavelengthPdf(double lambdaNm);
// Its inverse CDF: u in [0,1) → λ in [kLambdaMin, kLambdaMax].
double sampleVisibleWavelength(double u);
// Its CDF, for tests and for strata: λ → u.
double visibleWavelengthCdf(double lambdaNm);

class SampledWavelengths {
  public:
    // pbrt-v4's SampleVisible: the visible density, N strata from one u.
    static SampledWavelengths sampleVisible(float u);
    // Uniform over [kLambdaMin, kLambdaMax], N strata from one u (reference).
    static SampledWavelengths sampleUniform(float u);
    // Hero-wavelength sampling (Wilkie, Nawaz, Droske, Weidlich & Hanika 2014,
    // "Hero Wavelength Spectral Sampling", EGSR, eq. 5): the hero λ₀ uniform
    // from u, the others rotated from it by equal offsets of the range,
    // λ_i = λmin + ((λ₀ − λmin + i·Δ/N) mod Δ), Δ = λmax − λmin. Lane 0 is the
    // hero; as a set it equals sampleUniform's.
    static SampledWavelengths sampleHero(float u);
    // The sampler `mode` names.
    static SampledWavelengths sample(WavelengthSampling mode, float u) {
        return mode == WavelengthSampling::Hero ? sampleHero(u) : sampleVisible(u);
    }

    float lambda(int i) const { return lambda_[size_t(i)]; }
    float pdf(int i) const { return pdf_[size_t(i)]; }
    // The pdfs as a spectrum, to divide estimates by.
    SampledSpectrum pdfs() const {
        SampledSpectrum s;
        s.v = pdf_;
        return s;
    }

    // Wavelength-dependent refraction (a dispersive dielectric) makes the
    // lanes' paths diverge: keep lane 0 only, as pbrt-v4 does. The other pdfs
    // become 0 (their lanes then contribute nothing) and lane 0's is divided
    // by N, so the estimate stays unbiased with one wavelength instead of N.
    void terminateSecondary();
    bool secondaryTerminated() const;

  private:
    std::array<float, kSpectrumSamples> lambda_{}, pdf_{};
};

}  // namespace pathlab::spectral
