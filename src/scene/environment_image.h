// An image environment map (pbrt-v4's ImageInfiniteLight): radiance from every
// direction, read from a square image in pbrt-v4's equal-area octahedral
// parameterisation (core/equal_area.h) of the light's own frame.
#pragma once

#include <vector>

#include "core/math.h"

namespace pathlab {

struct EnvironmentImage {
    int width = 0, height = 0;
    std::vector<Vec3f> texels;  // linear RGB radiance, top row first, already scaled
    // world direction = toWorld[0]·x + toWorld[1]·y + toWorld[2]·z for the
    // light-space direction (x, y, z); toLight is its inverse.
    Vec3f toWorld[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    Vec3f toLight[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    // Sample light directions uniformly over the sphere instead of in
    // proportion to the map's luminance (to compare the two).
    bool uniformSampling = false;
    bool empty() const { return texels.empty(); }
};

}  // namespace pathlab
