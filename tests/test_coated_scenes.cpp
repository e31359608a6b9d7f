// Coated materials in both scene formats: pbrt-v4's coateddiffuse and
// coatedconductor parameters (prefixed "interface.*" and "conductor.*",
// pbrt-v4's defaults, the conductor's "reflectance"), pathlab's JSON
// "coating" with the same meaning, a JSON write and re-read that keeps every
// field, and one-line errors for bad values.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/json_scene.h"
#include "scene/named_spectra.h"
#include "scene/pbrt/importer.h"
#include "scene_test_util.h"

namespace pathlab {
namespace {

const std::string kTriangle =
    R"(Shape "trianglemesh" "point3 P" [0 0 0  1 0 0  0 1 0] "integer indices" [0 1 2])";

Material pbrtMaterial(const std::string& material) {
    const pbrt::ImportResult r = pbrt::importPbrtText(
        "WorldBegin\n" + material + "\n" + kTriangle + "\n", "test.pbrt", ".", {});
    return r.scene.materials[size_t(r.scene.meshes[0].material)];
}

std::string pbrtError(const std::string& material) {
    return test::inputErrorOf([&] { pbrtMaterial(material); });
}

TEST(CoatedScenes, PbrtCoatedDiffuseDefaultsAndParameters) {
    const Material d = pbrtMaterial(R"(Material "coateddiffuse")");
    EXPECT_EQ(d.type, MaterialType::CoatedDiffuse);
    EXPECT_FLOAT_EQ(d.albedo.y, 0.5f);
    EXPECT_FLOAT_EQ(d.coating.eta, 1.5f);
    EXPECT_FLOAT_EQ(d.coating.thickness, 0.01f);
    EXPECT_EQ(d.coating.maxDepth, 10);
    EXPECT_EQ(d.coating.nSamples, 1);
    EXPECT_EQ(d.coating.roughness, 0.0f);
    const Material m = pbrtMaterial(
        R"(Material "coateddiffuse" "rgb reflectance" [0.1 0.2 0.3] "float roughness" 0.04
           "float thickness" 0.2 "rgb albedo" [0.5 0.6 0.7] "float g" -0.2 "float eta" 1.33
           "integer maxdepth" 20 "integer nsamples" 4)");
    EXPECT_FLOAT_EQ(m.albedo.z, 0.3f);
    EXPECT_FLOAT_EQ(m.coating.roughness, 0.2f);  // √0.04, remapped
    EXPECT_FLOAT_EQ(m.coating.thickness, 0.2f);
    EXPECT_FLOAT_EQ(m.coating.albedo.y, 0.6f);
    EXPECT_FLOAT_EQ(m.coating.g, -0.2f);
    EXPECT_FLOAT_EQ(m.coating.eta, 1.33f);
    EXPECT_EQ(m.coating.maxDepth, 20);
    EXPECT_EQ(m.coating.nSamples, 4);
    const Material raw = pbrtMaterial(
        R"(Material "coateddiffuse" "float uroughness" 0.04 "float vroughness" 0.09
           "bool remaproughness" false)");
    EXPECT_FLOAT_EQ(raw.coating.roughness, 0.04f);
    EXPECT_FLOAT_EQ(raw.coating.roughnessV, 0.09f);
}

TEST(CoatedScenes, PbrtCoatedConductorPrefixedParameters) {
    const Material cu = pbrtMaterial(R"(Material "coatedconductor")");
    EXPECT_EQ(cu.type, MaterialType::CoatedConductor);
    EXPECT_FLOAT_EQ(cu.eta.x, namedMetalSpectrum("metal-Cu-eta")->x);
    EXPECT_EQ(cu.roughness, 0.0f);
    const Material au = pbrtMaterial(
        R"(Material "coatedconductor" "float interface.roughness" 0.01 "float interface.eta" 1.4
           "spectrum conductor.eta" "metal-Au-eta" "spectrum conductor.k" "metal-Au-k"
           "float conductor.uroughness" 0.09 "float conductor.vroughness" 0.16
           "float thickness" 0.05)");
    EXPECT_FLOAT_EQ(au.coating.roughness, 0.1f);
    EXPECT_FLOAT_EQ(au.coating.eta, 1.4f);
    EXPECT_FLOAT_EQ(au.k.x, namedMetalSpectrum("metal-Au-k")->x);
    EXPECT_FLOAT_EQ(au.roughness, 0.3f);
    EXPECT_FLOAT_EQ(au.roughnessV, 0.4f);
    EXPECT_FLOAT_EQ(au.coating.thickness, 0.05f);
    const Material r =
        pbrtMaterial(R"(Material "coatedconductor" "rgb reflectance" [0.8 0.8 0.8])");
    EXPECT_FLOAT_EQ(r.eta.x, 1.0f);
    EXPECT_FLOAT_EQ(r.k.x, 2 * std::sqrt(0.8f) / std::sqrt(0.2f));
    // The unprefixed "remaproughness" governs both layers: the given
    // roughness is then the alpha itself, to the bit.
    const Material raw = pbrtMaterial(
        R"(Material "coatedconductor" "bool remaproughness" false
           "float interface.roughness" 0.013 "float conductor.roughness" 0.37)");
    EXPECT_EQ(raw.coating.roughness, 0.013f);
    EXPECT_EQ(raw.roughness, 0.37f);
}

TEST(CoatedScenes, PbrtBadCoatingIsOneLine) {
    EXPECT_EQ(pbrtError(R"(Material "coateddiffuse" "float thickness" 0)"),
              "test.pbrt:2:1: coated material: thickness must be positive");
    EXPECT_EQ(pbrtError(R"(Material "coateddiffuse" "float g" 1)"),
              "test.pbrt:2:1: coated material: g must lie in (-1, 1)");
    EXPECT_EQ(pbrtError(R"(Material "coatedconductor" "integer nsamples" 0)"),
              "test.pbrt:2:1: coated material: maxdepth and nsamples must be at least 1");
    EXPECT_NE(pbrtError(R"(Material "coatedconductor" "float interface.bogus" 1)")
                  .find("(prefixed \"interface.\")"),
              std::string::npos);
}

// Coated materials take constant parameters only: a texture there is
// reported (strict) or dropped for the default (lenient), never half-used.
TEST(CoatedScenes, PbrtTexturedCoatedParametersAreUnsupported) {
    const std::string texture = "Texture \"r\" \"float\" \"constant\" \"float value\" 0.3\n";
    EXPECT_EQ(
        pbrtError(texture + R"(Material "coatedconductor" "texture conductor.roughness" "r")"),
        "test.pbrt:3:1: a textured roughness on a coated material is not supported "
        "(--lenient substitutes roughness 0)");
    EXPECT_EQ(pbrtError(texture + R"(Material "coateddiffuse" "texture roughness" "r")"),
              "test.pbrt:3:1: a textured roughness on a coated material is not supported "
              "(--lenient substitutes roughness 0)");
    pbrt::ImportOptions lenient;
    lenient.lenient = true;
    const pbrt::ImportResult r = pbrt::importPbrtText(
        "WorldBegin\n" + texture +
            R"(Material "coatedconductor" "texture conductor.roughness" "r" "texture interface.roughness" "r")" +
            "\n" + kTriangle + "\n",
        "test.pbrt", ".", lenient);
    const Material& m = r.scene.materials[size_t(r.scene.meshes[0].material)];
    EXPECT_EQ(m.type, MaterialType::CoatedConductor);
    EXPECT_EQ(m.roughnessTexture, -1);
    EXPECT_EQ(m.roughnessVTexture, -1);
    EXPECT_EQ(m.albedoTexture, -1);
    EXPECT_EQ(m.roughness, 0.0f);
    EXPECT_EQ(m.coating.roughness, 0.0f);
    ASSERT_EQ(r.warnings.size(), 2u);  // one per layer, each said once
    for (const std::string& w : r.warnings)
        EXPECT_NE(w.find("a textured roughness on a coated material"), std::string::npos) << w;
}

const char* kJson = R"({
  "camera": {"eye": [0, 1, 5], "target": [0, 1, 0], "fovY": 40},
  "materials": {
    "lacquer": {"type": "coateddiffuse", "reflectance": [0.7, 0.1, 0.08],
                "coating": {"ior": 1.4, "roughness": 0.1, "roughnessV": 0.2, "thickness": 0.3,
                            "albedo": [0.5, 0.6, 0.7], "g": 0.25, "maxDepth": 33,
                            "samples": 2}},
    "gold": {"type": "coatedconductor", "metal": "gold", "roughness": 0.15}
  },
  "spheres": [{"center": [0, 0, 0], "radius": 1, "material": "lacquer"},
              {"center": [3, 0, 0], "radius": 1, "material": "gold"}]
})";

void expectCoated(const SceneDescription& s) {
    ASSERT_EQ(s.materials.size(), 2u);
    const Material& l = s.materials[0].name == "lacquer" ? s.materials[0] : s.materials[1];
    const Material& g = s.materials[0].name == "lacquer" ? s.materials[1] : s.materials[0];
    EXPECT_EQ(l.type, MaterialType::CoatedDiffuse);
    EXPECT_FLOAT_EQ(l.albedo.x, 0.7f);
    EXPECT_FLOAT_EQ(l.coating.eta, 1.4f);
    EXPECT_FLOAT_EQ(l.coating.roughness, 0.1f);
    EXPECT_FLOAT_EQ(l.coating.roughnessV, 0.2f);
    EXPECT_FLOAT_EQ(l.coating.thickness, 0.3f);
    EXPECT_FLOAT_EQ(l.coating.albedo.z, 0.7f);
    EXPECT_FLOAT_EQ(l.coating.g, 0.25f);
    EXPECT_EQ(l.coating.maxDepth, 33);
    EXPECT_EQ(l.coating.nSamples, 2);
    EXPECT_EQ(g.type, MaterialType::CoatedConductor);
    EXPECT_FLOAT_EQ(g.roughness, 0.15f);
    EXPECT_FLOAT_EQ(g.coating.eta, 1.5f);  // pbrt-v4's defaults
    EXPECT_FLOAT_EQ(g.coating.thickness, 0.01f);
    EXPECT_EQ(g.coating.maxDepth, 10);
}

TEST(CoatedScenes, JsonReadsWritesAndRereads) {
    const SceneDescription s = parseJsonScene(kJson, ".", "test.json");
    expectCoated(s);
    expectCoated(parseJsonScene(sceneToJson(s), ".", "again.json"));
}

TEST(CoatedScenes, JsonBadCoatingIsOneLine) {
    const auto error = [](const std::string& coating) {
        const std::string text = R"({"camera": {"eye": [0, 1, 5], "target": [0, 0, 0], "fovY": 40},
          "materials": {"c": {"type": "coateddiffuse", "coating": )" +
                                 coating + R"(}},
          "spheres": [{"center": [0, 0, 0], "radius": 1, "material": "c"}]})";
        return test::inputErrorOf([&] { parseJsonScene(text, ".", "t.json"); });
    };
    EXPECT_NE(error(R"({"thickness": 0})").find("thickness"), std::string::npos);
    EXPECT_NE(error(R"({"g": -1})").find("between -1 and 1"), std::string::npos);
    EXPECT_NE(error(R"({"maxDepth": 2.5})").find("whole number"), std::string::npos);
    EXPECT_NE(error(R"({"albedo": 1.5})").find("at most 1"), std::string::npos);
    EXPECT_NE(error(R"({"bogus": 1})").find("bogus"), std::string::npos);
    for (const char* c : {R"({"thickness": 0})", R"({"bogus": 1})"})
        EXPECT_EQ(error(c).find('\n'), std::string::npos);
}

}  // namespace
}  // namespace pathlab
