#include "metrics/bias.h"

#include <tbb/parallel_for.h>

#include <string>
#include <vector>

#include "core/error.h"

namespace pathlab {

Bias signedBias(const Image& reference, const Image& test) {
    if (reference.width != test.width || reference.height != test.height)
        throw InputError("images differ in size: reference " + std::to_string(reference.width) +
                         "x" + std::to_string(reference.height) + ", test " +
                         std::to_string(test.width) + "x" + std::to_string(test.height));
    Bias b;
    const size_t pixels = reference.pixelCount();
    if (pixels == 0) return b;
    // Per row: the three channels' sums of t − r, and the sum of r.
    struct RowSums {
        std::array<double, 3> difference{};
        double reference = 0;
    };
    const size_t w = size_t(reference.width);
    std::vector<RowSums> rows(size_t(reference.height));
    tbb::parallel_for(0, reference.height, [&](int y) {
        RowSums& s = rows[size_t(y)];
        for (size_t i = size_t(y) * w * 3, end = i + w * 3; i < end; ++i) {
            s.difference[i % 3] += double(test.rgb[i]) - double(reference.rgb[i]);
            s.reference += reference.rgb[i];
        }
    });
    double referenceSum = 0;
    for (const RowSums& s : rows) {
        for (int c = 0; c < 3; ++c) b.channels[size_t(c)] += s.difference[size_t(c)];
        referenceSum += s.reference;
    }
    for (double& c : b.channels) c /= double(pixels);
    b.mean = (b.channels[0] + b.channels[1] + b.channels[2]) / 3.0;
    b.referenceMean = referenceSum / double(3 * pixels);
    if (b.referenceMean > 0) b.relative = b.mean / b.referenceMean;
    return b;
}

}  // namespace pathlab
