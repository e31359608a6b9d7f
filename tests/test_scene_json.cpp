// pathlab's JSON scene format: every feature, a round trip, and strictness.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/image.h"
#include "scene/builtin_scenes.h"
#include "scene/json_scene.h"
#include "scene/loader.h"
#include "scene/mesh_utils.h"
#include "scene_test_util.h"

namespace pathlab {
namespace {

using test::inputErrorOf;
using test::ScratchDir;

SceneDescription parse(const std::string& text, const std::filesystem::path& dir = ".") {
    return parseJsonScene(text, dir, "test.json");
}

// A valid scene to break one piece at a time.
const char* kMinimal = R"({
  "camera": {"eye": [0, 1, 5], "target": [0, 1, 0], "fovY": 40},
  "materials": {"grey": {"type": "diffuse", "albedo": 0.5}},
  "meshes": [{"material": "grey", "quads": [[[-1,0,-1], [-1,0,1], [1,0,1], [1,0,-1]]]}],
  "lights": [{"type": "quad", "vertices": [[0,3,0], [1,3,0], [1,3,1], [0,3,1]], "emission": 10}]
})";

void expectSameScene(const SceneDescription& a, const SceneDescription& b) {
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.credit, b.credit);
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(a.camera.eye[i], b.camera.eye[i]);
        EXPECT_EQ(a.camera.target[i], b.camera.target[i]);
        EXPECT_EQ(a.camera.up[i], b.camera.up[i]);
        EXPECT_EQ(a.environment[i], b.environment[i]);
    }
    EXPECT_EQ(a.camera.fovY, b.camera.fovY);
    EXPECT_EQ(a.resolution.x, b.resolution.x);
    EXPECT_EQ(a.resolution.y, b.resolution.y);
    ASSERT_EQ(a.materials.size(), b.materials.size());
    for (size_t i = 0; i < a.materials.size(); ++i) {
        const Material &x = a.materials[i], &y = b.materials[i];
        EXPECT_EQ(x.name, y.name);
        EXPECT_EQ(x.type, y.type);
        for (int c = 0; c < 3; ++c) {
            EXPECT_EQ(x.albedo[c], y.albedo[c]);
            if (x.type == MaterialType::Conductor) {
                EXPECT_EQ(x.eta[c], y.eta[c]);
                EXPECT_EQ(x.k[c], y.k[c]);
            }
        }
        if (x.type == MaterialType::Dielectric) {
            EXPECT_EQ(x.ior, y.ior);
        }
        if (x.type == MaterialType::Conductor) {
            EXPECT_EQ(x.roughness, y.roughness);
        }
    }
    ASSERT_EQ(a.meshes.size(), b.meshes.size());
    for (size_t i = 0; i < a.meshes.size(); ++i) {
        const Mesh &x = a.meshes[i], &y = b.meshes[i];
        EXPECT_EQ(x.name, y.name);
        EXPECT_EQ(x.material, y.material);
        EXPECT_EQ(x.indices, y.indices);
        EXPECT_EQ(x.twoSided, y.twoSided);
        ASSERT_EQ(x.positions.size(), y.positions.size());
        for (size_t v = 0; v < x.positions.size(); ++v)
            for (int c = 0; c < 3; ++c) EXPECT_EQ(x.positions[v][c], y.positions[v][c]);
        ASSERT_EQ(x.normals.size(), y.normals.size());
        for (size_t v = 0; v < x.normals.size(); ++v)
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(x.normals[v][c], y.normals[v][c], 1e-6f);
        ASSERT_EQ(x.uvs.size(), y.uvs.size());
        for (size_t v = 0; v < x.uvs.size(); ++v) {
            EXPECT_EQ(x.uvs[v].x, y.uvs[v].x);
            EXPECT_EQ(x.uvs[v].y, y.uvs[v].y);
        }
        for (int c = 0; c < 3; ++c) EXPECT_EQ(x.emission[c], y.emission[c]);
    }
    ASSERT_EQ(a.spheres.size(), b.spheres.size());
    for (size_t i = 0; i < a.spheres.size(); ++i) {
        EXPECT_EQ(a.spheres[i].radius, b.spheres[i].radius);
        EXPECT_EQ(a.spheres[i].material, b.spheres[i].material);
        for (int c = 0; c < 3; ++c) EXPECT_EQ(a.spheres[i].center[c], b.spheres[i].center[c]);
    }
}

TEST(JsonScene, RoundTripOfTheCornellBox) {
    const SceneDescription box = cornellBoxScene();
    expectSameScene(box, parse(sceneToJson(box)));
}

TEST(JsonScene, RoundTripOfEveryFeature) {
    SceneDescription s = parse(kMinimal);
    s.name = "everything";
    s.credit = "nobody";
    s.environment = {0.1f, 0.2f, 0.3f};
    s.resolution = {320, 200};
    Material glass;
    glass.name = "glass";
    glass.type = MaterialType::Dielectric;
    glass.ior = 1.33f;
    glass.albedo = Vec3f(1.0f);
    Material metal;
    metal.name = "metal";
    metal.type = MaterialType::Conductor;
    metal.eta = {0.1f, 0.2f, 0.3f};
    metal.k = {3.1f, 2.2f, 1.3f};
    metal.roughness = 0.07f;
    metal.albedo = Vec3f(0.8f);
    Material mirror;
    mirror.name = "mirror";
    mirror.type = MaterialType::Mirror;
    mirror.albedo = {0.9f, 0.8f, 0.7f};
    s.materials.insert(s.materials.end(), {glass, metal, mirror});
    Mesh smooth;
    smooth.name = "smooth";
    smooth.material = 2;
    smooth.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    smooth.normals = {normalize(Vec3f(0.1f, 0.2f, 1)), {0, 0, 1}, normalize(Vec3f(0, 1, 1))};
    smooth.uvs = {{0, 0}, {1, 0}, {0.25f, 1.0f / 3.0f}};
    smooth.indices = {0, 1, 2};
    smooth.twoSided = true;
    s.meshes.push_back(smooth);
    s.spheres.push_back({{1, 2, 3}, 0.5f, 3});
    expectSameScene(s, parse(sceneToJson(s)));
}

TEST(JsonScene, ReadsEveryFeatureFromFiles) {
    ScratchDir dir;
    Image tex(2, 2);
    tex.set(0, 0, {1, 0, 0});
    tex.set(1, 1, {0, 0, 1});
    writeImage((dir.path() / "tex.png").string(), tex);
    dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const std::string path = dir.write("scene.json", R"({
      // comments are allowed
      "name": "all", "credit": "me",
      "camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "up": [0, 1, 0], "fovY": 30},
      "resolution": [64, 48],
      "environment": [0.1, 0.2, 0.3],
      "materials": {
        "tex": {"type": "diffuse", "texture": "tex.png"},
        "glass": {"type": "dielectric", "ior": 1.4},
        "chrome": {"type": "mirror"},
        "gold": {"type": "conductor", "metal": "gold", "roughness": 0.1},
        "custom": {"type": "conductor", "eta": [1, 1, 1], "k": 2}
      },
      "meshes": [
        {"obj": "tri.obj", "material": "gold",
         "transform": {"scale": 2, "rotate": {"axis": [0, 0, 1], "degrees": 90},
                       "translate": [10, 0, 0]}},
        {"name": "two", "material": "tex", "triangles": [[[0,0,0], [1,0,0], [0,1,0]]],
         "quads": [[[0,0,1], [1,0,1], [1,1,1], [0,1,1]]]}
      ],
      "lights": [
        {"name": "lamp", "type": "triangle", "vertices": [[0,3,0], [1,3,0], [0,3,1]],
         "emission": [1, 2, 3], "twoSided": true, "material": "chrome"}
      ],
      "spheres": [{"center": [1, 2, 3], "radius": 0.5, "material": "glass"}]
    })");
    const SceneDescription s = loadScene(path);
    EXPECT_EQ(s.name, "all");
    EXPECT_EQ(s.credit, "me");
    EXPECT_EQ(s.resolution.x, 64);
    EXPECT_EQ(s.resolution.y, 48);
    EXPECT_EQ(s.environment.z, 0.3f);
    ASSERT_EQ(s.materials.size(), 5u);
    EXPECT_EQ(s.materials[0].texture, 0);
    ASSERT_EQ(s.textures.size(), 1u);
    EXPECT_EQ(s.textures[0].width, 2);
    EXPECT_NEAR(s.textures[0].texels[0].x, 1.0f, 1e-6f);
    EXPECT_EQ(s.materials[1].type, MaterialType::Dielectric);
    EXPECT_EQ(s.materials[1].ior, 1.4f);
    EXPECT_EQ(s.materials[2].type, MaterialType::Mirror);
    EXPECT_EQ(s.materials[3].type, MaterialType::Conductor);
    EXPECT_EQ(s.materials[3].roughness, 0.1f);
    EXPECT_EQ(s.materials[4].k.y, 2.0f);
    ASSERT_EQ(s.meshes.size(), 3u);
    // The OBJ triangle: scaled by 2, turned 90° about z, moved by 10 in x.
    const Mesh& obj = s.meshes[0];
    EXPECT_EQ(obj.material, 3);
    EXPECT_NEAR(obj.positions[1].x, 10.0f, 1e-5f);
    EXPECT_NEAR(obj.positions[1].y, 2.0f, 1e-5f);
    EXPECT_NEAR(obj.positions[2].x, 8.0f, 1e-5f);
    EXPECT_NEAR(obj.positions[2].y, 0.0f, 1e-5f);
    EXPECT_EQ(s.meshes[1].name, "two");
    EXPECT_EQ(s.meshes[1].triangleCount(), 3u);
    const Mesh& lamp = s.meshes[2];
    EXPECT_EQ(lamp.name, "lamp");
    EXPECT_EQ(lamp.emission.y, 2.0f);
    EXPECT_TRUE(lamp.twoSided);
    EXPECT_EQ(lamp.material, 2);
    ASSERT_EQ(s.spheres.size(), 1u);
    EXPECT_EQ(s.spheres[0].material, 1);
}

TEST(JsonScene, LightsDefaultToOneSidedNonReflecting) {
    const SceneDescription s = parse(kMinimal);
    const Mesh& light = s.meshes.back();
    EXPECT_FALSE(light.twoSided);
    EXPECT_EQ(light.emission.x, 10.0f);
    EXPECT_TRUE(isBlack(s.materials.at(size_t(light.material)).albedo));
}

TEST(JsonScene, MalformedJsonGivesLineAndColumn) {
    const std::string msg =
        inputErrorOf([] { parse("{\n  \"camera\": {\n    \"eye\": [0, 0 0]\n"); });
    EXPECT_NE(msg.find("test.json"), std::string::npos) << msg;
    EXPECT_NE(msg.find("line 3"), std::string::npos) << msg;
    EXPECT_NE(msg.find("column"), std::string::npos) << msg;
}

// A number too large for a double is bad input too, not an internal error.
TEST(JsonScene, NumberOverflowIsAnInputError) {
    const std::string msg = inputErrorOf([] { parse("{\"camera\": {\"fovY\": 222e222222}}"); });
    EXPECT_NE(msg.find("test.json: invalid JSON"), std::string::npos) << msg;
    EXPECT_NE(msg.find("number overflow"), std::string::npos) << msg;
}

struct BadCase {
    const char* from;
    const char* to;
    const char* mustMention;
};

// Each case edits kMinimal once; the message must name the offending key.
TEST(JsonScene, StrictErrorsNameTheKey) {
    const BadCase cases[] = {
        {"\"fovY\": 40", "\"fovY\": 40, \"fov\": 3", "'fov'"},           // unknown key
        {"\"fovY\": 40", "\"fovY\": \"wide\"", "camera.fovY"},           // wrong type
        {"\"eye\": [0, 1, 5], ", "", "'eye'"},                           // missing
        {"\"eye\": [0, 1, 5]", "\"eye\": [0, 1]", "camera.eye"},         // wrong length
        {"\"material\": \"grey\"", "\"material\": \"gray\"", "'gray'"},  // bad reference
        {"\"type\": \"diffuse\"", "\"type\": \"plastic\"", "materials.grey.type"},
        {"\"albedo\": 0.5", "\"albedo\": 0.5, \"ior\": 2", "'ior'"},  // key of another type
        {"\"albedo\": 0.5", "\"albedo\": -1", "materials.grey.albedo"},
        {"\"albedo\": 0.5", "\"albedo\": 0.5, \"texture\": \"t.png\"", "'texture'"},
        {"\"type\": \"quad\"", "\"type\": \"disk\"", "lights[0].type"},
        {"\"emission\": 10", "\"emission\": 10, \"emission\": 5", "'emission'"},  // duplicate
        {"\"fovY\": 40", "\"fovY\": 180", "camera.fovY"},
        {"[[-1,0,-1], [-1,0,1], [1,0,1], [1,0,-1]]", "[[-1,0,-1], [-1,0,1], [1,0,1]]",
         "meshes[0].quads[0]"},
        {"\"emission\": 10", "\"emission\": 10, \"twoSided\": 1", "lights[0].twoSided"},
        {"\"camera\"", "\"cam\"", "'cam'"},
        {"[[0,3,0], [1,3,0], [1,3,1], [0,3,1]]", "[[0,3,0], [0,3,0], [0,3,0], [0,3,0]]",
         "zero area"},
    };
    for (const BadCase& c : cases) {
        std::string text = kMinimal;
        const size_t at = text.find(c.from);
        ASSERT_NE(at, std::string::npos) << c.from;
        text.replace(at, std::string(c.from).size(), c.to);
        const std::string msg = inputErrorOf([&] { parse(text); });
        EXPECT_NE(msg.find(c.mustMention), std::string::npos)
            << "case " << c.to << " gave: " << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << "one line: " << msg;
    }
}

TEST(JsonScene, MissingFilesAreNamed) {
    ScratchDir dir;
    const std::string path = dir.write("s.json", R"({
      "camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "fovY": 30},
      "meshes": [{"obj": "nothere.obj"}]})");
    const std::string msg = inputErrorOf([&] { loadScene(path); });
    EXPECT_NE(msg.find("meshes[0].obj"), std::string::npos) << msg;
    EXPECT_NE(msg.find("nothere.obj"), std::string::npos) << msg;
}

TEST(JsonScene, EmptySceneIsAnError) {
    EXPECT_THROW(parse(R"({"camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "fovY": 30}})"),
                 InputError);
}

TEST(JsonScene, ShippedScenesLoad) {
    for (const char* name : {"cornell-box.json", "glass-and-metal.json"}) {
        const SceneDescription s = loadScene(std::string(PATHLAB_SOURCE_DIR) + "/scenes/" + name);
        EXPECT_FALSE(s.meshes.empty()) << name;
    }
    const SceneDescription gm =
        loadScene(std::string(PATHLAB_SOURCE_DIR) + "/scenes/glass-and-metal.json");
    bool types[4] = {};
    for (const Sphere& sp : gm.spheres)
        types[int(gm.materials.at(size_t(sp.material)).type)] = true;
    EXPECT_TRUE(types[int(MaterialType::Mirror)]);
    EXPECT_TRUE(types[int(MaterialType::Dielectric)]);
    EXPECT_TRUE(types[int(MaterialType::Conductor)]);
}

// The commented example in docs/scene-format.md is a valid scene.
TEST(JsonScene, DocumentedExampleLoads) {
    std::ifstream doc(std::string(PATHLAB_SOURCE_DIR) + "/docs/scene-format.md");
    std::stringstream text;
    text << doc.rdbuf();
    const std::string md = text.str();
    const size_t begin = md.find("```jsonc\n");
    ASSERT_NE(begin, std::string::npos);
    const size_t end = md.find("```", begin + 8);
    const std::string example = md.substr(begin + 9, end - begin - 9);
    ScratchDir dir;
    std::filesystem::create_directories(dir.path() / "models");
    dir.write("models/bunny.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    Image fur(1, 1);
    writeImage((dir.path() / "fur.png").string(), fur);
    writeImage((dir.path() / "sky.exr").string(), Image(4, 4));
    writeImage((dir.path() / "tiles-normals.png").string(), fur);
    writeImage((dir.path() / "heights.png").string(), fur);
    const SceneDescription s = loadScene(dir.write("example.json", example));
    EXPECT_EQ(s.name, "example");
    EXPECT_EQ(s.materials.size(), 17u);  // sixteen named and the lights' black one
    ASSERT_EQ(s.spheres.size(), 2u);
    EXPECT_EQ(s.spheres[1].emission.x, 40);  // an emitting sphere
    EXPECT_EQ(s.punctualLights.size(), 3u);
    EXPECT_EQ(s.environmentMap.width, 4);
}

}  // namespace
}  // namespace pathlab
