// FLIP, the perceptual difference evaluator of
//   [HPG20] Andersson, Nilsson, Akenine-Möller, Oskarsson, Åström, Fairchild,
//           "FLIP: A Difference Evaluator for Alternating Images", HPG 2020
//           (Proc. ACM Comput. Graph. Interact. Tech. 3(2), article 15),
// and its HDR extension
//   [EG21]  Andersson, Nilsson, Shirley, Akenine-Möller, "Visualizing Errors in
//           Rendered High Dynamic Range Images", Eurographics 2021 short paper.
// Defaults, constants and pooling follow NVIDIA's reference implementation
// (github.com/NVlabs/flip, v1.6) so that mean values agree with it; see
// docs/metrics.md for the measured agreement.
#pragma once

#include <optional>
#include <vector>

#include "core/image.h"

namespace pathlab::flip {

enum class Mode { Ldr, Hdr };

// Pixels per degree of visual angle for an observer at `distanceMeters` from a
// display `displayWidthMeters` wide with `displayWidthPixels` columns
// ([HPG20] viewing conditions): the pixels spanned by one degree at the centre.
float pixelsPerDegree(float distanceMeters, float displayWidthMeters, float displayWidthPixels);

// 0.7 m from a 0.7 m wide 4K (3840 px) monitor: ≈ 67.02 ppd, the default of
// [HPG20] and of the reference implementation.
float defaultPixelsPerDegree();

// ---- Building blocks (exposed so that each can be tested on its own) ----

// The contrast sensitivity functions of [HPG20] as spatial filters, separated
// into 1-D kernels of radius ⌈3·σ_max·ppd⌉: `achromatic` (Yy) and `redGreen`
// (Cx) are single Gaussians normalised to sum 1; the blue–yellow (Cz) filter is
// a sum of two Gaussians, so it is the sum of two separable products
// blueYellow1⊗blueYellow1 + blueYellow2⊗blueYellow2, scaled so the 2-D kernel
// sums to 1.
struct CsfFilters {
    int radius = 0;
    std::vector<float> achromatic, redGreen, blueYellow1, blueYellow2;
};
CsfFilters makeCsfFilters(float ppd);

// The feature detectors of [HPG20] (edges: first derivative of a Gaussian;
// points: second derivative), with σ = 0.5·0.082°·ppd, radius ⌈3σ⌉. `gaussian`
// sums to 1; the positive and negative parts of each derivative sum to +1 and
// −1 respectively.
struct FeatureFilters {
    int radius = 0;
    std::vector<float> gaussian, firstDerivative, secondDerivative;
};
FeatureFilters makeFeatureFilters(float ppd);

// Edge and point magnitudes of an achromatic image with values in [0,1]
// (row-major): |(∂x, ∂y)(G∗Y)| and |(∂²x, ∂²y)(G∗Y)| with the filters above,
// edges clamped ([HPG20], feature pipeline).
struct FeatureMaps {
    std::vector<float> edge, point;
};
FeatureMaps detectFeatures(const std::vector<float>& achromatic, int width, int height, float ppd);

// The largest colour distance, HyAB between Hunt-adjusted green and blue,
// raised to q_c = 0.7 ([HPG20], colour pipeline).
float maxColorDistance();

// Maps a colour difference ΔE_c^q_c to [0,1]: [0, p_c·c_max) linearly onto
// [0, p_t), the rest onto [p_t, 1] (p_c = 0.4, p_t = 0.95).
float remapColorDifference(float poweredDistance, float cmax);

// ACES filmic tone curve (Narkowicz's fit, with the 0.6 pre-exposure of that
// fit cancelled, as in the reference implementation), per channel.
float acesToneMap(float value);

// Per-pixel LDR-FLIP error map of two linear-RGB images with values in [0,1].
std::vector<float> ldrFlipErrorMap(const Image& reference, const Image& test, float ppd);

// The exposure range of [EG21]: from the exposure that maps the
// reference's largest luminance to the tone curve's 0.85 point, to the one
// that does so for its median luminance; count = max(2, ⌈stop − start⌉).
struct ExposureRange {
    float start = 0, stop = 0;
    int count = 0;
};
ExposureRange automaticExposureRange(const Image& reference);

// Per-pixel HDR-FLIP error map: the maximum of LDR-FLIP over the exposures,
// each image scaled by 2^exposure, tone mapped with ACES and clamped.
std::vector<float> hdrFlipErrorMap(const Image& reference, const Image& test, float ppd,
                                   const ExposureRange& exposures);

// Pooled statistics of an error map. The weighted median and quartiles weight
// each pixel by its own error, as the reference tool does: the p-quantile is
// the smallest error e (ascending order) at which the running sum of errors
// exceeds p · (sum of all errors); 0 when all errors are 0.
struct Statistics {
    double mean = 0, weightedMedian = 0, q1 = 0, q3 = 0, min = 0, max = 0;
};
Statistics poolErrors(const std::vector<float>& errors);
double weightedPercentile(std::vector<float> errors, double p);

// ---- The whole evaluation ----

struct Options {
    Mode mode = Mode::Ldr;
    float ppd = defaultPixelsPerDegree();
    // HDR only; when absent they come from automaticExposureRange(reference).
    std::optional<float> startExposure, stopExposure;
    std::optional<int> exposureCount;
};

struct Result {
    int width = 0, height = 0;
    std::vector<float> errorMap;  // row-major, one value in [0,1] per pixel
    Statistics stats;
    Mode mode = Mode::Ldr;
    float ppd = 0;
    ExposureRange exposures;  // HDR only
};

// The reference's half of FLIP, computed once for comparing many test images
// against one reference (a study measures every cell against its scene's
// reference): the exposure range and, per exposure, the reference's filtered
// colours and feature magnitudes. evaluate(test) equals
// flip::evaluate(reference, test, options) bit for bit at about half the cost.
struct LdrSide;
class PreparedReference {
  public:
    PreparedReference(const Image& reference, const Options& options);
    ~PreparedReference();
    Result evaluate(const Image& test) const;
    std::vector<float> errorMap(const Image& test) const;

  private:
    int width_, height_;
    Mode mode_;
    float ppd_;
    ExposureRange exposures_;
    std::vector<LdrSide> sides_;  // one (LDR) or one per exposure (HDR)
};

// Evaluates FLIP between two linear RGB images of equal size. LDR clamps both
// to [0,1]; HDR uses them as they are. Throws InputError for mismatched sizes
// or an invalid exposure range.
Result evaluate(const Image& reference, const Image& test, const Options& options);

}  // namespace pathlab::flip
