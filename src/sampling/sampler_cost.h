// What a sampler costs per dimension when drawn the way the renderer draws on
// the Cornell box: the camera rays of a batch of up to kBatchSamples samples
// first (their positions in the pixel through drawPixelLanes, a camera packet
// of kCameraPacketSamples at a time, as traceCameraPacket draws them), then the batch's
// paths together, as estimateRadianceBatch traces them: at each vertex depth,
// kCameraPacketSamples paths at a time, the paths' light points
// (dims::kLightPoint) and BSDF directions (dims::kBsdfDirection) through
// drawVertexLanes, then — from the third vertex on — their Russian roulette
// (dims::kRoulette, pbrt-v4's default) through drawLanes1D. (Every modelled
// path lives to the last vertex, so every group is full.)
// Shared by the Google Benchmark microbenchmarks and `pathlab bench --samplers`,
// which multiplies it by the dimensions a frame draws.
#pragma once

#include <algorithm>
#include <string>

#include "sampling/registry.h"

namespace pathlab {

// Vertices from this depth on draw the roulette dimension.
inline constexpr int kCostRouletteDepth = 2;

constexpr int dimensionsPerPath(int depth) {
    return 2 + 4 * depth + std::max(0, depth - kCostRouletteDepth);
}

// The sample indices of the group of up to kCameraPacketSamples samples that
// starts k0 samples into the batch; returns how many there are.
inline int groupIndices(int firstIndex, int count, int k0, int* indices) {
    const int lanes = std::min(kCameraPacketSamples, count - k0);
    for (int j = 0; j < lanes; ++j) indices[j] = firstIndex + k0 + j;
    return lanes;
}

// Samples firstIndex … firstIndex + count − 1 of `pixel` (count ≤
// kBatchSamples), each a path of `depth` vertices; returns the sum of the
// values so the work cannot be optimised away.
template <typename S>
float drawBatchDimensions(S& s, Vec2i pixel, int firstIndex, int count, int depth) {
    float acc = 0;
    for (int k0 = 0; k0 < count; k0 += kCameraPacketSamples) {
        int indices[kCameraPacketSamples];
        const int lanes = groupIndices(firstIndex, count, k0, indices);
        Vec2f p[kCameraPacketSamples];
        drawPixelLanes(s, pixel, indices, lanes, p);
        for (int j = 0; j < lanes; ++j) acc += p[j].x + p[j].y;
    }
    for (int d = 0; d < depth; ++d) {
        const int base = dims::bounceBase(d);
        for (int k0 = 0; k0 < count; k0 += kCameraPacketSamples) {
            int indices[kCameraPacketSamples];
            const int lanes = groupIndices(firstIndex, count, k0, indices);
            float choice[kCameraPacketSamples];
            Vec2f light[kCameraPacketSamples], dir[kCameraPacketSamples];
            drawVertexLanes(s, pixel, indices, lanes, base, false, choice, light, dir);
            for (int j = 0; j < lanes; ++j) acc += light[j].x + light[j].y + dir[j].x + dir[j].y;
            if (d < kCostRouletteDepth) continue;
            float roulette[kCameraPacketSamples];
            drawLanes1D(s, pixel, indices, lanes, base + dims::kRoulette, roulette);
            for (int j = 0; j < lanes; ++j) acc += roulette[j];
        }
    }
    return acc;
}

// A walk over an image's samples batch by batch, pixel after pixel (row by
// row, back to the first pixel after the last): where the next batch starts
// and how many samples it has (kBatchSamples, or the pixel's rest).
struct BatchWalk {
    int spp;
    Vec2i resolution;
    Vec2i pixel{0, 0};
    int index = 0;
    int count() const { return std::min(kBatchSamples, spp - index); }
    void advance() {
        if ((index += count()) < spp) return;
        index = 0;
        if (++pixel.x == resolution.x) pixel.x = 0, pixel.y = (pixel.y + 1) % resolution.y;
    }
};

// Single-threaded nanoseconds per dimension over `batches` batches
// (BatchWalk) of paths of `depth` vertices, in a `resolution` image with `spp`
// samples each.
double nanosecondsPerDimension(const std::string& sampler, int spp, Vec2i resolution, int depth,
                               int batches);

}  // namespace pathlab
