// Bump and normal maps (render/bump_mapping.h): a flat map leaves the image
// as it was bit for bit; a tilting normal map and a displacement ramp dim a
// diffuse floor under a light along its normal by the cosine of the tilt
// computed by hand; the geometry the maps perturb; and the readers.
#include <gtest/gtest.h>

#include <cmath>

#include "core/image.h"
#include "render/bump_mapping.h"
#include "render/renderer.h"
#include "scene/json_scene.h"
#include "scene/pbrt/importer.h"
#include "scene_test_util.h"

namespace pathlab {
namespace {

constexpr float kAlbedo = 0.5f;

// A 20×20 diffuse floor at y = 0 with u along +x and v along +z over [0, 1]
// (so ∂p/∂u = (20, 0, 0)), seen straight down through a narrow field of view
// and lit by a distant light travelling straight down: without a map every
// pixel has radiance (albedo/π)·L.
SceneDescription litFloor() {
    SceneDescription s;
    s.materials.push_back(Material{"floor", MaterialType::Diffuse, Vec3f(kAlbedo)});
    Mesh floor;
    floor.positions = {{-10, 0, -10}, {-10, 0, 10}, {10, 0, 10}, {10, 0, -10}};
    floor.uvs = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
    floor.indices = {0, 1, 2, 0, 2, 3};
    s.meshes.push_back(floor);
    PunctualLight light;
    light.type = PunctualLightType::Distant;
    light.direction = {0, -1, 0};
    light.radiance = Vec3f(2);
    s.punctualLights.push_back(light);
    s.camera = Camera{{0.3f, 1, 0.2f}, {0.3f, 0, 0.2f + 1e-3f}, {0, 0, 1}, 20};
    s.resolution = {8, 8};
    return s;
}

// A w×h image of one colour.
Texture uniformImage(Vec3f c, int w = 2, int h = 2) {
    Texture t;
    t.width = w, t.height = h;
    t.texels.assign(size_t(w * h), c);
    return t;
}

Image renderImage(const SceneDescription& desc, bool batched = true) {
    const RenderScene scene(desc);
    RenderSettings settings;
    settings.samplesPerPixel = 4;
    settings.maxDepth = 1;
    settings.threads = 1;
    settings.batchPaths = batched;
    return render(scene, settings).image;
}

// The image's mean, asserting that both integrators agree bit for bit.
double meanRadiance(const SceneDescription& desc) {
    const Image batched = renderImage(desc, true);
    EXPECT_EQ(batched.rgb, renderImage(desc, false).rgb);
    double sum = 0;
    for (float v : batched.rgb) sum += v;
    return sum / double(batched.rgb.size());
}

SceneDescription withNormalMap(Vec3f texel) {
    SceneDescription s = litFloor();
    s.textures.push_back(uniformImage(texel));
    s.materials[0].normalMap = 0;
    return s;
}

SceneDescription withDisplacement(ShadingTexture heights) {
    SceneDescription s = litFloor();
    heights.isFloat = true;
    s.shadingTextures.push_back(heights);
    s.materials[0].displacementTexture = 0;
    return s;
}

const double kUnmapped = kAlbedo / M_PI * 2;

TEST(NormalMap, FlatMapLeavesTheImageBitForBit) {
    const Image plain = renderImage(litFloor());
    EXPECT_NEAR(plain.rgb[0], kUnmapped, 1e-6);
    EXPECT_EQ(renderImage(withNormalMap({0.5f, 0.5f, 1})).rgb, plain.rgb);
}

TEST(NormalMap, TiltDimsTheFloorByTheCosine) {
    // t = 2c − 1 = (sin θ, 0, cos θ) tilts the normal by θ towards ∂p/∂u;
    // the light along the geometric normal then gives cos θ of the radiance.
    for (float degrees : {20.0f, 50.0f}) {
        const float theta = degrees * float(M_PI / 180);
        const Vec3f texel{0.5f + 0.5f * std::sin(theta), 0.5f, 0.5f + 0.5f * std::cos(theta)};
        EXPECT_NEAR(meanRadiance(withNormalMap(texel)), kUnmapped * std::cos(theta), 1e-5)
            << degrees << "°";
    }
    // Tilting towards ∂p/∂v (the map's green) as much.
    const float theta = 35 * float(M_PI / 180);
    const Vec3f texel{0.5f, 0.5f - 0.5f * std::sin(theta), 0.5f + 0.5f * std::cos(theta)};
    EXPECT_NEAR(meanRadiance(withNormalMap(texel)), kUnmapped * std::cos(theta), 1e-5);
}

TEST(BumpMap, ConstantDisplacementLeavesTheImageBitForBit) {
    ShadingTexture constant;
    constant.kind = TextureKind::Constant;
    constant.value = Vec3f(0.3f);
    EXPECT_EQ(renderImage(withDisplacement(constant)).rgb, renderImage(litFloor()).rgb);
}

TEST(BumpMap, RampTiltsTheFloorByItsSlope) {
    // Heights d = h·u over the floor's 20 units of u: slope h/20, so the
    // normal tilts by atan(h/20) and the radiance scales by 20/√(20² + h²).
    for (float h : {5.0f, 20.0f}) {
        ShadingTexture ramp;
        ramp.kind = TextureKind::Bilerp;
        ramp.corners[0] = ramp.corners[1] = Vec3f(0);  // v00, v01
        ramp.corners[2] = ramp.corners[3] = Vec3f(h);  // v10, v11
        const double expected = kUnmapped * 20 / std::sqrt(400.0 + h * h);
        EXPECT_NEAR(meanRadiance(withDisplacement(ramp)), expected, 1e-3 * expected) << h;
    }
}

TEST(BumpMap, GeometryOfTrianglesAndSpheres) {
    // ∂p/∂u and ∂p/∂v reproduce the corners: p_i − p_2 = Δu·∂p/∂u + Δv·∂p/∂v.
    const Vec3f p[3] = {{0, 0, 0}, {2, 0, 0}, {0, 0, 3}};
    const Vec2f uv[3] = {{0.1f, 0.2f}, {0.6f, 0.2f}, {0.1f, 0.8f}};
    const ShadingGeometry g = triangleShading(p, uv, nullptr, {0, 1, 0});
    EXPECT_NEAR(g.dpdu.x, 4, 1e-5);
    EXPECT_NEAR(g.dpdv.z, 5, 1e-5);
    EXPECT_NEAR(length(g.dpdu) * length(g.dpdv), 20, 1e-4);
    // A sphere's ∂p/∂u runs along the circle of latitude with length 2π·ρ,
    // and ∂n/∂u = ∂p/∂u / r.
    const ShadingGeometry s = sphereShading({0, 2, 0}, 2);
    EXPECT_NEAR(s.dpdu.x, -4 * M_PI, 1e-5);
    EXPECT_NEAR(s.dndu.x, -2 * M_PI, 1e-5);
    EXPECT_NEAR(dot(s.dpdu, s.n), 0, 1e-5);
    EXPECT_NEAR(dot(s.dpdv, s.n), 0, 1e-5);
}

TEST(MaterialMaps, PbrtAndJsonReadThemAndRejectBadOnes) {
    test::ScratchDir dir;
    const Image flat = [] {
        Image im(2, 2);
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < 2; ++x) im.set(x, y, {0.5f, 0.5f, 1});
        return im;
    }();
    writeImage((dir.path() / "flat.exr").string(), flat);
    const std::string quad =
        "Shape \"bilinearmesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0 1 1 0] "
        "\"point2 uv\" [0 0 1 0 0 1 1 1]\n";
    const std::string file =
        dir.write("maps.pbrt",
                  "WorldBegin\n"
                  "Texture \"ramp\" \"float\" \"bilerp\" \"float v10\" 1\n"
                  "Material \"diffuse\" \"string normalmap\" \"flat.exr\"\n" +
                      quad +
                      "Material \"conductor\" \"texture displacement\" "
                      "\"ramp\"\n" +
                      quad + "Material \"coateddiffuse\" \"float displacement\" 0.1\n" + quad);
    const pbrt::ImportResult r = pbrt::importPbrtFile(file);
    ASSERT_EQ(r.scene.materials.size(), 3u);
    EXPECT_GE(r.scene.materials[0].normalMap, 0);
    EXPECT_GE(r.scene.materials[1].displacementTexture, 0);
    EXPECT_EQ(r.scene.shadingTextures[size_t(r.scene.materials[2].displacementTexture)].value.x,
              0.1f);
    const std::string missing = dir.write(
        "missing.pbrt", "WorldBegin\nMaterial \"diffuse\" \"string normalmap\" \"nothere.png\"\n");
    EXPECT_NE(test::inputErrorOf([&] { pbrt::importPbrtFile(missing); }).find("nothere.png"),
              std::string::npos);
    const std::string mixed =
        dir.write("mix.pbrt",
                  "WorldBegin\nMakeNamedMaterial \"a\" \"string type\" \"diffuse\"\n"
                  "Material \"mix\" \"string materials\" [\"a\" \"a\"] \"float displacement\" 1\n");
    EXPECT_NE(test::inputErrorOf([&] { pbrt::importPbrtFile(mixed); }).find("displacement"),
              std::string::npos);

    const auto json = [&](const std::string& material) {
        return dir.write("scene.json",
                         R"({"camera": {"eye": [0, 1, 5], "target": [0, 1, 0], "fovY": 40},
                             "materials": {"m": )" +
                             material + R"(},
                             "meshes": [{"material": "m",
                                         "quads": [[[-1,0,-1], [-1,0,1], [1,0,1], [1,0,-1]]]}],
                             "lights": [{"type": "quad", "emission": 10,
                                         "vertices": [[0,3,0], [1,3,0], [1,3,1], [0,3,1]]}]})");
    };
    const SceneDescription s =
        loadJsonScene(json("{\"type\": \"diffuse\", \"bumpMap\": \"flat.exr\", \"bumpScale\": 2}"));
    ASSERT_GE(s.materials[0].displacementTexture, 0);
    EXPECT_EQ(s.shadingTextures[size_t(s.materials[0].displacementTexture)].scale, 2.0f);
    EXPECT_GE(
        loadJsonScene(
            json("{\"type\": \"conductor\", \"metal\": \"gold\", \"normalMap\": \"flat.exr\"}"))
            .materials[0]
            .normalMap,
        0);
    EXPECT_NE(test::inputErrorOf([&] {
                  loadJsonScene(
                      json("{\"type\": \"diffuse\", \"normalMap\": \"flat.exr\", "
                           "\"bumpMap\": \"flat.exr\"}"));
              }).find("not both"),
              std::string::npos);
    EXPECT_NE(test::inputErrorOf([&] {
                  loadJsonScene(json("{\"type\": \"interface\", \"normalMap\": \"flat.exr\"}"));
              }).find("unknown key 'normalMap'"),
              std::string::npos);
    EXPECT_NE(test::inputErrorOf([&] {
                  loadJsonScene(json("{\"type\": \"diffuse\", \"bumpMap\": \"nothere.png\"}"));
              }).find("nothere.png"),
              std::string::npos);
}

}  // namespace
}  // namespace pathlab
