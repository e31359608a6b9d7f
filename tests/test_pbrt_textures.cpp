// pbrt-v4's Texture directive through the importer and the renderer: the
// nodes it makes, textured material parameters, an image file's encodings,
// a textured plane under a uniform sky rendered against its albedos, and the
// one-line errors for bad textures.
#include <gtest/gtest.h>

#include <cmath>

#include "cli_runner.h"
#include "core/image.h"
#include "render/renderer.h"
#include "scene/pbrt/importer.h"
#include "scene_test_util.h"

namespace pathlab::pbrt {
namespace {

using test::inputErrorOf;
using test::ScratchDir;

const std::string kQuad =
    R"(Shape "trianglemesh" "point3 P" [0 0 0  1 0 0  1 1 0  0 1 0] "integer indices" [0 1 2  0 2 3] "point2 uv" [0 0  1 0  1 1  0 1])";

ImportResult load(const std::string& text, const std::string& dir = ".") {
    return importPbrtText(text, "test.pbrt", dir, {});
}
std::string errorOf(const std::string& text, const std::string& dir = ".") {
    return inputErrorOf([&] { load(text, dir); });
}
const Material& firstMaterial(const ImportResult& r) {
    return r.scene.materials.at(size_t(r.scene.meshes.at(0).material));
}

TEST(PbrtTextures, CheckerboardReflectanceBecomesATextureNode) {
    const ImportResult r = load(R"(WorldBegin
Texture "checks" "spectrum" "checkerboard" "float uscale" 4 "float vscale" 2
    "rgb tex1" [0.1 0.2 0.3] "rgb tex2" [0.7 0.8 0.9]
Material "diffuse" "texture reflectance" "checks"
)" + kQuad);
    const Material& m = firstMaterial(r);
    ASSERT_GE(m.albedoTexture, 0);
    const auto& nodes = r.scene.shadingTextures;
    const ShadingTexture& checks = nodes.at(size_t(m.albedoTexture));
    EXPECT_EQ(checks.kind, TextureKind::Checkerboard);
    EXPECT_FLOAT_EQ(checks.mapping.su, 4);
    EXPECT_FLOAT_EQ(checks.mapping.sv, 2);
    // (u, v) = (0.3, 0.1) → (s, t) = (1.2, 0.2): an odd square, tex2.
    const Vec3f c = evaluateTexture(nodes, r.scene.textures, m.albedoTexture, {{0.3f, 0.1f}, {}});
    EXPECT_FLOAT_EQ(c.y, 0.8f);
}

TEST(PbrtTextures, FloatTexturesDriveRoughnessAndMixAmount) {
    const ImportResult r = load(R"(WorldBegin
Texture "rough" "float" "bilerp" "float v00" 0.04 "float v01" 0.04 "float v10" 0.36 "float v11" 0.36
MakeNamedMaterial "a" "string type" "diffuse"
MakeNamedMaterial "b" "string type" "conductor" "texture roughness" "rough"
Material "mix" "string materials" ["a" "b"] "texture amount" "rough"
)" + kQuad);
    const Material& mix = firstMaterial(r);
    ASSERT_EQ(mix.type, MaterialType::Mix);
    const Material& metal = r.scene.materials.at(size_t(mix.mix[1]));
    EXPECT_GE(metal.roughnessTexture, 0);
    EXPECT_EQ(metal.roughnessVTexture, metal.roughnessTexture);  // v falls back to roughness
    EXPECT_TRUE(metal.remapRoughness);
    EXPECT_EQ(mix.amountTexture, metal.roughnessTexture);
    // The renderer picks the mix's component by the textured amount: 0.04
    // at u = 0 (< every hash value but a few), so the diffuse one.
    SceneDescription s = r.scene;
    const RenderScene scene(std::move(s));
    int diffuse = 0;
    for (int i = 0; i < 200; ++i) {
        const Vec3f p{0, float(i) / 200, 0};
        diffuse +=
            scene.mixComponent(r.scene.meshes[0].material, p, {0, 0, -1}, {0, p.y}) == mix.mix[0];
    }
    EXPECT_GT(diffuse, 170);  // expected 192 (0.96 of 200)
}

TEST(PbrtTextures, ImageMapEncodingsAndOrientation) {
    ScratchDir dir;
    // Codes 64 and 192 in the top row, 255 and 0 in the bottom one, written
    // as sRGB so that the file holds exactly those codes.
    Image img(2, 2);
    const auto code = [](int c) { return Vec3f(srgbToLinear(float(c) / 255)); };
    img.set(0, 0, code(64)), img.set(1, 0, code(192));
    img.set(0, 1, code(255)), img.set(1, 1, code(0));
    writeImage((dir.path() / "tex.png").string(), img);
    const ImportResult r = load(R"(WorldBegin
Texture "srgb" "spectrum" "imagemap" "string filename" "tex.png"
Texture "lin" "spectrum" "imagemap" "string filename" "tex.png" "string encoding" "linear" "string filter" "point"
Material "diffuse" "texture reflectance" "lin"
)" + kQuad,
                                dir.path().string());
    ASSERT_EQ(r.scene.textures.size(), 2u);  // one image per encoding
    const auto& nodes = r.scene.shadingTextures;
    const int lin = firstMaterial(r).albedoTexture;
    EXPECT_TRUE(nodes.at(size_t(lin)).pointFilter);
    const auto at = [&](int node, float u, float v) {
        return evaluateTexture(nodes, r.scene.textures, node, {{u, v}, {}}).x;
    };
    // v = 0.75 is the top row: codes 64 and 192.
    EXPECT_NEAR(at(lin, 0.25f, 0.75f), 64 / 255.0f, 1e-4f);
    EXPECT_NEAR(at(lin, 0.75f, 0.75f), 192 / 255.0f, 1e-4f);
    EXPECT_NEAR(at(lin, 0.25f, 0.25f), 1.0f, 1e-4f);
    EXPECT_NEAR(at(lin - 1, 0.25f, 0.75f), srgbToLinear(64 / 255.0f), 1e-4f);
}

// A unit square of checkerboard albedos 0.2 and 0.8 (4 × 4 squares) under a
// uniform sky of radiance 1, seen from above by an orthographic camera that
// frames it exactly: each square's pixels average its albedo.
TEST(PbrtTextures, TexturedPlaneUnderUniformSkyShowsItsAlbedos) {
    const ImportResult r = load(R"(LookAt 0.5 0.5 1  0.5 0.5 0  0 1 0
Camera "orthographic" "float screenwindow" [-0.5 0.5 -0.5 0.5]
Film "rgb" "integer xresolution" 32 "integer yresolution" 32
PixelFilter "box"
WorldBegin
LightSource "infinite" "rgb L" [1 1 1]
Texture "checks" "spectrum" "checkerboard" "float uscale" 4 "float vscale" 4
    "rgb tex1" [0.2 0.2 0.2] "rgb tex2" [0.8 0.8 0.8]
Material "diffuse" "texture reflectance" "checks"
)" + kQuad);
    const RenderScene scene(r.scene);
    RenderSettings s;
    s.sampler = "independent";
    s.samplesPerPixel = 16;
    s.resolution = {32, 32};
    s.threads = 2;
    const Image image = render(scene, s).image;
    const auto squareMean = [&](int bx, int by) {
        double sum = 0;
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 8; ++x) sum += image.at(bx * 8 + x, by * 8 + y).y;
        return sum / 64;
    };
    // Adjacent squares alternate; which one is which depends on the camera's
    // handedness, so compare with the corner square.
    const double corner = squareMean(0, 0) < 0.5 ? 0.2 : 0.8;
    double total = 0;
    for (int by = 0; by < 4; ++by)
        for (int bx = 0; bx < 4; ++bx) {
            const double mean = squareMean(bx, by);
            total += mean;
            const double expected = (bx + by) % 2 == 0 ? corner : 1 - corner;
            EXPECT_NEAR(mean, expected, 0.04) << "square " << bx << ", " << by;
        }
    EXPECT_NEAR(total / 16, 0.5, 0.01);
}

TEST(PbrtTextures, BadTexturesAreOneLineErrorsAtTheirPlace) {
    const std::string e1 = errorOf(
        "WorldBegin\nTexture \"t\" \"spectrum\" \"imagemap\" \"string filename\" \"nope.png\"\n");
    EXPECT_EQ(e1.rfind("test.pbrt:2:", 0), 0u) << e1;
    EXPECT_NE(e1.find("'nope.png' does not exist"), std::string::npos) << e1;
    const std::string e2 = errorOf("WorldBegin\nTexture \"t\" \"spectrum\" \"swirl\"\n");
    EXPECT_EQ(e2, "test.pbrt:2:1: Texture 't': unknown texture class 'swirl'");
    const std::string e3 =
        errorOf("WorldBegin\nMaterial \"diffuse\" \"texture reflectance\" \"missing\"\n" + kQuad);
    EXPECT_EQ(e3.rfind("test.pbrt:2:", 0), 0u) << e3;
    EXPECT_NE(e3.find("no spectrum texture named 'missing'"), std::string::npos) << e3;
    const std::string e4 = errorOf(
        "WorldBegin\nTexture \"f\" \"float\" \"constant\" \"float value\" 0.5\n"
        "Material \"diffuse\" \"texture reflectance\" \"f\"\n" +
        kQuad);
    EXPECT_NE(e4.find("needs a spectrum texture, but 'f' is a float texture"), std::string::npos)
        << e4;
    const std::string e5 = errorOf(
        "WorldBegin\nTexture \"c\" \"spectrum\" \"checkerboard\" \"string mapping\" \"cubic\"\n");
    EXPECT_NE(e5.find("unknown mapping 'cubic'"), std::string::npos) << e5;
    const std::string e6 = errorOf(
        "WorldBegin\nTexture \"c\" \"float\" \"constant\"\nTexture \"c\" \"float\" \"constant\"\n");
    EXPECT_EQ(e6, "test.pbrt:3:1: Texture 'c' is already defined");
}

TEST(PbrtTextures, MissingTextureFileFailsTheCommandWithExitCodeTwo) {
    const auto dir = testing::scratchDirectory("pbrt-textures");
    ScratchDir scenes;
    const std::string scene = scenes.write(
        "s.pbrt",
        "Film \"rgb\" \"integer xresolution\" 8 \"integer yresolution\" 8\nWorldBegin\n"
        "Texture \"t\" \"spectrum\" \"imagemap\" \"string filename\" \"gone.png\"\n"
        "Material \"diffuse\" \"texture reflectance\" \"t\"\nShape \"sphere\"\n");
    const std::string out = (dir / "a.exr").string();
    const auto result = testing::runPathlab("render --scene " + scene + " -o " + out, dir);
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_EQ(result.errLines(), 1) << result.err;
    EXPECT_NE(result.err.find(scene + ":3:"), std::string::npos) << result.err;
    EXPECT_FALSE(std::filesystem::exists(out));
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace pathlab::pbrt
