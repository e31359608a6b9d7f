// Shapes cut out by alpha (pbrt-v4's shape "alpha"): where it is 0 the sky
// comes through exactly, for camera and shadow rays alike; a constant alpha
// in (0, 1) lets that fraction of rays stop; an alpha texture cuts where it
// is 0 only.
#include <gtest/gtest.h>

#include "core/image.h"
#include "render/renderer.h"
#include "scene/pbrt/importer.h"
#include "scene/textures/alpha_cutout.h"
#include "scene_test_util.h"

namespace pathlab::pbrt {
namespace {

// An orthographic camera looking down −z at the unit square, a uniform sky of
// radiance 1.
const std::string kView = R"(LookAt 0.5 0.5 2  0.5 0.5 0  0 1 0
Camera "orthographic" "float screenwindow" [-0.5 0.5 -0.5 0.5]
Film "rgb" "integer xresolution" 16 "integer yresolution" 16
PixelFilter "box"
WorldBegin
LightSource "infinite" "rgb L" [1 1 1]
)";
std::string quad(float z, const std::string& extra) {
    const std::string h = std::to_string(z);
    return "Shape \"trianglemesh\" \"point3 P\" [-1 -1 " + h + "  2 -1 " + h + "  2 2 " + h +
           "  -1 2 " + h + "] \"integer indices\" [0 1 2  0 2 3] " + extra + "\n";
}

Image renderFile(const std::string& text, int spp = 4) {
    const ImportResult r = importPbrtText(text, "test.pbrt", ".", {});
    const RenderScene scene(r.scene);
    RenderSettings s;
    s.sampler = "independent";
    s.samplesPerPixel = spp;
    s.resolution = {16, 16};
    s.threads = 2;
    return render(scene, s).image;
}

double meanGreen(const Image& image) {
    double sum = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) sum += image.at(x, y).y;
    return sum / double(image.pixelCount());
}

TEST(AlphaCutout, AlphaZeroLetsTheSkyThroughExactly) {
    const std::string black = "Material \"diffuse\" \"rgb reflectance\" [0 0 0]\n";
    const Image opaque = renderFile(kView + black + quad(1, ""));
    EXPECT_EQ(meanGreen(opaque), 0.0);
    const Image cut = renderFile(kView + black + quad(1, "\"float alpha\" 0"));
    for (int y = 0; y < cut.height; ++y)
        for (int x = 0; x < cut.width; ++x) ASSERT_FLOAT_EQ(cut.at(x, y).y, 1.0f) << x << ", " << y;
}

TEST(AlphaCutout, ShadowRaysPassWhereAlphaIsZero) {
    // A grey floor (albedo 0.5) under the sky: radiance 0.5 in expectation.
    // A black roof over it cut out entirely changes nothing; opaque, it
    // blocks the sky (both the camera's view and the floor's light).
    const std::string floor = "Material \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]\n" +
                              quad(0, "") + "Material \"diffuse\" \"rgb reflectance\" [0 0 0]\n";
    const double open = meanGreen(renderFile(kView + floor, 16));
    const double cut = meanGreen(renderFile(kView + floor + quad(1, "\"float alpha\" 0"), 16));
    EXPECT_NEAR(open, 0.5, 0.02);
    EXPECT_NEAR(cut, 0.5, 0.02);
    EXPECT_LT(meanGreen(renderFile(kView + floor + quad(1, ""), 4)), 0.01);
}

TEST(AlphaCutout, PartialAlphaStopsThatFractionOfRays) {
    const std::string black = "Material \"diffuse\" \"rgb reflectance\" [0 0 0]\n";
    // Each camera ray stops with probability 0.3 (a hash of the ray): the
    // sky shows through 70% of them. 16·16·16 rays: σ ≈ 0.007.
    const double m = meanGreen(renderFile(kView + black + quad(1, "\"float alpha\" 0.3"), 16));
    EXPECT_NEAR(m, 0.7, 0.03);
}

TEST(AlphaCutout, ATextureCutsWhereItIsZero) {
    // A checkerboard alpha over [−1, 2]² (uv default corners per triangle are
    // replaced by explicit uvs): the left half of the view is cut (alpha 0),
    // the right half opaque (alpha 1).
    const std::string text =
        kView +
        "Texture \"half\" \"float\" \"bilerp\" \"float v00\" 0 \"float v01\" 0 \"float v10\" 1 "
        "\"float v11\" 1\n"
        "Texture \"step\" \"float\" \"scale\" \"texture tex\" \"half\" \"float scale\" 1\n"
        "Material \"diffuse\" \"rgb reflectance\" [0 0 0]\n" +
        quad(1, "\"point2 uv\" [0 0  1 0  1 1  0 1] \"texture alpha\" \"step\"");
    const ImportResult r = importPbrtText(text, "test.pbrt", ".", {});
    ASSERT_GE(r.scene.meshes.at(0).alphaTexture, 0);
    const AlphaCutout cutout{&r.scene.meshes[0], &r.scene};
    // Barycentrics (b1, b2) on triangle 0 (corners 0, 1, 2): u = b1 + b2.
    EXPECT_FALSE(alphaKeepsHit(cutout, {0, 0, 2}, {0, 0, -1}, 0, 0.0f, 0.0f));  // u = 0
    EXPECT_TRUE(alphaKeepsHit(cutout, {0, 0, 2}, {0, 0, -1}, 0, 0.9f, 0.1f));   // u = 1
}

}  // namespace
}  // namespace pathlab::pbrt
