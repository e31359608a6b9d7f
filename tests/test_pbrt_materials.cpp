// pbrt-v4's materials as the importer reads them: parameters, defaults,
// named spectra, roughness remapping, named materials used before they are
// defined, mix and interface, and the one-line errors.
#include <gtest/gtest.h>

#include <cmath>

#include "render/render_scene.h"
#include "scene/named_spectra.h"
#include "scene/pbrt/importer.h"
#include "scene_test_util.h"

namespace pathlab::pbrt {
namespace {

using test::inputErrorOf;

const std::string kTriangle =
    R"(Shape "trianglemesh" "point3 P" [0 0 0  1 0 0  0 1 0] "integer indices" [0 1 2])";

std::string world(const std::string& body) {
    return "WorldBegin\n" + body + "\n";
}
ImportResult load(const std::string& text, bool lenient = false) {
    return importPbrtText(text, "test.pbrt", ".", {lenient});
}
std::string errorOf(const std::string& text) {
    return inputErrorOf([&] { load(text); });
}
// The material of the scene's first mesh.
Material firstMaterial(const std::string& material) {
    const ImportResult r = load(world(material + "\n" + kTriangle));
    return r.scene.materials[size_t(r.scene.meshes.at(0).material)];
}

TEST(PbrtMaterials, ConductorRoughnessIsRemappedAndMayBeAnisotropic) {
    const Material iso = firstMaterial(R"(Material "conductor" "float roughness" 0.09)");
    EXPECT_EQ(iso.type, MaterialType::Conductor);
    EXPECT_FLOAT_EQ(iso.roughness, 0.3f);  // RoughnessToAlpha: √0.09
    EXPECT_LT(iso.roughnessV, 0.0f);       // isotropic
    const Material aniso =
        firstMaterial(R"(Material "conductor" "float roughness" 0.04 "float vroughness" 0.25)");
    EXPECT_FLOAT_EQ(aniso.roughness, 0.2f);  // u falls back to roughness
    EXPECT_FLOAT_EQ(aniso.roughnessV, 0.5f);
    const Material raw = firstMaterial(
        R"(Material "conductor" "float uroughness" 0.04 "float vroughness" 0.25 "bool remaproughness" false)");
    EXPECT_FLOAT_EQ(raw.roughness, 0.04f);
    EXPECT_FLOAT_EQ(raw.roughnessV, 0.25f);
}

TEST(PbrtMaterials, ConductorNamedSpectraAndDefaults) {
    const Material gold = firstMaterial(
        R"(Material "conductor" "spectrum eta" "metal-Au-eta" "spectrum k" "metal-Au-k")");
    EXPECT_EQ(gold.eta.x, namedMetalSpectrum("metal-Au-eta")->x);
    EXPECT_EQ(gold.k.z, namedMetalSpectrum("metal-Au-k")->z);
    // Gold reflects red more than blue: η small and k large in red.
    EXPECT_LT(gold.eta.x, gold.eta.z);
    EXPECT_GT(gold.k.x, gold.k.z);
    // pbrt-v4's default is copper.
    const Material plain = firstMaterial(R"(Material "conductor")");
    EXPECT_EQ(plain.eta.y, namedMetalSpectrum("metal-Cu-eta")->y);
    EXPECT_EQ(plain.k.y, namedMetalSpectrum("metal-Cu-k")->y);
    EXPECT_FLOAT_EQ(plain.roughness, 0.0f);
    for (const char* metal : {"Ag", "Al", "Au", "Cu", "CuZn", "MgO", "TiO2"})
        for (const char* part : {"-eta", "-k"})
            EXPECT_TRUE(namedMetalSpectrum(std::string("metal-") + metal + part)) << metal << part;
    EXPECT_FALSE(namedMetalSpectrum("metal-Pt-eta"));
}

TEST(PbrtMaterials, ConductorReflectanceGivesThatReflectanceAtNormalIncidence) {
    const Material m = firstMaterial(R"(Material "conductor" "rgb reflectance" [0.9 0.5 0.2])");
    EXPECT_EQ(m.eta.x, 1.0f);
    const float expected[] = {0.9f, 0.5f, 0.2f};
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(fresnelComplex(1.0f, m.eta[c], m.k[c]), expected[c], 1e-5f);
    EXPECT_EQ(
        errorOf(world(R"(Material "conductor" "rgb reflectance" [0.5 0.5 0.5] "rgb eta" [1 1 1])")),
        "test.pbrt:2:1: conductor: give \"reflectance\" or \"eta\" and \"k\", not both");
}

TEST(PbrtMaterials, DielectricRoughnessAndNamedGlass) {
    const Material smooth = firstMaterial(R"(Material "dielectric")");
    EXPECT_EQ(smooth.type, MaterialType::Dielectric);
    EXPECT_FLOAT_EQ(smooth.ior, 1.5f);
    EXPECT_EQ(smooth.roughness, 0.0f);
    const Material rough =
        firstMaterial(R"(Material "dielectric" "spectrum eta" "glass-BK7" "float roughness" 0.01)");
    EXPECT_NEAR(rough.ior, 1.5168f, 1e-4f);  // BK7's catalogue n_d
    EXPECT_FLOAT_EQ(rough.roughness, 0.1f);
    EXPECT_NEAR(*namedGlassIor("glass-F11"), 1.7847f, 1e-3f);  // SF11's n_d
    const Material thin = firstMaterial(R"(Material "thindielectric" "float eta" 1.33)");
    EXPECT_EQ(thin.type, MaterialType::ThinDielectric);
    EXPECT_FLOAT_EQ(thin.ior, 1.33f);
    EXPECT_EQ(errorOf(world(R"(Material "dielectric" "float roughness" -0.1)")),
              "test.pbrt:2:1: roughness must not be negative");
}

TEST(PbrtMaterials, DiffuseTransmissionScalesAndClamps) {
    const Material m = firstMaterial(
        R"(Material "diffusetransmission" "rgb reflectance" [0.2 0.4 0.8] "rgb transmittance" [0.5 0.1 0.3] "float scale" 1.5)");
    EXPECT_EQ(m.type, MaterialType::DiffuseTransmission);
    EXPECT_FLOAT_EQ(m.albedo.x, 0.3f);
    EXPECT_FLOAT_EQ(m.albedo.z, 1.0f);  // clamped
    EXPECT_FLOAT_EQ(m.transmittance.x, 0.75f);
    const Material d = firstMaterial(R"(Material "diffusetransmission")");
    EXPECT_FLOAT_EQ(d.albedo.y, 0.25f);
    EXPECT_FLOAT_EQ(d.transmittance.y, 0.25f);
}

TEST(PbrtMaterials, NamedMaterialsMayBeUsedBeforeTheyAreDefined) {
    const ImportResult r = load(world("NamedMaterial \"gold\"\n" + kTriangle +
                                      "\nMakeNamedMaterial \"gold\" \"string type\" "
                                      "\"conductor\" \"float roughness\" 0.01\n"));
    const Material& m = r.scene.materials[size_t(r.scene.meshes[0].material)];
    EXPECT_EQ(m.type, MaterialType::Conductor);
    EXPECT_EQ(m.name, "gold");
    EXPECT_EQ(errorOf(world("NamedMaterial \"gold\"\n" + kTriangle)),
              "test.pbrt:2:1: NamedMaterial: no material named 'gold'");
    EXPECT_EQ(errorOf(world("MakeNamedMaterial \"a\" \"string type\" \"diffuse\"\n"
                            "MakeNamedMaterial \"a\" \"string type\" \"diffuse\"")),
              "test.pbrt:3:1: MakeNamedMaterial: material 'a' is already defined");
}

TEST(PbrtMaterials, MixNamesMaterialsDefinedBeforeIt) {
    const ImportResult r =
        load(world("MakeNamedMaterial \"a\" \"string type\" \"diffuse\"\n"
                   "MakeNamedMaterial \"b\" \"string type\" \"conductor\"\n"
                   "Material \"mix\" \"string materials\" [\"a\" \"b\"] \"float amount\" 0.25\n" +
                   kTriangle));
    const Material& m = r.scene.materials[size_t(r.scene.meshes[0].material)];
    EXPECT_EQ(m.type, MaterialType::Mix);
    EXPECT_EQ(r.scene.materials[size_t(m.mix[0])].type, MaterialType::Diffuse);
    EXPECT_EQ(r.scene.materials[size_t(m.mix[1])].type, MaterialType::Conductor);
    EXPECT_FLOAT_EQ(m.amount, 0.25f);
    EXPECT_EQ(errorOf(world("Material \"mix\" \"string materials\" [\"a\" \"b\"]")),
              "test.pbrt:2:1: mix: no material named 'a' defined before it");
    EXPECT_EQ(errorOf(world("NamedMaterial \"x\"\n"
                            "MakeNamedMaterial \"x\" \"string type\" \"mix\" "
                            "\"string materials\" [\"x\" \"x\"]")),
              "test.pbrt:3:1: mix: no material named 'x' defined before it");
    EXPECT_EQ(errorOf(world("MakeNamedMaterial \"i\" \"string type\" \"interface\"\n"
                            "Material \"mix\" \"string materials\" [\"i\" \"i\"]")),
              "test.pbrt:3:1: mix: 'i' is an interface, which cannot be mixed");
    EXPECT_EQ(errorOf(world("Material \"mix\" \"string materials\" \"a\"")),
              "test.pbrt:2:1: mix: needs \"string materials\" with two material names");
}

TEST(PbrtMaterials, MixChoosesByAmountDeterministicallyPerShadingPoint) {
    const ImportResult r =
        load(world("MakeNamedMaterial \"a\" \"string type\" \"diffuse\"\n"
                   "MakeNamedMaterial \"b\" \"string type\" \"conductor\"\n"
                   "Material \"mix\" \"string materials\" [\"a\" \"b\"] \"float amount\" 0.3\n" +
                   kTriangle));
    const int mixIndex = r.scene.meshes[0].material;
    const int b = r.scene.materials[size_t(mixIndex)].mix[1];
    const RenderScene scene(r.scene);
    const int n = 100000;
    int chosenB = 0;
    for (int i = 0; i < n; ++i) {
        const Vec3f p{float(i % 317) / 317, float(i / 317) / 317, 0};
        const Vec3f dir = normalize(Vec3f(0.1f, 0.2f, -1));
        const int c = scene.mixComponent(mixIndex, p, dir);
        ASSERT_EQ(c, scene.mixComponent(mixIndex, p, dir));  // same point: same choice
        chosenB += c == b;
    }
    // Binomial: 0.3 ± 4.5 standard deviations (σ = √(0.21/n) ≈ 0.0014).
    EXPECT_NEAR(double(chosenB) / n, 0.3, 0.0065);
}

TEST(PbrtMaterials, InterfaceIsNoSurface) {
    const Material m = firstMaterial(R"(Material "interface")");
    EXPECT_EQ(m.type, MaterialType::Interface);
}

}  // namespace
}  // namespace pathlab::pbrt
