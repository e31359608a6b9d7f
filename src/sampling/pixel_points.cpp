#include "sampling/pixel_points.h"

#include <algorithm>
#include <cmath>
#include <variant>

#include "sampling/registry.h"

namespace pathlab {

std::vector<Vec2f> pixelPoints(const PixelPointsRequest& r) {
    AnySampler sampler = makeSampler(r.sampler, SamplerConfig{r.spp, r.seed, r.resolution});
    std::vector<Vec2f> points(size_t(std::max(r.count, 0)));
    std::visit(
        [&](auto& s) {
            for (int k = 0; k < r.count; ++k)
                points[size_t(k)] = sampleDimensions(s, r.pixel, k, r.dimX, r.dimY);
        },
        sampler);
    return points;
}

int spectrumFrequency(size_t count) {
    const int wanted = std::max(16, 2 * int(std::ceil(std::sqrt(double(count)))));
    const int affordable = int(std::sqrt(2e8 / double(std::max<size_t>(count, 1))) / 2);
    return std::clamp(std::min(wanted, affordable), 4, 128);
}

}  // namespace pathlab
