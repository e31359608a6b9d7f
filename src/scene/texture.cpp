#include <cmath>

#include "scene/scene.h"

namespace pathlab {

Vec3f Texture::lookup(Vec2f uv) const {
    if (width <= 0 || height <= 0) return Vec3f(0.0f);
    const float fx = (uv.x - std::floor(uv.x)) * width - 0.5f;
    const float fy = (uv.y - std::floor(uv.y)) * height - 0.5f;
    const float x0f = std::floor(fx), y0f = std::floor(fy);
    const float tx = fx - x0f, ty = fy - y0f;
    // fx lies in [−0.5, width − 0.5] (the fraction above is in [0, 1]), so
    // x0 in [−1, width − 1] and x0 + 1 in [0, width]: one step wraps them, with
    // no integer division (four per lookup were a tenth of a wolf frame's
    // shading time).
    auto wrap = [](int i, int n) { return i < 0 ? i + n : (i >= n ? i - n : i); };
    const int x0 = wrap(int(x0f), width), x1 = wrap(int(x0f) + 1, width);
    const int y0 = wrap(int(y0f), height), y1 = wrap(int(y0f) + 1, height);
    auto texel = [&](int x, int y) { return texels[size_t(y) * width + x]; };
    return lerp(ty, lerp(tx, texel(x0, y0), texel(x1, y0)), lerp(tx, texel(x0, y1), texel(x1, y1)));
}

}  // namespace pathlab
