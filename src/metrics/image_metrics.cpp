#include "metrics/image_metrics.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "core/error.h"

namespace pathlab {
namespace {

void requireSameSize(const Image& reference, const Image& test) {
    if (reference.width != test.width || reference.height != test.height)
        throw InputError("images differ in size: reference " + std::to_string(reference.width) +
                         "x" + std::to_string(reference.height) + ", test " +
                         std::to_string(test.width) + "x" + std::to_string(test.height));
}

// Mean over all pixels and channels of perChannel(r, t): one double sum per
// row (in parallel), then the rows summed in order.
template <typename PerChannel>
double meanOverChannels(const Image& reference, const Image& test, const PerChannel& perChannel) {
    requireSameSize(reference, test);
    if (reference.pixelCount() == 0) return 0.0;
    const size_t rowLength = size_t(reference.width) * 3;
    std::vector<double> rowSums(reference.height, 0.0);
    tbb::parallel_for(tbb::blocked_range<int>(0, reference.height),
                      [&](const tbb::blocked_range<int>& rows) {
                          for (int y = rows.begin(); y != rows.end(); ++y) {
                              const float* r = &reference.rgb[size_t(y) * rowLength];
                              const float* t = &test.rgb[size_t(y) * rowLength];
                              double sum = 0;
                              for (size_t i = 0; i < rowLength; ++i) sum += perChannel(r[i], t[i]);
                              rowSums[y] = sum;
                          }
                      });
    double total = 0;
    for (double s : rowSums) total += s;
    return total / double(reference.rgb.size());
}

}  // namespace

double meanSquaredError(const Image& reference, const Image& test) {
    return meanOverChannels(reference, test, [](double r, double t) { return (t - r) * (t - r); });
}

RegionMse meanSquaredErrorByRegion(const Image& reference, const Image& test,
                                   const std::vector<uint8_t>& mask) {
    requireSameSize(reference, test);
    if (mask.size() != reference.pixelCount())
        throw std::invalid_argument("region mask does not match the image size");
    // Row sums in parallel, added in row order: independent of thread count.
    const size_t w = size_t(reference.width);
    std::vector<double> inside(reference.height, 0.0), outside(reference.height, 0.0);
    tbb::parallel_for(0, reference.height, [&](int y) {
        for (size_t x = 0; x < w; ++x) {
            const size_t i = size_t(y) * w + x;
            double sum = 0;
            for (size_t c = 0; c < 3; ++c) {
                const double d = double(test.rgb[3 * i + c]) - reference.rgb[3 * i + c];
                sum += d * d;
            }
            (mask[i] ? inside : outside)[size_t(y)] += sum;
        }
    });
    RegionMse r;
    for (uint8_t m : mask) ++(m ? r.insidePixels : r.outsidePixels);
    double in = 0, out = 0;
    for (int y = 0; y < reference.height; ++y) in += inside[size_t(y)], out += outside[size_t(y)];
    if (r.insidePixels) r.inside = in / (3.0 * double(r.insidePixels));
    if (r.outsidePixels) r.outside = out / (3.0 * double(r.outsidePixels));
    return r;
}

double rootMeanSquaredError(const Image& reference, const Image& test) {
    return std::sqrt(meanSquaredError(reference, test));
}

double relativeMeanSquaredError(const Image& reference, const Image& test, double epsilon) {
    return meanOverChannels(reference, test, [epsilon](double r, double t) {
        return (t - r) * (t - r) / (r * r + epsilon);
    });
}

double psnrFromMse(double mse, double peak) {
    if (mse <= 0) return std::numeric_limits<double>::infinity();
    return 10.0 * std::log10(peak * peak / mse);
}

double peakSignalToNoiseRatio(const Image& reference, const Image& test, double peak) {
    return psnrFromMse(meanSquaredError(reference, test), peak);
}

size_t countNonFinitePixels(const Image& image) {
    size_t count = 0;
    for (size_t i = 0; i < image.pixelCount(); ++i) {
        const float* p = &image.rgb[3 * i];
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) ++count;
    }
    return count;
}

void requireComparable(const Image& reference, const Image& test, const std::string& referenceName,
                       const std::string& testName) {
    if (reference.width != test.width || reference.height != test.height)
        throw InputError("images differ in size: '" + referenceName + "' is " +
                         std::to_string(reference.width) + "x" + std::to_string(reference.height) +
                         ", '" + testName + "' is " + std::to_string(test.width) + "x" +
                         std::to_string(test.height));
    for (const auto& [image, name] : {std::pair{&reference, &referenceName}, {&test, &testName}}) {
        const size_t bad = countNonFinitePixels(*image);
        if (bad > 0)
            throw InputError("'" + *name + "' has " + std::to_string(bad) + " of " +
                             std::to_string(image->pixelCount()) +
                             " pixels with NaN or infinite values");
    }
}

flip::Mode flipModeForFiles(const std::string& referencePath, const std::string& testPath) {
    const bool bothPng = imageFormatFromPath(referencePath) == ImageFormat::Png &&
                         imageFormatFromPath(testPath) == ImageFormat::Png;
    return bothPng ? flip::Mode::Ldr : flip::Mode::Hdr;
}

}  // namespace pathlab
