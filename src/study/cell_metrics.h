// What a study measures about one render against its reference, and the
// per-pixel pictures of it that the report shows.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"
#include "metrics/flip.h"
#include "metrics/power_spectrum.h"
#include "study/spec.h"

namespace pathlab {

struct CellMetrics {
    double mse = 0, rmse = 0;
    std::optional<double> relmse, flip, flipMedian, psnr;
    // MSE over the emitter-edge pixels and over the rest (render/emitter_edges.h);
    // absent without a mask, or for a region with no pixels.
    std::optional<double> mseEdge, mseRest;
    // Relative bias (metrics/bias.h): mean of test − reference over the
    // reference's mean; absent for a reference whose mean is not positive.
    std::optional<double> bias;
    // The share of the signed error's power below a quarter of Nyquist
    // (metrics/error_spectrum.h); absent for a constant error.
    std::optional<double> lowFrequencyFraction;
    RadialPowerSpectrum errorSpectrum;  // written beside the cell's images
    std::vector<float> flipMap;         // HDR-FLIP per pixel; empty unless FLIP was measured
};

// MSE, RMSE, the relative bias and the error spectrum always, the rest as
// `spec.metrics` asks. FLIP is HDR-FLIP (the renders are linear and
// unbounded); PSNR is that of the tone-mapped 8-bit views (both images scaled
// by 2^exposure, clamped, sRGB encoded, peak 1). `flip` is the reference
// prepared once for HDR-FLIP (CellMeter below); the values are those of
// flip::evaluate(reference, test). With `edgeMask` (one entry per pixel,
// nonzero = emitter edge) the MSE is also split by region.
CellMetrics measureCell(const Image& reference, const Image& test, float exposure,
                        const StudySpec& spec, const flip::PreparedReference* flip = nullptr,
                        const std::vector<uint8_t>* edgeMask = nullptr);

// Measures cells against one reference: the reference's half of FLIP is
// computed once, not once per cell.
class CellMeter {
  public:
    CellMeter(const Image& reference, float exposure, const StudySpec& spec,
              const std::vector<uint8_t>* edgeMask = nullptr);
    CellMetrics measure(const Image& test) const;

  private:
    const Image& reference_;
    const std::vector<uint8_t>* edgeMask_;
    float exposure_;
    const StudySpec& spec_;
    std::optional<flip::PreparedReference> flip_;
};

// The reference's own noise, from the renderer's per-pixel variance of the
// mean: E[MSE(test, reference)] = true MSE + noiseMse for a test independent of
// the reference, so no MSE below noiseMse says anything about the test.
// With `edgeMask`, the floor of each region's MSE as well.
struct NoiseFloor {
    double mse = 0, relmse = 0;
    std::optional<double> mseEdge, mseRest;
};
NoiseFloor referenceNoise(const Image& reference, const Image& varianceOfMean,
                          const std::vector<uint8_t>* edgeMask = nullptr);

// Stops of exposure that put the reference's 95th-percentile luminance at 0.9,
// so the PNGs of one scene share one brightness and few pixels clip. Not the
// 99th: the Cornell box's light alone covers about 1% of the frame, and at
// 64×64 the 99th percentile fell on it, leaving the walls three stops dark.
float viewingExposure(const Image& reference);

// Per pixel, the relative squared error (t−r)²/(r²+ε) averaged over channels,
// mapped to [0,1] on a log scale from 1e-4 (0) to 10 (1) so maps of different
// samplers and sample counts can be compared side by side.
std::vector<float> relativeSquaredErrorMap(const Image& reference, const Image& test);

}  // namespace pathlab
