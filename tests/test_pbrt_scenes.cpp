// pbrt-v4 scenes end to end: the Cornell box written for pbrt-v4 renders as
// the built-in one, each shape type through the importer, the PLY models of
// Debian's assimp-testmodels, and `pathlab render` with a .pbrt file's own
// sampler, spp and depth (the command line overriding them).
#include <gtest/gtest.h>

#include <cmath>

#include "cli_runner.h"
#include "core/image.h"
#include "render/renderer.h"
#include "scene/builtin_scenes.h"
#include "scene/loader.h"
#include "scene/mesh_utils.h"
#include "scene/pbrt/importer.h"
#include "scene_test_util.h"

namespace pathlab {
namespace {

using test::inputErrorOf;
using test::ScratchDir;

const std::string kScenes = std::string(PATHLAB_SOURCE_DIR) + "/scenes/";

Image renderScene(SceneDescription desc, const std::string& sampler, int spp, Vec2i size) {
    const RenderScene scene(std::move(desc));
    RenderSettings s;
    s.sampler = sampler;
    s.samplesPerPixel = spp;
    s.resolution = size;
    s.threads = 2;
    return render(scene, s).image;
}

TEST(PbrtScenes, CornellBoxFileRendersAsTheBuiltInBitForBit) {
    const SceneDescription fromFile = loadScene(kScenes + "cornell-box.pbrt");
    const SceneDescription builtIn = cornellBoxScene();
    EXPECT_EQ(fromFile.resolution.x, builtIn.resolution.x);
    EXPECT_EQ(fromFile.defaults.maxDepth, 8);
    EXPECT_EQ(fromFile.film.filter.type, FilterType::Box);
    for (const char* sampler : {"independent", "sobol-owen", "halton-owen"}) {
        const Image a = renderScene(fromFile, sampler, 8, {40, 32});
        const Image b = renderScene(builtIn, sampler, 8, {40, 32});
        EXPECT_EQ(a.rgb, b.rgb) << sampler;
    }
}

pbrt::ImportResult load(const std::string& text) {
    return pbrt::importPbrtText(text, "test.pbrt", ".", {});
}

double meshArea(const Mesh& m) {
    double a = 0;
    for (size_t i = 0; i + 2 < m.indices.size(); i += 3)
        a += 0.5 *
             length(triangleNormalArea(m.positions[m.indices[i]], m.positions[m.indices[i + 1]],
                                       m.positions[m.indices[i + 2]]));
    return a;
}

TEST(PbrtScenes, SpheresStayExactUnderSimilarityTransforms) {
    const auto r = load(
        "WorldBegin\nAttributeBegin\nTranslate 1 2 3\nRotate 40 1 1 0\nScale 2 2 2\n"
        "Shape \"sphere\" \"float radius\" 1.5\nAttributeEnd\n"
        "Scale 1 2 1\nShape \"sphere\"\n");
    ASSERT_EQ(r.scene.spheres.size(), 1u);
    EXPECT_NEAR(r.scene.spheres[0].radius, 3, 1e-5);
    EXPECT_NEAR(r.scene.spheres[0].center.y, 2, 1e-5);
    // The stretched one is tessellated: an ellipsoid of semi-axes 1, 2, 1.
    ASSERT_EQ(r.scene.meshes.size(), 1u);
    for (const Vec3f& p : r.scene.meshes[0].positions)
        EXPECT_NEAR(p.x * p.x + p.y * p.y / 4 + p.z * p.z, 1, 1e-5);
    const Bounds3f b = meshBounds(r.scene.meshes[0]);
    EXPECT_NEAR(b.extent().y, 4, 1e-5);
}

// A whole emitting sphere stays an exact sphere, a light sampled by the cone
// it subtends (render/sphere_light.h); a partial one is tessellated, without
// the triangles of no area at its pole (a triangle light is sampled by area),
// facing outwards.
TEST(PbrtScenes, EmittingSpheresAreExactOrValidTriangleLights) {
    ScratchDir dir;
    const std::string file =
        dir.write("s.pbrt",
                  "WorldBegin\nAttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [2 2 2]\n"
                  "Translate 0 5 0\nShape \"sphere\" \"float radius\" 0.5\n"
                  "Shape \"sphere\" \"float radius\" 0.5 \"float zmax\" 0.25\nAttributeEnd\n"
                  "Shape \"bilinearmesh\" \"point3 P\" [-1 0 -1 1 0 -1 -1 0 1 1 0 1]\n");
    const SceneDescription s = loadScene(file);  // validated
    ASSERT_EQ(s.spheres.size(), 1u);
    EXPECT_EQ(s.spheres[0].emission.x, 2);
    EXPECT_EQ(s.spheres[0].radius, 0.5f);
    EXPECT_EQ(s.spheres[0].center.y, 5);
    ASSERT_EQ(s.meshes.size(), 2u);
    EXPECT_EQ(s.meshes[0].emission.x, 2);
    EXPECT_NEAR(meshArea(s.meshes[0]), 2 * kPi * 0.5 * 0.75, 0.01);
    // Outward: every triangle's front faces away from the centre.
    const Mesh& m = s.meshes[0];
    for (size_t i = 0; i + 2 < m.indices.size(); i += 3) {
        const Vec3f p0 = m.positions[m.indices[i]];
        EXPECT_GT(dot(triangleNormalArea(p0, m.positions[m.indices[i + 1]],
                                         m.positions[m.indices[i + 2]]),
                      p0 - Vec3f(0, 5, 0)),
                  0);
    }
}

TEST(PbrtScenes, DisksBilinearPatchesAndLoopSubdivisionBecomeMeshes) {
    const auto r = load(
        "WorldBegin\nShape \"disk\" \"float radius\" 2 \"float innerradius\" 1\n"
        "Shape \"bilinearmesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0 1 1 0]\n"
        "Shape \"loopsubdiv\" \"integer levels\" 2 \"point3 P\" [1 0 0 -1 0 0 0 1 0 0 -1 0 0 0 1 "
        "0 0 -1] \"integer indices\" [0 2 4 2 1 4 1 3 4 3 0 4 2 0 5 1 2 5 3 1 5 0 3 5]\n");
    ASSERT_EQ(r.scene.meshes.size(), 3u);
    EXPECT_NEAR(meshArea(r.scene.meshes[0]), kPi * (4 - 1), 0.01);
    EXPECT_NEAR(meshArea(r.scene.meshes[1]), 1, 1e-6);
    EXPECT_EQ(r.scene.meshes[1].triangleCount(), 2u);        // planar: two exact triangles
    EXPECT_EQ(r.scene.meshes[2].triangleCount(), 8u * 16u);  // 4 times per level
}

TEST(PbrtScenes, PlyMeshesOfAssimpTestModels) {
    const std::string wuson = "/usr/share/assimp/models/PLY/Wuson.ply";
    const std::string pond = "/usr/share/assimp/models/PLY/pond.0.ply";
    if (!std::filesystem::exists(wuson)) GTEST_SKIP() << "assimp-testmodels missing";
    const auto r = load("WorldBegin\nShape \"plymesh\" \"string filename\" \"" + wuson + "\"\n");
    ASSERT_EQ(r.scene.meshes.size(), 1u);
    EXPECT_GT(r.scene.meshes[0].triangleCount(), 3000u);
    EXPECT_EQ(r.scene.meshes[0].normals.size(), r.scene.meshes[0].positions.size());
    const std::string err = inputErrorOf(
        [&] { load("WorldBegin\nShape \"plymesh\" \"string filename\" \"" + pond + "\"\n"); });
    EXPECT_EQ(err.rfind("test.pbrt:2:1: ", 0), 0u) << err;
    const std::string missing = inputErrorOf(
        [&] { load("WorldBegin\nShape \"plymesh\" \"string filename\" \"no.ply\"\n"); });
    EXPECT_EQ(missing, "test.pbrt:2:1: file 'no.ply' does not exist (looked in '.')");
}

class PbrtRenderCli : public ::testing::Test {
  protected:
    void SetUp() override { dir = testing::scratchDirectory("pbrt-render"); }
    void TearDown() override { std::filesystem::remove_all(dir); }
    std::filesystem::path dir;
};

TEST_F(PbrtRenderCli, TheFilesSamplerAndDepthApplyUnlessTheCommandLineSaysOtherwise) {
    ScratchDir scenes;
    const std::string scene =
        scenes.write("s.pbrt",
                     "LookAt 0 0 -3 0 0 0 0 1 0\nCamera \"perspective\" \"float fov\" 40\n"
                     "Film \"rgb\" \"integer xresolution\" 24 \"integer yresolution\" 16\n"
                     "Sampler \"halton\" \"integer pixelsamples\" 3\nIntegrator \"path\" \"integer "
                     "maxdepth\" 2\n"
                     "WorldBegin\nLightSource \"infinite\" \"rgb L\" [1 1 1]\nShape \"sphere\"\n");
    const auto r =
        testing::runPathlab("render --scene " + scene + " -o " + (dir / "a.exr").string(), dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("(24x16, 3 spp, halton-rd)"), std::string::npos) << r.err;
    const auto o = testing::runPathlab(
        "render --scene " + scene + " --sampler independent --spp 2 -o " + (dir / "b.exr").string(),
        dir);
    ASSERT_EQ(o.exitCode, 0) << o.err;
    EXPECT_NE(o.err.find("(24x16, 2 spp, independent)"), std::string::npos) << o.err;
}

TEST_F(PbrtRenderCli, UnsupportedIsOneLineOrLenientWarnings) {
    ScratchDir scenes;
    const std::string scene = scenes.write(
        "s.pbrt",
        "Film \"rgb\" \"integer xresolution\" 8 \"integer yresolution\" 8\nWorldBegin\n"
        "LightSource \"goniometric\" \"rgb I\" [1 1 1]\nLightSource \"infinite\"\n"
        "Material \"hair\"\nShape \"sphere\"\n");
    const std::string out = (dir / "a.exr").string();
    const auto strict = testing::runPathlab("render --scene " + scene + " -o " + out, dir);
    EXPECT_EQ(strict.exitCode, 2);
    EXPECT_EQ(strict.err, "pathlab: error: " + scene +
                              ":3:1: LightSource 'goniometric' is not supported (--lenient "
                              "substitutes no light)\n");
    EXPECT_FALSE(std::filesystem::exists(out));
    const auto lenient =
        testing::runPathlab("render --lenient --scene " + scene + " -o " + out, dir);
    EXPECT_EQ(lenient.exitCode, 0) << lenient.err;
    EXPECT_NE(lenient.err.find(scene + ": 2 unsupported features substituted (--lenient)"),
              std::string::npos)
        << lenient.err;
    EXPECT_TRUE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace pathlab
