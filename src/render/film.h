// The part of the full image a render produces: pbrt-v4's film pixel bounds
// from its crop window (film.cpp, RGBFilm's pixelBounds). The camera always
// maps the full resolution; the image holds only the pixels inside the crop.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/math.h"
#include "scene/scene.h"

namespace pathlab {

// Pixels min.x … max.x − 1 by min.y … max.y − 1 of the full image.
struct PixelBounds {
    Vec2i min, max;
    int width() const { return max.x - min.x; }
    int height() const { return max.y - min.y; }
    bool isFullImage(Vec2i resolution) const {
        return min.x == 0 && min.y == 0 && max.x == resolution.x && max.y == resolution.y;
    }
};

// pbrt-v4: each pair is ordered and clamped to [0, 1], then the image holds
// pixels ceil(W·xmin) … ceil(W·xmax) − 1 (and likewise in y), the products
// taken in float. Throws InputError when that leaves no pixel.
inline PixelBounds filmPixelBounds(const Film& film, Vec2i resolution) {
    const float* c = film.cropWindow;
    for (int k = 0; k < 4; ++k)
        if (!std::isfinite(c[k])) throw InputError("the film's crop window is not a number");
    const auto clamp01 = [](float v) { return std::clamp(v, 0.0f, 1.0f); };
    const float x0 = clamp01(std::min(c[0], c[1])), x1 = clamp01(std::max(c[0], c[1]));
    const float y0 = clamp01(std::min(c[2], c[3])), y1 = clamp01(std::max(c[2], c[3]));
    const PixelBounds b{
        {int(std::ceil(float(resolution.x) * x0)), int(std::ceil(float(resolution.y) * y0))},
        {int(std::ceil(float(resolution.x) * x1)), int(std::ceil(float(resolution.y) * y1))}};
    if (b.width() <= 0 || b.height() <= 0)
        throw InputError("the film's crop window holds no pixel of the " +
                         std::to_string(resolution.x) + "x" + std::to_string(resolution.y) +
                         " image");
    return b;
}

}  // namespace pathlab
