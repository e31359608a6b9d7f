// OBJ/MTL through tinyobjloader: grouping, material mapping, bad input.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/image.h"
#include "scene/loader.h"
#include "scene/mesh_utils.h"
#include "scene/obj_loader.h"
#include "scene_test_util.h"

namespace pathlab {
namespace {

using test::inputErrorOf;
using test::ScratchDir;

const char* kMtl = R"(newmtl matte
Kd 0.5 0.25 0.125
map_Kd tex.png
newmtl lamp
Kd 0 0 0
Ke 4 5 6
newmtl glass
illum 7
Ni 1.33
newmtl chrome
illum 3
Ks 0.9 0.9 0.9
Ns 1000
newmtl brushed
illum 3
Ks 0.5 0.5 0.5
Ns 98
newmtl pbr
Kd 0.8 0.6 0.2
Pm 1
Pr 0.5
)";

const char* kObj = R"(mtllib m.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
usemtl matte
f 1/1/1 2/2/1 3/3/1 4/4/1
usemtl lamp
f 1 2 3
usemtl glass
f 1 3 4
usemtl chrome
f 1 2 4
usemtl brushed
f 2 3 4
usemtl pbr
f 1 2 3
usemtl matte
f 1/1/1 3/3/1 4/4/1
)";

struct Fixture {
    ScratchDir dir;
    std::string obj;
    Fixture(const std::string& objText = kObj) {
        Image tex(2, 2);
        tex.set(0, 0, {1, 1, 1});
        writeImage((dir.path() / "tex.png").string(), tex);
        dir.write("m.mtl", kMtl);
        obj = dir.write("model.obj", objText);
    }
};

TEST(ObjLoader, GroupsByMaterialAndMapsMtl) {
    Fixture f;
    SceneDescription s;
    ASSERT_EQ(appendObj(s, f.obj), 6u);
    ASSERT_EQ(s.materials.size(), 6u);
    // matte: a quad (2 triangles) and one more triangle, smooth, textured.
    const Mesh& matte = s.meshes[0];
    EXPECT_EQ(s.materials[size_t(matte.material)].name, "matte");
    EXPECT_EQ(matte.triangleCount(), 3u);
    EXPECT_EQ(matte.positions.size(), 4u);  // shared vertices merged
    EXPECT_EQ(matte.normals.size(), 4u);
    ASSERT_EQ(matte.uvs.size(), 4u);
    EXPECT_EQ(matte.uvs[0].y, 1.0f);  // OBJ v = 0 is the bottom row: flipped
    const Material& m = s.materials[0];
    EXPECT_EQ(m.type, MaterialType::Diffuse);
    EXPECT_EQ(m.albedo.y, 0.25f);
    EXPECT_EQ(m.texture, 0);
    ASSERT_EQ(s.textures.size(), 1u);
    // lamp: emitting, flat, no UVs.
    const Mesh& lamp = s.meshes[1];
    EXPECT_EQ(lamp.emission.z, 6.0f);
    EXPECT_FALSE(lamp.twoSided);
    EXPECT_TRUE(lamp.normals.empty());
    EXPECT_TRUE(lamp.uvs.empty());
    EXPECT_EQ(s.materials[2].type, MaterialType::Dielectric);
    EXPECT_EQ(s.materials[2].ior, 1.33f);
    EXPECT_EQ(s.materials[3].type, MaterialType::Mirror);
    EXPECT_EQ(s.materials[3].albedo.x, 0.9f);
    EXPECT_EQ(s.materials[4].type, MaterialType::Conductor);
    EXPECT_NEAR(s.materials[4].roughness, std::sqrt(2.0f / 100.0f), 1e-6f);
    // Normal-incidence reflectance of eta = 1, k: k²/(4 + k²) = Ks.
    const float k = s.materials[4].k.x;
    EXPECT_NEAR(k * k / (4 + k * k), 0.5f, 1e-5f);
    EXPECT_EQ(s.materials[5].type, MaterialType::Conductor);
    EXPECT_NEAR(s.materials[5].roughness, 0.25f, 1e-6f);
}

TEST(ObjLoader, MaterialOverrideAndDefaultMaterial) {
    Fixture f;
    SceneDescription s;
    s.materials.resize(1);
    EXPECT_EQ(appendObj(s, f.obj, 0), 1u);
    EXPECT_EQ(s.materials.size(), 1u);
    EXPECT_EQ(s.meshes[0].material, 0);
    EXPECT_EQ(s.meshes[0].triangleCount(), 8u);

    ScratchDir dir;
    SceneDescription bare;
    appendObj(bare, dir.write("bare.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
    ASSERT_EQ(bare.materials.size(), 1u);
    EXPECT_EQ(bare.materials[0].albedo.x, 0.8f);
}

TEST(ObjLoader, BadIndexIsAnError) {
    ScratchDir dir;
    for (const char* face : {"f 1 2 9", "f 1 2 -7", "f 1 2 0", "f 1 2 x", "f 1/1 2/1 3/5"}) {
        const std::string path =
            dir.write("bad.obj", std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\n") + face + "\n");
        SceneDescription s;
        const std::string msg = inputErrorOf([&] { appendObj(s, path); });
        EXPECT_NE(msg.find("bad.obj"), std::string::npos) << face << ": " << msg;
    }
}

TEST(ObjLoader, NonFiniteVertexIsAnError) {
    ScratchDir dir;
    for (const char* v : {"v nan 0 0", "v 0 inf 0", "v 0 0 1e999", "vn nan 0 1", "vt -inf 0"}) {
        const std::string path =
            dir.write("nan.obj", std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\n") + v + "\nf 1 2 3\n");
        SceneDescription s;
        const std::string msg = inputErrorOf([&] { appendObj(s, path); });
        EXPECT_NE(msg.find("line 4"), std::string::npos) << v << ": " << msg;
    }
}

TEST(ObjLoader, ZeroAreaEmissiveTriangleIsAnError) {
    ScratchDir dir;
    dir.write("l.mtl", "newmtl lamp\nKe 1 1 1\n");
    const std::string path = dir.write(
        "l.obj",
        "mtllib l.mtl\nv 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nusemtl lamp\nf 1 2 4\nf 1 2 3\n");
    const std::string msg = inputErrorOf([&] { loadScene(path); });
    EXPECT_NE(msg.find("zero-area"), std::string::npos) << msg;
}

TEST(ObjLoader, MissingFilesAreErrors) {
    ScratchDir dir;
    SceneDescription s;
    EXPECT_THROW(appendObj(s, (dir.path() / "none.obj").string()), InputError);
    const std::string path =
        dir.write("m.obj", "mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_NE(inputErrorOf([&] { appendObj(s, path); }).find("gone.mtl"), std::string::npos);
    dir.write("t.mtl", "newmtl a\nmap_Kd missing.png\n");
    const std::string tex =
        dir.write("t.obj", "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n");
    EXPECT_NE(inputErrorOf([&] { appendObj(s, tex); }).find("missing.png"), std::string::npos);
}

TEST(ObjLoader, BareObjGetsCameraAndSky) {
    Fixture f;
    ScratchDir dir;
    const std::string path =
        dir.write("cube.obj", "v 0 0 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\nf 1 2 3 4\n");
    const SceneDescription s = loadScene(path);
    EXPECT_EQ(s.environment.x, 1.0f);  // no emitters: lit by the sky
    EXPECT_EQ(s.camera.target.x, 1.0f);
    EXPECT_EQ(s.camera.target.y, 1.0f);
    EXPECT_GT(s.camera.eye.z, 2.0f);  // in front (+z), outside the bounds
    const SceneDescription lit = loadScene(f.obj);
    EXPECT_EQ(lit.environment.x, 0.0f);  // has its own light
}

TEST(ObjLoader, ReadsTinyobjloadersCornellBox) {
    const std::string path = "/usr/share/doc/python3-tinyobjloader/examples/cornell_box.obj";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not installed";
    const SceneDescription s = loadScene(path);
    size_t triangles = 0;
    for (const Mesh& m : s.meshes) triangles += m.triangleCount();
    EXPECT_GE(triangles, 30u);
}

}  // namespace
}  // namespace pathlab
