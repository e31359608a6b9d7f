// Pixel-wise error metrics between a reference and a test image (linear RGB,
// equal size): MSE, RMSE, relMSE and PSNR, averaged over all pixels and the
// three channels. Sums are accumulated per row in double precision and the
// rows added in order, so results do not depend on the number of threads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"
#include "metrics/flip.h"

namespace pathlab {

// The ε of relMSE: keeps the ratio finite where the reference is black.
inline constexpr double kRelMseEpsilon = 0.01;

// mean of (t − r)² over pixels and channels.
double meanSquaredError(const Image& reference, const Image& test);
double rootMeanSquaredError(const Image& reference, const Image& test);
// mean of (t − r)² / (r² + ε): the error relative to the reference's brightness.
double relativeMeanSquaredError(const Image& reference, const Image& test,
                                double epsilon = kRelMseEpsilon);
// 10·log10(peak² / MSE) in dB; +infinity for identical images.
double peakSignalToNoiseRatio(const Image& reference, const Image& test, double peak = 1.0);
double psnrFromMse(double mse, double peak = 1.0);

// The MSE of the pixels a mask selects and of the others (each over its own
// pixels and the three channels); nullopt for a region without pixels. The
// mask is row-major, one entry per pixel, nonzero = inside. The two values
// weighted by their pixel counts average to meanSquaredError.
struct RegionMse {
    std::optional<double> inside, outside;
    size_t insidePixels = 0, outsidePixels = 0;
};
RegionMse meanSquaredErrorByRegion(const Image& reference, const Image& test,
                                   const std::vector<uint8_t>& mask);

// Number of pixels with at least one NaN or infinite channel.
size_t countNonFinitePixels(const Image& image);

// Throws InputError (naming the files) unless both images have the same size
// and only finite values.
void requireComparable(const Image& reference, const Image& test, const std::string& referenceName,
                       const std::string& testName);

// FLIP's mode for a pair of files: HDR when either is EXR or PFM (linear,
// unbounded), LDR when both are PNG (display-referred sRGB).
flip::Mode flipModeForFiles(const std::string& referencePath, const std::string& testPath);

}  // namespace pathlab
