// The JSON format's textures: a JSON scene and the equivalent .pbrt file
// (image maps in two encodings, checkerboard, scale, bilerp, mix, constant,
// uv and spherical mappings, a textured roughness, a bump map from a float
// image, an alpha cut-out) render the same image bit for bit; the texture
// graph a JSON file makes; and bad texture keys as one-line errors, exit 2.
#include <gtest/gtest.h>

#include "cli_runner.h"
#include "core/image.h"
#include "render/renderer.h"
#include "scene/json_scene.h"
#include "scene/pbrt/importer.h"
#include "scene_test_util.h"

namespace pathlab {
namespace {

using test::inputErrorOf;
using test::ScratchDir;

// A 4×4 PNG of varied colours (its codes are what the file holds).
void writeCheckImage(const ScratchDir& dir) {
    Image img(4, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
            img.set(x, y, Vec3f(float(x) / 3, float(y) / 3, float((x + y) % 2) * 0.8f + 0.1f));
    writeImage((dir.path() / "tex.png").string(), img);
}

const char* kPbrt = R"(LookAt 0.5 -1.2 1.6  0.5 0.5 0  0 0 1
Camera "perspective" "float fov" 50
Film "rgb" "integer xresolution" 24 "integer yresolution" 18
WorldBegin
LightSource "infinite" "rgb L" [0.75 0.75 0.75]
Texture "img" "spectrum" "imagemap" "string filename" "tex.png" "string filter" "point"
  "string wrap" "clamp" "float scale" 0.875 "float udelta" 0.25
Texture "checks" "spectrum" "checkerboard" "float uscale" 4 "float vscale" 2
  "texture tex1" "img" "rgb tex2" [0.25 0.5 0.125]
Texture "heightimg" "float" "imagemap" "string filename" "tex.png" "string encoding" "linear"
  "bool invert" true
Texture "heights" "float" "scale" "texture tex" "heightimg" "float scale" 0.02
Material "diffuse" "texture reflectance" "checks" "texture displacement" "heights"
Shape "trianglemesh" "point3 P" [0 0 0  1 0 0  1 1 0  0 1 0] "integer indices" [0 1 2  0 2 3]
  "point2 uv" [0 0  1 0  1 1  0 1]
Texture "cut" "float" "checkerboard" "float uscale" 3 "float vscale" 3
  "float tex1" 1 "float tex2" 0.25
Texture "rough" "float" "bilerp" "float v00" 0.01 "float v01" 0.25 "float v10" 0.5 "float v11" 0.0625
Material "conductor" "texture roughness" "rough"
Shape "trianglemesh" "point3 P" [0 0.75 0  1 0.75 0  1 0.75 1  0 0.75 1]
  "integer indices" [0 1 2  0 2 3] "point2 uv" [0 0  1 0  1 1  0 1] "texture alpha" "cut"
AttributeBegin
  Translate 0.5 0.25 0.25
  Texture "fade" "float" "bilerp" "string mapping" "spherical" "float v00" 0 "float v01" 1
    "float v10" 0 "float v11" 1
  Texture "ball" "spectrum" "mix" "texture tex1" "img" "rgb tex2" [0.125 0.25 0.75]
    "texture amount" "fade"
  Texture "half" "spectrum" "constant" "rgb value" [0.5 0.5 0.5]
  Material "diffusetransmission" "texture reflectance" "ball" "texture transmittance" "half"
  Shape "sphere" "float radius" 0.25
AttributeEnd
)";

// The same scene in pathlab's JSON format (camera, film and resolution are
// copied from the .pbrt one: the two formats' cameras differ in spelling).
const char* kJson = R"({
  "camera": {"eye": [0, 0, 1], "target": [0, 0, 0], "fovY": 50},
  "environment": 0.75,
  "textures": {
    "img": {"type": "imagemap", "file": "tex.png", "filter": "point", "wrap": "clamp",
            "scale": 0.875, "mapping": {"type": "uv", "udelta": 0.25}},
    "checks": {"type": "checkerboard", "mapping": {"type": "uv", "uscale": 4, "vscale": 2},
               "tex1": "img", "tex2": [0.25, 0.5, 0.125]},
    "heightimg": {"type": "imagemap", "float": true, "file": "tex.png", "encoding": "linear",
                  "invert": true},
    "heights": {"type": "scale", "float": true, "tex": "heightimg", "scale": 0.02},
    "cut": {"type": "checkerboard", "float": true, "mapping": {"type": "uv", "uscale": 3, "vscale": 3},
            "tex1": 1, "tex2": 0.25},
    "rough": {"type": "bilerp", "float": true, "v00": 0.01, "v01": 0.25, "v10": 0.5, "v11": 0.0625},
    "fade": {"type": "bilerp", "float": true, "v00": 0, "v01": 1, "v10": 0, "v11": 1,
             "mapping": {"type": "spherical", "transform": {"translate": [0.5, 0.25, 0.25]}}},
    "ball": {"type": "mix", "tex1": "img", "tex2": [0.125, 0.25, 0.75], "amount": "fade"},
    "half": {"type": "constant", "value": 0.5}
  },
  "materials": {
    "floor": {"type": "diffuse", "albedo": "checks", "displacement": "heights"},
    "metal": {"type": "conductor", "metal": "gold", "roughness": "rough", "remapRoughness": true},
    "ball": {"type": "diffusetransmission", "reflectance": "ball", "transmittance": "half"}
  },
  "meshes": [
    {"material": "floor", "positions": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]],
     "indices": [0, 1, 2, 0, 2, 3], "uvs": [[0, 0], [1, 0], [1, 1], [0, 1]]},
    {"material": "metal", "positions": [[0, 0.75, 0], [1, 0.75, 0], [1, 0.75, 1], [0, 0.75, 1]],
     "indices": [0, 1, 2, 0, 2, 3], "uvs": [[0, 0], [1, 0], [1, 1], [0, 1]], "alpha": "cut"}
  ],
  "spheres": [{"center": [0.5, 0.25, 0.25], "radius": 0.25, "material": "ball"}]
})";

TEST(JsonTextures, RendersAsTheEquivalentPbrtFileBitForBit) {
    ScratchDir dir;
    writeCheckImage(dir);
    SceneDescription p = pbrt::importPbrtText(kPbrt, "s.pbrt", dir.path().string(), {}).scene;
    SceneDescription j = parseJsonScene(kJson, dir.path(), "s.json");
    // The conductor's index is not textured: take the .pbrt file's (copper).
    ASSERT_EQ(p.materials.size(), j.materials.size());
    j.materials[1].eta = p.materials[1].eta, j.materials[1].k = p.materials[1].k;
    j.camera = p.camera, j.film = p.film, j.resolution = p.resolution;
    RenderSettings s;
    s.samplesPerPixel = 4;
    s.maxDepth = 4;
    const Image a = render(RenderScene(p), s).image, b = render(RenderScene(j), s).image;
    ASSERT_EQ(a.rgb.size(), b.rgb.size());
    EXPECT_TRUE(a.rgb == b.rgb);
    // Not a vacuous equality: the textures vary the image.
    double lo = 1e9, hi = 0;
    for (float v : a.rgb) lo = std::min(lo, double(v)), hi = std::max(hi, double(v));
    EXPECT_GT(hi - lo, 0.2);
}

TEST(JsonTextures, GraphMatchesTheJsonFile) {
    ScratchDir dir;
    writeCheckImage(dir);
    const SceneDescription s = parseJsonScene(kJson, dir.path(), "s.json");
    ASSERT_EQ(s.textures.size(), 2u);  // tex.png in sRGB and linear encodings
    const Material& floor = s.materials[0];
    const ShadingTexture& checks = s.shadingTextures.at(size_t(floor.albedoTexture));
    EXPECT_EQ(checks.kind, TextureKind::Checkerboard);
    EXPECT_FLOAT_EQ(checks.mapping.su, 4);
    const ShadingTexture& img = s.shadingTextures.at(size_t(checks.inputs[0]));
    EXPECT_EQ(img.kind, TextureKind::Image);
    EXPECT_TRUE(img.pointFilter);
    EXPECT_EQ(img.wrap, TextureWrap::Clamp);
    EXPECT_FLOAT_EQ(img.scale, 0.875f);
    const Material& metal = s.materials[1];
    EXPECT_GE(metal.roughnessTexture, 0);
    EXPECT_EQ(metal.roughnessVTexture, metal.roughnessTexture);
    EXPECT_TRUE(metal.remapRoughness);
    // "cut": 1 on even squares of 3 × 3, 0.25 on odd ones.
    const auto alpha = [&](float u, float v) {
        return evaluateTexture(s.shadingTextures, s.textures, s.meshes[1].alphaTexture,
                               {{u, v}, {}})
            .x;
    };
    EXPECT_EQ(alpha(0.1f, 0.1f), 1.0f);
    EXPECT_EQ(alpha(0.4f, 0.1f), 0.25f);
    // The spherical mapping's texture space is centred on the sphere.
    const ShadingTexture& ball = s.shadingTextures.at(size_t(s.materials[2].albedoTexture));
    const ShadingTexture& fade = s.shadingTextures.at(size_t(ball.inputs[2]));
    const Vec3f origin = fade.mapping.worldToTexture.point({0.5f, 0.25f, 0.25f});
    EXPECT_TRUE(origin.x == 0 && origin.y == 0 && origin.z == 0);
    // A constant roughness with remapRoughness is pbrt-v4's: alpha √r.
    const SceneDescription r = parseJsonScene(
        R"({"camera": {"eye": [0, 0, 1], "target": [0, 0, 0], "fovY": 50},
            "materials": {"m": {"type": "dielectric", "roughness": 0.25, "remapRoughness": true}},
            "spheres": [{"center": [0, 0, 0], "radius": 1, "material": "m"}]})",
        ".", "r.json");
    EXPECT_FLOAT_EQ(r.materials[0].roughness, 0.5f);
}

// A scene with one material `m` and one texture section `t`, on a quad.
std::string sceneWith(const std::string& textures, const std::string& material,
                      const std::string& meshExtra = "") {
    return R"({"camera": {"eye": [0, 0, 1], "target": [0, 0, 0], "fovY": 50},
      "textures": {)" +
           textures + R"(}, "materials": {"m": )" + material + R"(},
      "meshes": [{"material": "m", "quads": [[[0,0,0], [1,0,0], [1,1,0], [0,1,0]]])" +
           meshExtra + "}]}";
}

std::string errorOf(const std::string& text) {
    return inputErrorOf([&] { parseJsonScene(text, ".", "s.json"); });
}

TEST(JsonTextures, BadTextureKeysAreOneLineErrorsNamingTheKey) {
    const std::string diffuse = R"({"type": "diffuse"})";
    EXPECT_EQ(errorOf(sceneWith(R"("c": {"type": "constant", "colour": 1})", diffuse)),
              "s.json: textures.c: unknown key 'colour' (expected one of: type, float, value)");
    EXPECT_EQ(errorOf(sceneWith(R"("c": {"type": "dots"})", diffuse)),
              "s.json: textures.c.type: unknown texture type 'dots' (constant, imagemap, "
              "checkerboard, scale, mix, bilerp)");
    EXPECT_EQ(errorOf(sceneWith(R"("c": {"type": "checkerboard", "mapping": "polar"})", diffuse)),
              "s.json: textures.c.mapping: unknown mapping 'polar' (uv, spherical, cylindrical "
              "or planar)");
    EXPECT_EQ(
        errorOf(sceneWith(R"("c": {"type": "bilerp", "mapping": {"type": "uv", "v1": [1,0,0]}})",
                          diffuse)),
        "s.json: textures.c.mapping: unknown key 'v1' (expected one of: type, uscale, vscale, "
        "udelta, vdelta)");
    EXPECT_EQ(errorOf(sceneWith(R"("c": {"type": "constant"})",
                                R"({"type": "conductor", "metal": "gold", "roughness": "c"})")),
              "s.json: materials.m.roughness: needs a float texture, but 'c' is a spectrum "
              "texture");
    EXPECT_EQ(errorOf(sceneWith(R"("c": {"type": "scale", "tex": "d"})", diffuse)),
              "s.json: textures.c.tex: no texture named 'd' in \"textures\" (before this use)");
    EXPECT_EQ(errorOf(sceneWith(R"("c": {"type": "imagemap", "file": "nothere.png"})", diffuse)),
              "s.json: textures.c.file: file './nothere.png' does not exist");
    EXPECT_EQ(errorOf(sceneWith("", diffuse, R"(, "alpha": 1.5)")),
              "s.json: meshes[0].alpha: must be in [0, 1] or name a float texture");
    EXPECT_EQ(errorOf(sceneWith("", R"({"type": "diffuse", "displacement": 0.1, "bumpMap": "x"})")),
              "s.json: materials.m: give either 'displacement' or a map ('normalMap', "
              "'bumpMap'), not both");
    EXPECT_EQ(errorOf(sceneWith(R"("c": {"type": "constant", "float": true})",
                                R"({"type": "coateddiffuse", "reflectance": "c"})")),
              "s.json: materials.m.reflectance: expected an RGB colour [r, g, b] or one number, "
              "got a string");
}

TEST(JsonTextures, BadTextureFailsTheCommandWithExitCodeTwo) {
    const auto dir = testing::scratchDirectory("json-textures");
    ScratchDir scenes;
    const std::string scene = scenes.write(
        "s.json", sceneWith(R"("c": {"type": "mix", "amount": "c"})", R"({"type": "diffuse"})"));
    const std::string out = (dir / "a.exr").string();
    const auto result = testing::runPathlab("render --scene " + scene + " -o " + out, dir);
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_EQ(result.errLines(), 1) << result.err;
    EXPECT_NE(result.err.find("textures.c.amount: no texture named 'c'"), std::string::npos)
        << result.err;
    EXPECT_FALSE(std::filesystem::exists(out));
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace pathlab
