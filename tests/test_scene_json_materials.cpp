// pathlab's JSON format for the pbrt-v4 materials: every material reads as
// documented (docs/scene-format.md), survives a write and re-read, and bad
// values are one-line errors naming their key.
#include <gtest/gtest.h>

#include "scene/json_scene.h"
#include "scene_test_util.h"

namespace pathlab {
namespace {

const char* kScene = R"({
  "camera": {"eye": [0, 1, 5], "target": [0, 1, 0], "fovY": 40},
  "materials": {
    "wall": {"type": "diffuse"},
    "frosted": {"type": "dielectric", "ior": 1.33, "roughness": 0.2},
    "brushed": {"type": "conductor", "metal": "aluminium", "roughness": 0.02, "roughnessV": 0.3},
    "pane": {"type": "thindielectric", "ior": 1.6},
    "leaf": {"type": "diffusetransmission", "reflectance": [0.2, 0.4, 0.1],
             "transmittance": 0.5},
    "worn": {"type": "mix", "materials": ["wall", "brushed"], "amount": 0.3},
    "portal": {"type": "interface"}
  },
  "spheres": [{"center": [0, 0, 0], "radius": 1, "material": "worn"}]
})";

SceneDescription parse(const std::string& text) {
    return parseJsonScene(text, ".", "test.json");
}

const Material& byName(const SceneDescription& s, const std::string& name) {
    for (const Material& m : s.materials)
        if (m.name == name) return m;
    throw std::runtime_error("no material " + name);
}

void expectMaterials(const SceneDescription& s) {
    const Material& frosted = byName(s, "frosted");
    EXPECT_EQ(frosted.type, MaterialType::Dielectric);
    EXPECT_FLOAT_EQ(frosted.ior, 1.33f);
    EXPECT_FLOAT_EQ(frosted.roughness, 0.2f);
    EXPECT_LT(frosted.roughnessV, 0.0f);
    const Material& brushed = byName(s, "brushed");
    EXPECT_FLOAT_EQ(brushed.roughness, 0.02f);
    EXPECT_FLOAT_EQ(brushed.roughnessV, 0.3f);
    EXPECT_EQ(byName(s, "pane").type, MaterialType::ThinDielectric);
    EXPECT_FLOAT_EQ(byName(s, "pane").ior, 1.6f);
    const Material& leaf = byName(s, "leaf");
    EXPECT_EQ(leaf.type, MaterialType::DiffuseTransmission);
    EXPECT_FLOAT_EQ(leaf.albedo.y, 0.4f);
    EXPECT_FLOAT_EQ(leaf.transmittance.z, 0.5f);
    const Material& worn = byName(s, "worn");
    EXPECT_EQ(worn.type, MaterialType::Mix);
    EXPECT_EQ(s.materials[size_t(worn.mix[0])].name, "wall");
    EXPECT_EQ(s.materials[size_t(worn.mix[1])].name, "brushed");
    EXPECT_FLOAT_EQ(worn.amount, 0.3f);
    EXPECT_EQ(byName(s, "portal").type, MaterialType::Interface);
}

TEST(JsonMaterials, ReadAsDocumentedAndSurviveAWrite) {
    const SceneDescription s = parse(kScene);
    expectMaterials(s);
    // A smooth dielectric stays smooth (its roughness is 0, not the conductor's default).
    const SceneDescription glass = parse(R"({"camera": {"eye": [0, 1, 5], "target": [0, 1, 0],
        "fovY": 40}, "materials": {"g": {"type": "dielectric"}},
        "spheres": [{"center": [0, 0, 0], "radius": 1, "material": "g"}]})");
    EXPECT_EQ(glass.materials[0].roughness, 0.0f);
    expectMaterials(parse(sceneToJson(s)));
}

TEST(JsonMaterials, BadValuesNameTheirKey) {
    const auto errorOf = [](const std::string& materials) {
        return test::inputErrorOf([&] {
            parse(R"({"camera": {"eye": [0, 1, 5], "target": [0, 1, 0], "fovY": 40},
                      "materials": {)" +
                  materials + "}}");
        });
    };
    EXPECT_EQ(errorOf(R"("m": {"type": "dielectric", "roughness": -1})"),
              "test.json: materials.m.roughness: must not be negative");
    EXPECT_EQ(errorOf(R"("m": {"type": "mix", "materials": ["a"]})"),
              "test.json: materials.m.materials: expected two material names");
    EXPECT_EQ(errorOf(R"("m": {"type": "mix", "materials": ["m", "x"]})"),
              "test.json: materials.m.materials[1]: unknown material 'x'");
    EXPECT_EQ(errorOf(R"("m": {"type": "mix", "materials": ["m", "m"]})"),
              "test.json: materials: mix material 'm' contains itself");
    EXPECT_EQ(errorOf(R"("m": {"type": "thindielectric", "roughness": 0.1})"),
              "test.json: materials.m: unknown key 'roughness' (expected one of: type, ior, "
              "normalMap, bumpMap, bumpScale, displacement)");
    EXPECT_EQ(errorOf(R"("m": {"type": "diffusetransmission", "transmittance": 2})"),
              "test.json: materials.m.transmittance: must be at most 1");
}

}  // namespace
}  // namespace pathlab
