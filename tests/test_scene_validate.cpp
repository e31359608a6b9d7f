// Checks common to every scene source, texture lookup and decoding, and the
// built-in wolf.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/image.h"
#include "scene/assets.h"
#include "scene/builtin_scenes.h"
#include "scene/dds.h"
#include "scene/loader.h"
#include "scene/mesh_utils.h"
#include "scene/texture_loader.h"
#include "scene/validate.h"
#include "scene_test_util.h"

namespace pathlab {
namespace {

using test::inputErrorOf;

std::string problem(SceneDescription s) {
    return inputErrorOf([&] { validateScene(s, "s"); });
}

TEST(SceneValidation, AcceptsTheCornellBox) {
    EXPECT_NO_THROW(validateScene(cornellBoxScene(), "cb"));
}

TEST(SceneValidation, RejectsBrokenScenes) {
    const SceneDescription good = cornellBoxScene();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    SceneDescription s = good;
    s.meshes.clear();
    EXPECT_NE(problem(s).find("no geometry"), std::string::npos);
    s = good;
    s.camera.target = s.camera.eye;
    EXPECT_NE(problem(s).find("eye equals"), std::string::npos);
    s = good;
    s.camera.up = {0, 0, 1};  // parallel to the view direction
    EXPECT_NE(problem(s).find("parallel"), std::string::npos);
    s = good;
    s.meshes[0].positions[2].y = nan;
    EXPECT_NE(problem(s).find("non-finite position"), std::string::npos);
    s = good;
    s.meshes[0].positions[2].x = std::numeric_limits<float>::infinity();
    EXPECT_NE(problem(s).find("non-finite position"), std::string::npos);
    s = good;
    s.meshes[1].indices[4] = 99;
    EXPECT_NE(problem(s).find("out of range"), std::string::npos);
    s = good;
    s.meshes.back().positions[2] = s.meshes.back().positions[1];  // a light triangle collapses
    EXPECT_NE(problem(s).find("zero-area"), std::string::npos);
    s = good;
    s.meshes[0].material = 17;
    EXPECT_NE(problem(s).find("material 17"), std::string::npos);
    s = good;
    s.materials[0].texture = 0;
    EXPECT_NE(problem(s).find("texture"), std::string::npos);
    s = good;
    s.meshes[0].emission = {-1, 0, 0};
    EXPECT_NE(problem(s).find("emission"), std::string::npos);
    s = good;
    s.resolution = {0, 0};
    EXPECT_NE(problem(s).find("resolution"), std::string::npos);
    s = good;
    s.spheres.push_back({{0, 0, 0}, -1, 0});
    EXPECT_NE(problem(s).find("sphere"), std::string::npos);
    s = good;
    s.meshes[0].normals.resize(1);
    EXPECT_NE(problem(s).find("normals"), std::string::npos);
}

TEST(SceneValidation, DegenerateTrianglesOfOrdinaryMeshesAreFine) {
    SceneDescription s = cornellBoxScene();
    appendTriangle(s.meshes[0], {1, 1, 1}, {1, 1, 1}, {2, 2, 2});
    EXPECT_NO_THROW(validateScene(s, "s"));
}

TEST(SceneLoader, UnknownNamesAndFilesAreOneLine) {
    const std::string msg = inputErrorOf([] { loadScene("cornel-box"); });
    EXPECT_NE(msg.find("cornel-box"), std::string::npos);
    EXPECT_NE(msg.find("cornell-box, wolf"), std::string::npos);
    EXPECT_EQ(msg.find('\n'), std::string::npos);
    test::ScratchDir dir;
    const std::string ply = dir.write("m.ply", "ply\n");
    EXPECT_NE(inputErrorOf([&] { loadScene(ply); }).find(".ply"), std::string::npos);
    const std::string bad = dir.write("bad.json", "{");
    EXPECT_THROW(loadScene(bad), InputError);
    EXPECT_THROW(loadScene(dir.path().string()), InputError);  // a directory
}

TEST(SceneTexture, LookupIsTopRowFirstBilinearAndWraps) {
    Texture t;
    t.width = 2, t.height = 2;
    t.texels = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};  // top row: red, green
    auto near = [](Vec3f a, Vec3f b) {
        EXPECT_NEAR(a.x, b.x, 1e-6f);
        EXPECT_NEAR(a.y, b.y, 1e-6f);
        EXPECT_NEAR(a.z, b.z, 1e-6f);
    };
    near(t.lookup({0.25f, 0.25f}), {1, 0, 0});  // texel centres
    near(t.lookup({0.75f, 0.25f}), {0, 1, 0});
    near(t.lookup({0.25f, 0.75f}), {0, 0, 1});
    near(t.lookup({1.25f, -0.25f}), {0, 0, 1});      // wraps (v −0.25 ≡ 0.75)
    near(t.lookup({0.5f, 0.25f}), {0.5f, 0.5f, 0});  // halfway along the top row
}

TEST(SceneTexture, LoadsPngAsLinear) {
    test::ScratchDir dir;
    Image img(1, 1);
    img.set(0, 0, {0.5f, 0.25f, 1.0f});
    const std::string path = (dir.path() / "t.png").string();
    writeImage(path, img);
    const Texture t = loadTexture(path);
    ASSERT_EQ(t.texels.size(), 1u);
    EXPECT_NEAR(t.texels[0].x, 0.5f, 0.01f);
    EXPECT_NEAR(t.texels[0].y, 0.25f, 0.01f);
    EXPECT_THROW(loadTexture((dir.path() / "none.png").string()), InputError);
}

TEST(SceneTexture, DdsDecoderMatchesTheSharedPng) {
    WolfAssets assets;
    if (!findWolfAssets(assets)) GTEST_SKIP() << "wolf data not found (set PATHLAB_ASSETS)";
    const auto dir = assets.mesh.parent_path();
    if (!std::filesystem::exists(dir / "animal_wolf_grey.dds") ||
        !std::filesystem::exists(dir / "animal_wolf_grey.png"))
        GTEST_SKIP() << "needs both the DDS and the PNG";
    const Image dds = readDds((dir / "animal_wolf_grey.dds").string());
    const Image png = readImage((dir / "animal_wolf_grey.png").string());
    ASSERT_EQ(dds.width, png.width);
    ASSERT_EQ(dds.height, png.height);
    // The PNG was made from the DDS, but reading it composites its alpha onto
    // black, which darkens the few texels with alpha < 1 (the teeth); all
    // others must agree to within rounding of the interpolated colours.
    size_t off = 0;
    for (size_t i = 0; i < dds.rgb.size(); ++i)
        off += std::abs(linearToSrgb(dds.rgb[i]) - linearToSrgb(png.rgb[i])) > 2.5f / 255.0f;
    EXPECT_LT(off, dds.rgb.size() / 100);
}

TEST(SceneTexture, DdsRejectsGarbage) {
    const std::vector<uint8_t> junk(200, 7);
    EXPECT_THROW(decodeDds(junk, "junk"), InputError);
}

// The wolf: two lights of different size and power, the wolf in view.
TEST(WolfScene, BuildsWithTwoDifferentLightsAndFramesTheWolf) {
    WolfAssets assets;
    if (!findWolfAssets(assets)) GTEST_SKIP() << "wolf data not found (set PATHLAB_ASSETS)";
    const SceneDescription s = loadScene("wolf");
    EXPECT_NE(s.credit.find("Wildfire Games"), std::string::npos);
    std::vector<std::pair<float, float>> lights;  // (area, power)
    for (const Mesh& m : s.meshes) {
        if (isBlack(m.emission)) continue;
        EXPECT_FALSE(m.twoSided);
        float area = 0;
        for (size_t t = 0; t < m.triangleCount(); ++t)
            area += 0.5f * length(triangleNormalArea(m.positions[m.indices[3 * t]],
                                                     m.positions[m.indices[3 * t + 1]],
                                                     m.positions[m.indices[3 * t + 2]]));
        lights.push_back({area, area * kPi * luminance(m.emission)});
    }
    ASSERT_EQ(lights.size(), 2u);
    EXPECT_GT(std::abs(lights[0].first / lights[1].first - 1), 1.0f);
    EXPECT_GT(std::abs(lights[0].second / lights[1].second - 1), 1.0f);
    EXPECT_GT(maxComponent(s.environment), 0.0f);
    EXPECT_LE(maxComponent(s.environment), 0.1f);

    const Mesh& wolf = s.meshes[0];
    EXPECT_EQ(wolf.name, "wolf");
    EXPECT_EQ(wolf.normals.size(), wolf.positions.size());
    EXPECT_GE(s.materials.at(size_t(wolf.material)).texture, 0);
    // Every wolf vertex projects inside the image, and the wolf spans more
    // than half of it in width.
    const Vec3f fwd = normalize(s.camera.target - s.camera.eye);
    const Vec3f right = normalize(cross(fwd, s.camera.up)), up = cross(right, fwd);
    const float t = std::tan(s.camera.fovY * kPi / 360.0f);
    const float aspect = float(s.resolution.x) / float(s.resolution.y);
    float xmin = 1, xmax = -1;
    for (const Vec3f& p : wolf.positions) {
        const Vec3f d = p - s.camera.eye;
        const float x = dot(d, right) / dot(d, fwd) / (t * aspect),
                    y = dot(d, up) / dot(d, fwd) / t;
        EXPECT_LT(std::abs(x), 0.98f);
        EXPECT_LT(std::abs(y), 0.98f);
        xmin = std::min(xmin, x), xmax = std::max(xmax, x);
    }
    EXPECT_GT(xmax - xmin, 1.0f);
}

}  // namespace
}  // namespace pathlab
