// The built-in Cornell box against MISSION.md and the published data.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <tuple>

#include "scene/builtin_scenes.h"
#include "scene/json_scene.h"
#include "scene/loader.h"
#include "scene/mesh_utils.h"
#include "scene/obj_loader.h"

namespace pathlab {
namespace {

const Mesh* findMesh(const SceneDescription& s, const std::string& name) {
    for (const Mesh& m : s.meshes)
        if (m.name == name) return &m;
    return nullptr;
}

const Material& materialOf(const SceneDescription& s, const std::string& mesh) {
    return s.materials.at(size_t(findMesh(s, mesh)->material));
}

void expectVec(Vec3f a, Vec3f b) {
    EXPECT_EQ(a.x, b.x);
    EXPECT_EQ(a.y, b.y);
    EXPECT_EQ(a.z, b.z);
}

TEST(CornellBox, LightIsTheSpecifiedQuadFacingDown) {
    const SceneDescription s = cornellBoxScene();
    std::vector<const Mesh*> lights;
    for (const Mesh& m : s.meshes)
        if (!isBlack(m.emission)) lights.push_back(&m);
    ASSERT_EQ(lights.size(), 1u);
    const Mesh& l = *lights[0];
    expectVec(l.emission, {17, 12, 4});
    EXPECT_FALSE(l.twoSided);
    ASSERT_EQ(l.positions.size(), 4u);
    expectVec(l.positions[0], {343, 548, 227});
    expectVec(l.positions[1], {343, 548, 332});
    expectVec(l.positions[2], {213, 548, 332});
    expectVec(l.positions[3], {213, 548, 227});
    ASSERT_EQ(l.triangleCount(), 2u);
    float area = 0;
    for (size_t t = 0; t < 2; ++t) {
        const Vec3f n =
            triangleNormalArea(l.positions[l.indices[3 * t]], l.positions[l.indices[3 * t + 1]],
                               l.positions[l.indices[3 * t + 2]]);
        EXPECT_EQ(n.x, 0.0f);
        EXPECT_LT(n.y, 0.0f);  // emits downwards
        EXPECT_EQ(n.z, 0.0f);
        area += 0.5f * length(n);
    }
    EXPECT_FLOAT_EQ(area, 130.0f * 105.0f);
    // The light reflects nothing.
    EXPECT_TRUE(isBlack(s.materials.at(size_t(l.material)).albedo));
}

TEST(CornellBox, LightHangsBelowAnUnbrokenCeiling) {
    const SceneDescription s = cornellBoxScene();
    const Mesh* ceiling = findMesh(s, "ceiling");
    ASSERT_NE(ceiling, nullptr);
    ASSERT_EQ(ceiling->triangleCount(), 2u);  // one quad: no hole in the data
    for (const Vec3f& p : ceiling->positions) EXPECT_EQ(p.y, 548.8f);
    EXPECT_EQ(findMesh(s, "front_wall"), nullptr);
}

TEST(CornellBox, MaterialsExact) {
    const SceneDescription s = cornellBoxScene();
    for (const char* white : {"floor", "ceiling", "back_wall", "short_block", "tall_block"}) {
        const Material& m = materialOf(s, white);
        EXPECT_EQ(m.type, MaterialType::Diffuse) << white;
        expectVec(m.albedo, {0.725f, 0.71f, 0.68f});
        EXPECT_EQ(m.texture, -1);
    }
    EXPECT_EQ(materialOf(s, "red_wall").type, MaterialType::Diffuse);
    expectVec(materialOf(s, "red_wall").albedo, {0.63f, 0.065f, 0.05f});
    EXPECT_EQ(materialOf(s, "green_wall").type, MaterialType::Diffuse);
    expectVec(materialOf(s, "green_wall").albedo, {0.14f, 0.45f, 0.091f});
    EXPECT_TRUE(isBlack(s.environment));
}

TEST(CornellBox, CameraExact) {
    const SceneDescription s = cornellBoxScene();
    expectVec(s.camera.eye, {278, 273, -800});
    expectVec(s.camera.target, {278, 273, 0});
    expectVec(s.camera.up, {0, 1, 0});
    EXPECT_EQ(s.camera.fovY, 37.5f);
    EXPECT_EQ(s.resolution.x, 512);
    EXPECT_EQ(s.resolution.y, 512);
}

TEST(CornellBox, RedWallLeftGreenWallRight) {
    const SceneDescription s = cornellBoxScene();
    // The camera convention of scene.h: image right = normalize(cross(forward, up)).
    const Vec3f forward = normalize(s.camera.target - s.camera.eye);
    const Vec3f right = normalize(cross(forward, s.camera.up));
    auto side = [&](const char* mesh) {
        return dot(meshBounds(*findMesh(s, mesh)).center() - s.camera.eye, right);
    };
    EXPECT_LT(side("red_wall"), 0.0f);
    EXPECT_GT(side("green_wall"), 0.0f);
}

TEST(CornellBox, WallsFaceIntoTheBox) {
    const SceneDescription s = cornellBoxScene();
    const Vec3f centre{278, 274, 280};
    for (const char* wall : {"ceiling", "back_wall", "red_wall", "green_wall"}) {
        const Mesh& m = *findMesh(s, wall);
        const Vec3f n = triangleNormalArea(m.positions[0], m.positions[1], m.positions[2]);
        EXPECT_GT(dot(n, centre - m.positions[0]), 0.0f) << wall;
    }
}

// Every face of the published data (Embree's copy), vertex for vertex.
TEST(CornellBox, GeometryMatchesThePublishedData) {
    const std::string obj = "/usr/share/doc/embree3/models/cornell_box.obj";
    if (!std::filesystem::exists(obj)) GTEST_SKIP() << obj << " not installed (embree-tools)";
    SceneDescription data;
    appendObj(data, obj);
    using V = std::tuple<float, float, float>;
    auto vertices = [](const SceneDescription& s, bool includeLight) {
        std::multiset<V> out;
        float area = 0;
        for (const Mesh& m : s.meshes) {
            if (!includeLight && (!isBlack(m.emission) || m.name == "light")) continue;
            for (size_t t = 0; t < m.triangleCount(); ++t) {
                const Vec3f a = m.positions[m.indices[3 * t]],
                            b = m.positions[m.indices[3 * t + 1]],
                            c = m.positions[m.indices[3 * t + 2]];
                area += 0.5f * length(triangleNormalArea(a, b, c));
                for (Vec3f p : {a, b, c}) out.insert({p.x, p.y, p.z});
            }
        }
        return std::make_pair(std::set<V>(out.begin(), out.end()), area);
    };
    const auto [ours, ourArea] = vertices(cornellBoxScene(), false);
    const auto [theirs, theirArea] = vertices(data, false);
    EXPECT_EQ(ours, theirs);
    EXPECT_NEAR(ourArea, theirArea, 1e-4f * theirArea);
}

TEST(CornellBox, ShippedJsonReproducesTheBuiltIn) {
    const SceneDescription a = cornellBoxScene();
    const SceneDescription b =
        loadScene(std::string(PATHLAB_SOURCE_DIR) + "/scenes/cornell-box.json");
    expectVec(a.camera.eye, b.camera.eye);
    expectVec(a.camera.target, b.camera.target);
    EXPECT_EQ(a.camera.fovY, b.camera.fovY);
    ASSERT_EQ(a.meshes.size(), b.meshes.size());
    for (size_t i = 0; i < a.meshes.size(); ++i) {
        const Mesh &ma = a.meshes[i], &mb = b.meshes[i];
        EXPECT_EQ(ma.name, mb.name);
        ASSERT_EQ(ma.positions.size(), mb.positions.size()) << ma.name;
        for (size_t v = 0; v < ma.positions.size(); ++v)
            expectVec(ma.positions[v], mb.positions[v]);
        EXPECT_EQ(ma.indices, mb.indices);
        expectVec(ma.emission, mb.emission);
        EXPECT_EQ(ma.twoSided, mb.twoSided);
        const Material &xa = a.materials[size_t(ma.material)],
                       &xb = b.materials[size_t(mb.material)];
        EXPECT_EQ(xa.type, xb.type);
        expectVec(xa.albedo, xb.albedo);
    }
}

TEST(CornellBox, LoadsByName) {
    const SceneDescription s = loadScene("cornell-box");
    EXPECT_EQ(s.name, "cornell-box");
    EXPECT_EQ(s.meshes.size(), 8u);
}

}  // namespace
}  // namespace pathlab
