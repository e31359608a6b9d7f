// Texture lookups and mappings against hand-computed values: bilinear and
// point filtering, the wrap modes, pbrt-v4's bottom-row-first (s, t), the
// colour encodings, each mapping at known points, checkerboard, bilerp, mix
// and scale.
#include <gtest/gtest.h>

#include <cmath>

#include "core/image.h"
#include "scene/scene.h"
#include "scene/textures/image_encoding.h"
#include "scene/textures/shading_texture.h"

namespace pathlab {
namespace {

const Vec3f kA{0.1f, 0.2f, 0.3f}, kB{0.5f, 0.6f, 0.7f}, kC{0.9f, 0.8f, 0.7f}, kD{0.0f, 1.0f, 0.5f};

// 2×2, top row first: A B / C D.
Texture twoByTwo() {
    Texture t;
    t.width = t.height = 2;
    t.texels = {kA, kB, kC, kD};
    return t;
}

void expectNear(Vec3f a, Vec3f b, float tol = 1e-6f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

TEST(Textures, BilinearLookupInterpolatesBetweenTexelCentres) {
    const Texture t = twoByTwo();
    // Texel centres sit at (i + 0.5)/2.
    expectNear(lookupImage(t, {0.25f, 0.25f}, TextureWrap::Repeat, false), kA);
    expectNear(lookupImage(t, {0.75f, 0.75f}, TextureWrap::Repeat, false), kD);
    expectNear(lookupImage(t, {0.5f, 0.25f}, TextureWrap::Repeat, false), (kA + kB) * 0.5f);
    expectNear(lookupImage(t, {0.5f, 0.5f}, TextureWrap::Repeat, false),
               (kA + kB + kC + kD) * 0.25f);
    // A quarter of the way from A's centre to B's.
    expectNear(lookupImage(t, {0.375f, 0.25f}, TextureWrap::Repeat, false),
               kA * 0.75f + kB * 0.25f);
}

TEST(Textures, WrapModesDecideWhatLiesBeyondTheEdges) {
    const Texture t = twoByTwo();
    // x = −0.25·2 − 0.5 = −1: the texel column left of the first.
    const Vec2f left{-0.25f, 0.25f};
    expectNear(lookupImage(t, left, TextureWrap::Repeat, false), kB);
    expectNear(lookupImage(t, left, TextureWrap::Clamp, false), kA);
    expectNear(lookupImage(t, left, TextureWrap::Black, false), Vec3f(0.0f));
    // Half way between A's centre and the black beyond the top edge.
    expectNear(lookupImage(t, {0.25f, 0.0f}, TextureWrap::Black, false), kA * 0.5f);
    // Repeat is periodic: one period to the right reads the same.
    expectNear(lookupImage(t, {1.375f, 0.75f}, TextureWrap::Repeat, false),
               lookupImage(t, {0.375f, 0.75f}, TextureWrap::Repeat, false));
}

TEST(Textures, PointFilterReadsTheNearestTexel) {
    const Texture t = twoByTwo();
    expectNear(lookupImage(t, {0.3f, 0.2f}, TextureWrap::Repeat, true), kA);   // x = 0.1
    expectNear(lookupImage(t, {0.55f, 0.2f}, TextureWrap::Repeat, true), kB);  // x = 0.6
    expectNear(lookupImage(t, {0.55f, 0.8f}, TextureWrap::Repeat, true), kD);
}

ShadingTexture imageNode() {
    ShadingTexture n;
    n.kind = TextureKind::Image;
    n.image = 0;
    return n;
}

TEST(Textures, ImageTexturesPutTZeroAtTheBottomRowScaleAndInvert) {
    const std::vector<Texture> images{twoByTwo()};
    std::vector<ShadingTexture> nodes{imageNode()};
    // v near 1 is the image's top row (pbrt-v4's ImageTexture flips t).
    expectNear(evaluateTexture(nodes, images, 0, {{0.25f, 0.75f}, {}}), kA);
    expectNear(evaluateTexture(nodes, images, 0, {{0.75f, 0.25f}, {}}), kD);
    nodes[0].scale = 2;
    nodes[0].invert = true;
    // max(0, 1 − 2·c) per channel.
    expectNear(evaluateTexture(nodes, images, 0, {{0.25f, 0.75f}, {}}), {0.8f, 0.6f, 0.4f});
    expectNear(evaluateTexture(nodes, images, 0, {{0.25f, 0.25f}, {}}), {0.0f, 0.0f, 0.0f});
    // A float texture reads the first channel.
    nodes[0] = imageNode();
    nodes[0].isFloat = true;
    expectNear(evaluateTexture(nodes, images, 0, {{0.75f, 0.75f}, {}}), Vec3f(kB.x));
}

TEST(Textures, EncodingsDecodeCodeValues) {
    ASSERT_TRUE(parseImageEncoding("sRGB"));
    ASSERT_TRUE(parseImageEncoding("linear"));
    const auto gamma = parseImageEncoding("gamma 2.2");
    ASSERT_TRUE(gamma);
    EXPECT_FLOAT_EQ(gamma->gamma, 2.2f);
    EXPECT_FALSE(parseImageEncoding("gamma"));
    EXPECT_FALSE(parseImageEncoding("gamma -1"));
    EXPECT_FALSE(parseImageEncoding("gamma 2x"));
    EXPECT_FALSE(parseImageEncoding("srgb"));
    // A PNG code value of 128 reads as sRGB-decoded; re-encoded it is 128/255
    // (linear) or (128/255)^2.2.
    Texture t;
    t.width = t.height = 1;
    const float code = 128 / 255.0f;
    t.texels = {Vec3f(srgbToLinear(code))};
    EXPECT_NEAR(t.texels[0].x, 0.2158605f, 1e-5f);  // ((c + 0.055)/1.055)^2.4
    Texture linear = t, gamma22 = t;
    reencodeTexels(linear, *parseImageEncoding("linear"));
    reencodeTexels(gamma22, *gamma);
    EXPECT_NEAR(linear.texels[0].y, code, 1e-5f);
    EXPECT_NEAR(gamma22.texels[0].z, std::pow(code, 2.2f), 1e-5f);
}

TEST(Textures, MappingsAtKnownPoints) {
    TextureMapping uv;
    uv.su = 2, uv.sv = 3, uv.du = 0.1f, uv.dv = -1;
    const Vec2f a = mapTextureCoordinates(uv, {{0.2f, 0.3f}, {}});
    EXPECT_NEAR(a.x, 0.5f, 1e-6f);
    EXPECT_NEAR(a.y, -0.1f, 1e-6f);

    // Spherical: (θ/π, φ/2π) about the texture space's origin, here (1, 2, 3).
    TextureMapping sph;
    sph.type = UvMapping::Spherical;
    sph.worldToTexture = Affine::translation({-1, -2, -3});
    const auto sphAt = [&](Vec3f d) {
        return mapTextureCoordinates(sph, {{}, Vec3f(1, 2, 3) + d});
    };
    EXPECT_NEAR(sphAt({0, 0, 5}).x, 0.0f, 1e-6f);
    EXPECT_NEAR(sphAt({0, 0, -2}).x, 1.0f, 1e-6f);
    EXPECT_NEAR(sphAt({0, 3, 0}).x, 0.5f, 1e-6f);
    EXPECT_NEAR(sphAt({0, 3, 0}).y, 0.25f, 1e-6f);
    EXPECT_NEAR(sphAt({-1, 0, 0}).y, 0.5f, 1e-6f);
    EXPECT_NEAR(sphAt({0, -1, 0}).y, 0.75f, 1e-6f);

    // Cylindrical: ((π + atan2(y, x))/2π, z).
    TextureMapping cyl;
    cyl.type = UvMapping::Cylindrical;
    const Vec2f c1 = mapTextureCoordinates(cyl, {{}, {1, 0, 0.3f}});
    EXPECT_NEAR(c1.x, 0.5f, 1e-6f);
    EXPECT_NEAR(c1.y, 0.3f, 1e-6f);
    EXPECT_NEAR(mapTextureCoordinates(cyl, {{}, {0, -2, 7}}).x, 0.25f, 1e-6f);

    // Planar: (du + p·v1, dv + p·v2) in texture space (scaled by 2 here).
    TextureMapping plane;
    plane.type = UvMapping::Planar;
    plane.v1 = {1, 0, 0}, plane.v2 = {0, 0, 1};
    plane.du = 0.5f, plane.dv = 0.25f;
    plane.worldToTexture = Affine::scaling({2, 2, 2});
    const Vec2f p = mapTextureCoordinates(plane, {{}, {0.1f, 7, 0.4f}});
    EXPECT_NEAR(p.x, 0.7f, 1e-6f);
    EXPECT_NEAR(p.y, 1.05f, 1e-6f);
}

ShadingTexture constant(Vec3f v) {
    ShadingTexture n;
    n.value = v;
    return n;
}

TEST(Textures, CheckerboardAlternatesBySquareParity) {
    const Vec3f red{1, 0, 0}, blue{0, 0, 1};
    std::vector<ShadingTexture> nodes{constant(red), constant(blue), {}};
    nodes[2].kind = TextureKind::Checkerboard;
    nodes[2].inputs[0] = 0, nodes[2].inputs[1] = 1;
    nodes[2].mapping.su = nodes[2].mapping.sv = 4;
    const auto at = [&](float u, float v) { return evaluateTexture(nodes, {}, 2, {{u, v}, {}}); };
    expectNear(at(0.1f, 0.1f), red);     // (0.4, 0.4): even, even
    expectNear(at(0.3f, 0.1f), blue);    // (1.2, 0.4)
    expectNear(at(0.3f, 0.3f), red);     // (1.2, 1.2)
    expectNear(at(-0.1f, 0.1f), blue);   // (−0.4, 0.4): floor −1 is odd
    expectNear(at(0.95f, 0.55f), blue);  // (3.8, 2.2)
}

TEST(Textures, BilerpMixAndScale) {
    std::vector<ShadingTexture> nodes(1);
    nodes[0].kind = TextureKind::Bilerp;
    nodes[0].corners[0] = Vec3f(0.0f);  // v00
    nodes[0].corners[1] = Vec3f(1.0f);  // v01
    nodes[0].corners[2] = Vec3f(2.0f);  // v10
    nodes[0].corners[3] = Vec3f(4.0f);  // v11
    // 0.75·0.5·0 + 0.25·0.5·2 + 0.75·0.5·1 + 0.25·0.5·4
    expectNear(evaluateTexture(nodes, {}, 0, {{0.25f, 0.5f}, {}}), Vec3f(1.125f));

    nodes = {constant(Vec3f(0.2f)), constant(Vec3f(1.0f)), constant(Vec3f(0.25f)), {}};
    nodes[3].kind = TextureKind::Mix;
    nodes[3].inputs[0] = 0, nodes[3].inputs[1] = 1, nodes[3].inputs[2] = 2;
    expectNear(evaluateTexture(nodes, {}, 3, {}), Vec3f(0.4f));  // 0.75·0.2 + 0.25·1

    nodes = {constant({0.2f, 0.4f, 0.6f}), constant(Vec3f(0.5f)), {}};
    nodes[2].kind = TextureKind::Scale;
    nodes[2].inputs[0] = 0, nodes[2].inputs[1] = 1;
    expectNear(evaluateTexture(nodes, {}, 2, {}), {0.1f, 0.2f, 0.3f});
}

}  // namespace
}  // namespace pathlab
