// What a sampler costs per dimension when drawn the way the path integrator
// draws: startPixelSample at each vertex's block, then the block's 1D and 2D
// draws (light choice, light point, lobe, direction, roulette). Shared by the
// Google Benchmark microbenchmarks and `pathlab bench --samplers`, which
// multiplies it by the dimensions a frame draws.
#pragma once

#include <string>

#include "sampling/registry.h"

namespace pathlab {

// Pixel 2D plus `depth` vertex blocks: 2 + 7·depth dimensions; returns their sum
// so the work cannot be optimised away.
template <typename S>
float drawPathDimensions(S& s, Vec2i pixel, int index, int depth) {
    s.startPixelSample(pixel, index, dims::kPixel);
    const Vec2f p = s.getPixel2D();
    float acc = p.x + p.y;
    for (int d = 0; d < depth; ++d) {
        s.startPixelSample(pixel, index, dims::bounceBase(d));
        acc += s.get1D();
        const Vec2f light = s.get2D();
        acc += s.get1D();
        const Vec2f dir = s.get2D();
        acc += light.x + light.y + dir.x + dir.y + s.get1D();
    }
    return acc;
}

constexpr int dimensionsPerPath(int depth) {
    return 2 + 7 * depth;
}

// Single-threaded nanoseconds per dimension over `paths` paths of `depth`
// vertices, walking pixels of a `resolution` image with `spp` samples each.
double nanosecondsPerDimension(const std::string& sampler, int spp, Vec2i resolution, int depth,
                               int paths);

}  // namespace pathlab
