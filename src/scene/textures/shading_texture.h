// Textures that material parameters refer to: pbrt-v4's texture classes
// (PBRT 4th ed., chapter 10; pbrt-v4's textures.h) as a small graph of nodes
// evaluated at a hit from its (u, v) and its world-space position. Every node
// yields RGB; a float texture yields the same value in all three channels.
// The image texels themselves live in SceneDescription::textures.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/affine.h"
#include "core/math.h"

namespace pathlab {

struct Texture;

// How a hit becomes the texture coordinates (s, t) (pbrt-v4's
// TextureMapping2D; PBRT 4th ed., 10.2).
enum class UvMapping {
    Uv,           // (su·u + du, sv·v + dv)
    Spherical,    // (θ/π, φ/2π) of the point in texture space, about its origin
    Cylindrical,  // ((π + atan2(y, x))/2π, z) in texture space
    Planar,       // (du + p·v1, dv + p·v2) in texture space
};

struct TextureMapping {
    UvMapping type = UvMapping::Uv;
    float su = 1, sv = 1, du = 0, dv = 0;
    Vec3f v1{1, 0, 0}, v2{0, 1, 0};  // planar
    Affine worldToTexture;           // the inverse of the CTM at the Texture directive
};

// What an image lookup outside [0, 1]² reads (pbrt-v4's WrapMode).
enum class TextureWrap { Repeat, Black, Clamp };
// pbrt-v4's names, "repeat", "black", "clamp"; nothing for any other.
inline std::optional<TextureWrap> textureWrapNamed(const std::string& name) {
    if (name == "repeat") return TextureWrap::Repeat;
    if (name == "black") return TextureWrap::Black;
    if (name == "clamp") return TextureWrap::Clamp;
    return std::nullopt;
}

enum class TextureKind {
    Constant,      // `value`
    Image,         // texels of `image`, times `scale`, inverted (1 − x, ≥ 0) if `invert`
    Checkerboard,  // inputs[0] on even squares of (s, t), inputs[1] on odd ones
    Scale,         // inputs[0] · inputs[1]
    Mix,           // (1 − a)·inputs[0] + a·inputs[1], a = inputs[2]
    Bilerp,        // corners v00, v01, v10, v11 interpolated at (s, t)
};

struct ShadingTexture {
    TextureKind kind = TextureKind::Constant;
    // A float texture of an RGB image reads its first channel, as pbrt-v4's
    // CPU MIPMap::Texel<Float> does.
    bool isFloat = false;
    TextureMapping mapping;
    Vec3f value{0.0f};
    int image = -1;            // index into SceneDescription::textures (linear, top row first)
    bool pointFilter = false;  // nearest texel instead of bilinear
    TextureWrap wrap = TextureWrap::Repeat;
    float scale = 1;
    bool invert = false;
    int inputs[3] = {-1, -1, -1};  // indices of earlier nodes
    Vec3f corners[4] = {};         // bilerp: v00, v01, v10, v11
};

// Where a texture is evaluated.
struct TextureContext {
    Vec2f uv;
    Vec3f p;  // world space
};

// (s, t) of a hit under a mapping.
Vec2f mapTextureCoordinates(const TextureMapping& mapping, const TextureContext& ctx);

// An image at (s, t) with pbrt-v4's convention: t = 0 is the image's bottom
// row; bilinear between texel centres (Image::BilerpChannel) or the nearest
// texel (MIPMap's point filter), beyond the edges as `wrap` says.
Vec3f lookupImage(const Texture& image, Vec2f st, TextureWrap wrap, bool pointFilter);

// Node `index` of `nodes` at ctx (inputs are evaluated only where needed).
Vec3f evaluateTexture(const std::vector<ShadingTexture>& nodes, const std::vector<Texture>& images,
                      int index, const TextureContext& ctx);

}  // namespace pathlab
