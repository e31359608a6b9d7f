// The points one pixel receives from a sampler in two dimensions of the
// renderer's layout, and how finely to take their power spectrum: what
// `pathlab points` writes and `pathlab view`'s points panel shows.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"

namespace pathlab {

struct PixelPointsRequest {
    std::string sampler;
    int count = 1;           // samples 0 … count − 1
    int dimX = 0, dimY = 1;  // two different dimensions (0, 1: the position in the pixel)
    Vec2i pixel{0, 0};
    Vec2i resolution{1, 1};  // the image the sampler is built for; holds the pixel
    int spp = 1;             // the samples per pixel it is built for
    uint64_t seed = 0;
};

// Each sample's (dimX, dimY) as the renderer draws them (sampleDimensions).
// Throws InputError for an unknown sampler.
std::vector<Vec2f> pixelPoints(const PixelPointsRequest& request);

// The highest frequency of a spectrum of `count` points: about twice the
// blue-noise peak at √N, limited so that the DFT (radialPowerSpectrum) stays
// around 2·10^8 operations.
int spectrumFrequency(size_t count);

}  // namespace pathlab
