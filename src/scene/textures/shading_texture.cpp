// pbrt-v4's texture mappings and texture classes (textures.h, textures.cpp,
// util/image.h), evaluated without ray differentials: pathlab samples the
// finest image level and draws no filter footprint (docs/pbrt-format.md).
#include "scene/textures/shading_texture.h"

#include <algorithm>
#include <cmath>

#include "scene/scene.h"

namespace pathlab {

namespace {

// θ/π and φ/2π of a texture-space direction (pbrt-v4's SphericalTheta, SphericalPhi).
Vec2f sphericalST(Vec3f q) {
    const float len = length(q);
    if (!(len > 0)) return {0, 0};
    const Vec3f d = q / len;
    const float theta = std::acos(std::clamp(d.z, -1.0f, 1.0f));
    float phi = std::atan2(d.y, d.x);
    if (phi < 0) phi += 2 * kPi;
    return {theta / kPi, phi / (2 * kPi)};
}

// A texel index beyond [0, n): wrapped, clamped, or −1 for black.
int remapTexel(int i, int n, TextureWrap wrap) {
    if (i >= 0 && i < n) return i;
    switch (wrap) {
        case TextureWrap::Repeat: {
            const int r = i % n;
            return r < 0 ? r + n : r;
        }
        case TextureWrap::Clamp:
            return std::clamp(i, 0, n - 1);
        case TextureWrap::Black:
            break;
    }
    return -1;
}

Vec3f texelAt(const Texture& image, int x, int y, TextureWrap wrap) {
    x = remapTexel(x, image.width, wrap);
    y = remapTexel(y, image.height, wrap);
    if (x < 0 || y < 0) return Vec3f(0.0f);
    return image.texels[size_t(y) * size_t(image.width) + size_t(x)];
}

Vec3f imageValue(const ShadingTexture& node, const std::vector<Texture>& images,
                 const TextureContext& ctx) {
    Vec2f st = mapTextureCoordinates(node.mapping, ctx);
    // pbrt-v4's ImageTexture: (s, t) = (0, 0) is the image's lower left corner.
    st.y = 1 - st.y;
    Vec3f c = lookupImage(images[size_t(node.image)], st, node.wrap, node.pointFilter);
    if (node.isFloat) c = Vec3f(c.x);
    c = c * node.scale;
    if (node.invert) c = Vec3f(1.0f) - c;
    return {std::max(c.x, 0.0f), std::max(c.y, 0.0f), std::max(c.z, 0.0f)};
}

// pbrt-v4's Checkerboard() without a filter footprint: 0 on squares whose
// integer parts of s and t have equal parity, else 1.
float checkerboardWeight(Vec2f st) {
    // Beyond ±2^52 every float is an even integer (and NaN has no square):
    // clamped so that the conversions below stay defined.
    constexpr float kLimit = 0x1p52f;
    if (!std::isfinite(st.x) || !std::isfinite(st.y)) return 0;
    st = {std::clamp(st.x, -kLimit, kLimit), std::clamp(st.y, -kLimit, kLimit)};
    const bool oddS = (int64_t(std::floor(st.x)) & 1) != 0;
    const bool oddT = (int64_t(std::floor(st.y)) & 1) != 0;
    return oddS != oddT ? 1.0f : 0.0f;
}

}  // namespace

Vec2f mapTextureCoordinates(const TextureMapping& m, const TextureContext& ctx) {
    switch (m.type) {
        case UvMapping::Uv:
            return {m.su * ctx.uv.x + m.du, m.sv * ctx.uv.y + m.dv};
        case UvMapping::Spherical:
            return sphericalST(m.worldToTexture.point(ctx.p));
        case UvMapping::Cylindrical: {
            const Vec3f q = m.worldToTexture.point(ctx.p);
            return {(kPi + std::atan2(q.y, q.x)) / (2 * kPi), q.z};
        }
        case UvMapping::Planar: {
            const Vec3f q = m.worldToTexture.point(ctx.p);
            return {m.du + dot(q, m.v1), m.dv + dot(q, m.v2)};
        }
    }
    return ctx.uv;
}

Vec3f lookupImage(const Texture& image, Vec2f st, TextureWrap wrap, bool pointFilter) {
    if (image.width <= 0 || image.height <= 0) return Vec3f(0.0f);
    float x = st.x * float(image.width) - 0.5f, y = st.y * float(image.height) - 0.5f;
    // Coordinates far outside the image are clamped before becoming texel
    // indices (a float beyond the int range would be undefined to convert).
    constexpr float kLimit = 0x1p30f;
    if (!(std::abs(x) < kLimit && std::abs(y) < kLimit)) {
        if (!std::isfinite(x) || !std::isfinite(y)) return Vec3f(0.0f);
        x = std::clamp(x, -kLimit, kLimit), y = std::clamp(y, -kLimit, kLimit);
    }
    if (pointFilter) return texelAt(image, int(std::lround(x)), int(std::lround(y)), wrap);
    const float fx = std::floor(x), fy = std::floor(y);
    const int xi = int(fx), yi = int(fy);
    const float dx = x - fx, dy = y - fy;
    return texelAt(image, xi, yi, wrap) * ((1 - dx) * (1 - dy)) +
           texelAt(image, xi + 1, yi, wrap) * (dx * (1 - dy)) +
           texelAt(image, xi, yi + 1, wrap) * ((1 - dx) * dy) +
           texelAt(image, xi + 1, yi + 1, wrap) * (dx * dy);
}

Vec3f evaluateTexture(const std::vector<ShadingTexture>& nodes, const std::vector<Texture>& images,
                      int index, const TextureContext& ctx) {
    const ShadingTexture& node = nodes[size_t(index)];
    const auto input = [&](int i) { return evaluateTexture(nodes, images, node.inputs[i], ctx); };
    switch (node.kind) {
        case TextureKind::Constant:
            return node.value;
        case TextureKind::Image:
            return imageValue(node, images, ctx);
        case TextureKind::Checkerboard:
            return checkerboardWeight(mapTextureCoordinates(node.mapping, ctx)) == 0 ? input(0)
                                                                                     : input(1);
        case TextureKind::Scale:
            return input(0) * input(1);
        case TextureKind::Mix: {
            const float a = input(2).x;
            // As pbrt-v4's MixTexture: an input with weight 0 is not evaluated.
            const Vec3f t0 = a != 1 ? input(0) : Vec3f(0.0f);
            const Vec3f t1 = a != 0 ? input(1) : Vec3f(0.0f);
            return t0 * (1 - a) + t1 * a;
        }
        case TextureKind::Bilerp: {
            const Vec2f st = mapTextureCoordinates(node.mapping, ctx);
            const float s = st.x, t = st.y;
            return node.corners[0] * ((1 - s) * (1 - t)) + node.corners[2] * (s * (1 - t)) +
                   node.corners[1] * ((1 - s) * t) + node.corners[3] * (s * t);
        }
    }
    return Vec3f(0.0f);
}

}  // namespace pathlab
