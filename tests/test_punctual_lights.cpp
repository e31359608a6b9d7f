// Point, spot and distant lights: a diffuse floor lit by each has the radiance
// (albedo/π)·E computed by hand, in both integrators (which also shows the
// light sample's MIS weight is 1: weighted against the BSDF's density, the
// floor came out about 9% too dark); shadows; the light choice in proportion
// to power; and the JSON and pbrt-v4 readers.
#include <gtest/gtest.h>

#include <cmath>

#include "render/lights.h"
#include "render/renderer.h"
#include "scene/json_scene.h"
#include "scene/pbrt/importer.h"
#include "scene_test_util.h"

namespace pathlab {
namespace {

constexpr float kAlbedo = 0.5f;

// A 20×20 diffuse floor at y = 0, seen straight down through a 0.5° field of
// view from height 1 above the origin: every pixel sees the floor within
// 0.005 of the origin. Lit by `light` alone.
SceneDescription floorUnder(const PunctualLight& light, bool occluder = false) {
    SceneDescription s;
    s.materials.push_back(Material{"floor", MaterialType::Diffuse, Vec3f(kAlbedo)});
    Mesh floor;
    floor.positions = {{-10, 0, -10}, {-10, 0, 10}, {10, 0, 10}, {10, 0, -10}};
    floor.indices = {0, 1, 2, 0, 2, 3};
    s.meshes.push_back(floor);
    if (occluder) {  // a small square at height 2 between the origin and the light
        Mesh block;
        block.positions = {{-0.2f, 2, -0.2f}, {0.2f, 2, -0.2f}, {0.2f, 2, 0.2f}, {-0.2f, 2, 0.2f}};
        block.indices = {0, 1, 2, 0, 2, 3};
        s.meshes.push_back(block);
    }
    s.punctualLights.push_back(light);
    s.camera = Camera{{0, 1, 0.001f}, {0, 0, 0}, {0, 0, 1}, 0.5f};
    s.resolution = {6, 6};
    return s;
}

// Mean radiance over the image, rendered by the scalar or the batched
// integrator (asserted bit-identical).
double meanRadiance(const SceneDescription& desc, int maxDepth = 1) {
    const RenderScene scene(desc);
    RenderSettings settings;
    settings.samplesPerPixel = 8;
    settings.maxDepth = maxDepth;
    settings.threads = 1;
    const RenderOutput batched = render(scene, settings);
    settings.batchPaths = false;
    const RenderOutput scalar = render(scene, settings);
    EXPECT_EQ(batched.image.rgb, scalar.image.rgb);
    double sum = 0;
    for (float v : batched.image.rgb) sum += v;
    return sum / double(batched.image.rgb.size());
}

PunctualLight point(Vec3f position, float intensity) {
    PunctualLight l;
    l.type = PunctualLightType::Point;
    l.position = position;
    l.intensity = Vec3f(intensity);
    return l;
}

TEST(PointLight, LightsTheFloorWithIntensityOverDistanceSquared) {
    // Height 3, straight above: E = I·cos0/3² at the origin.
    const double expected = kAlbedo / M_PI * 9.0 / 9.0;
    EXPECT_NEAR(meanRadiance(floorUnder(point({0, 3, 0}, 9))), expected, 2e-4 * expected);
    // Off to the side: E = I·cosθ/r² with r² = 4² + 3², cosθ = 3/5.
    const double side = kAlbedo / M_PI * 50 * (3.0 / 5.0) / 25.0;
    EXPECT_NEAR(meanRadiance(floorUnder(point({4, 3, 0}, 50))), side, 2e-3 * side);
}

TEST(PointLight, IsShadowedAndLightsNothingFromBelow) {
    EXPECT_EQ(meanRadiance(floorUnder(point({0, 3, 0}, 9), /*occluder=*/true)), 0.0);
    EXPECT_EQ(meanRadiance(floorUnder(point({0, -3, 0}, 9))), 0.0);
}

// pbrt-v4's falloff written out: smoothstep of cosθ from cos(cone) up to
// cos(cone − delta).
double expectedFalloff(double cosTheta, double cone, double delta) {
    const double end = std::cos(cone * M_PI / 180), start = std::cos((cone - delta) * M_PI / 180);
    const double t = std::clamp((cosTheta - end) / (start - end), 0.0, 1.0);
    return t * t * (3 - 2 * t);
}

TEST(SpotLight, FallsOffSmoothlyBetweenItsTwoCones) {
    // The spot 4 above the origin, its axis tilted so the origin sits at
    // angle θ off it.
    const float cone = 30, delta = 10;
    for (float thetaDegrees : {5.0f, 22.0f, 25.0f, 28.0f, 35.0f}) {
        PunctualLight l;
        l.type = PunctualLightType::Spot;
        l.position = {0, 4, 0};
        const float theta = thetaDegrees * float(M_PI / 180);
        l.direction = {std::sin(theta), -std::cos(theta), 0};
        l.intensity = Vec3f(16);
        setSpotCone(l, cone, delta);
        const double expected =
            kAlbedo / M_PI * 16 / 16 * expectedFalloff(std::cos(theta), cone, delta);
        EXPECT_NEAR(meanRadiance(floorUnder(l)), expected, 1e-3 * (expected + 1e-3))
            << thetaDegrees << "°";
    }
}

TEST(DistantLight, DeliversRadianceTimesCosine) {
    PunctualLight l;
    l.type = PunctualLightType::Distant;
    // Travelling down and sideways at 60° from the floor's normal.
    l.direction = {std::sin(float(M_PI / 3)), -std::cos(float(M_PI / 3)), 0};
    l.radiance = Vec3f(2);
    EXPECT_NEAR(meanRadiance(floorUnder(l)), kAlbedo / M_PI * 2 * 0.5, 1e-5);
    l.direction = {0, -1, 0};
    EXPECT_EQ(meanRadiance(floorUnder(l, /*occluder=*/true)), 0.0);
}

// Two point lights of intensities 1 and 3 (power 4π·I): chosen a quarter and
// three quarters of the time, and together they light the floor by the sum
// of their irradiances (sampled: within the estimate's noise).
TEST(LightChoice, PointLightsInProportionToPower) {
    SceneDescription s = floorUnder(point({0, 2, 0}, 1));
    s.punctualLights.push_back(point({1, 2, 0}, 3));
    const LightSet lights(s, Vec3f(0.0f));
    ASSERT_TRUE(lights.choiceUsesSample());
    const auto first = lights.sample({0, 0, 0}, {0, 1, 0}, 0.2f, {0.5f, 0.5f});
    const auto second = lights.sample({0, 0, 0}, {0, 1, 0}, 0.3f, {0.5f, 0.5f});
    ASSERT_TRUE(first && second);
    EXPECT_TRUE(first->delta && second->delta);
    EXPECT_FLOAT_EQ(first->pdf, 0.25f);
    EXPECT_FLOAT_EQ(second->pdf, 0.75f);
    EXPECT_FLOAT_EQ(first->radiance.x, 1.0f / 4);          // I / r², r = 2
    EXPECT_NEAR(second->wi.x, 1 / std::sqrt(5.0f), 1e-6);  // towards (1, 2, 0)
    const double expected = kAlbedo / M_PI * (1.0 / 4 + 3 * (2 / std::sqrt(5.0)) / 5);
    EXPECT_NEAR(meanRadiance(s), expected, 0.05 * expected);
}

TEST(PunctualLightsJson, ReadsEachTypeAndRejectsBadValues) {
    const std::string head = R"({"camera": {"eye": [0, 1, 5], "target": [0, 1, 0], "fovY": 40},
      "materials": {"m": {"type": "diffuse"}},
      "spheres": [{"center": [0, 0, 0], "radius": 1, "material": "m"}], "lights": [)";
    const SceneDescription s =
        parseJsonScene(head + R"({"type": "point", "position": [1, 2, 3], "intensity": [1, 2, 3]},
        {"type": "spot", "position": [0, 4, 0], "direction": [0, -2, 0], "intensity": 5,
         "coneAngle": 60, "coneDeltaAngle": 60},
        {"type": "distant", "direction": [0, 0, -3], "radiance": 7}]})",
                       ".", "s.json");
    ASSERT_EQ(s.punctualLights.size(), 3u);
    EXPECT_EQ(s.punctualLights[0].type, PunctualLightType::Point);
    EXPECT_EQ(s.punctualLights[0].intensity.z, 3.0f);
    EXPECT_EQ(s.punctualLights[1].direction.y, -1.0f);
    EXPECT_NEAR(s.punctualLights[1].cosFalloffEnd, 0.5f, 1e-6);
    EXPECT_EQ(s.punctualLights[1].cosFalloffStart, 1.0f);
    EXPECT_EQ(s.punctualLights[2].direction.z, -1.0f);
    EXPECT_EQ(s.punctualLights[2].radiance.y, 7.0f);
    // Written and read back: the same lights.
    const SceneDescription back = parseJsonScene(sceneToJson(s), ".", "back.json");
    ASSERT_EQ(back.punctualLights.size(), 3u);
    EXPECT_EQ(back.punctualLights[1].cosFalloffEnd, s.punctualLights[1].cosFalloffEnd);
    EXPECT_EQ(back.punctualLights[1].coneDeltaAngle, 60.0f);
    EXPECT_EQ(back.punctualLights[2].radiance.y, 7.0f);
    const auto error = [&](const std::string& light) {
        return test::inputErrorOf([&] { parseJsonScene(head + light + "]}", ".", "s.json"); });
    };
    EXPECT_EQ(error(R"({"type": "point", "position": [0, 0, 0], "intensity": -1})"),
              "s.json: lights[0].intensity: colour components must not be negative");
    EXPECT_EQ(error(R"({"type": "point", "position": [0, 0, 0], "intensity": 1, "to": 1})"),
              "s.json: lights[0]: unknown key 'to' (expected one of: name, type, position, "
              "intensity)");
    EXPECT_EQ(error(R"({"type": "spot", "position": [0, 0, 0], "direction": [0, 1, 0],
                        "intensity": 1, "coneAngle": 190})"),
              "s.json: lights[0].coneAngle: must be in (0, 180] degrees");
}

pbrt::ImportResult loadPbrt(const std::string& world) {
    return pbrt::importPbrtText("WorldBegin\n" + world +
                                    "\nShape \"trianglemesh\" \"point3 P\" [0 0 0  1 0 0  0 1 0] "
                                    "\"integer indices\" [0 1 2]\n",
                                "t.pbrt", ".", {});
}

TEST(PunctualLightsPbrt, ParametersAsPbrtV4ReadsThem) {
    const auto r = loadPbrt(
        "Translate 1 2 3\n"
        "LightSource \"point\" \"rgb I\" [1 2 3] \"float scale\" 2 \"point3 from\" [0 1 0]\n"
        "LightSource \"point\" \"float power\" 100\n"
        "LightSource \"spot\" \"point3 from\" [0 0 0] \"point3 to\" [0 0 -5] "
        "\"float coneangle\" 60 \"float conedeltaangle\" 60 \"float power\" 10\n"
        "LightSource \"distant\" \"point3 from\" [0 4 0] \"point3 to\" [0 0 0] "
        "\"rgb L\" [1 1 2] \"float illuminance\" 3\n");
    const auto& lights = r.scene.punctualLights;
    ASSERT_EQ(lights.size(), 4u);
    EXPECT_EQ(lights[0].position.y, 3.0f);  // from (0,1,0) translated by (1,2,3)
    EXPECT_EQ(lights[0].intensity.z, 6.0f);
    EXPECT_NEAR(lights[1].intensity.x, 100 / (4 * M_PI), 1e-5);  // Φ / 4π
    // Cone 60°, falloff from the axis: Φ / (2π·(0 + (1 − 0.5)/2)) = Φ / (π/2).
    EXPECT_NEAR(lights[2].intensity.x, 10 / (M_PI / 2), 1e-4);
    EXPECT_EQ(lights[2].direction.z, -1.0f);
    EXPECT_EQ(lights[3].direction.y, -1.0f);  // travelling from → to
    EXPECT_EQ(lights[3].radiance.z, 6.0f);
}

// pbrt-v4's area light power: Φ / (sides · π · A) per shape, where each
// triangle of a mesh is a shape of its own and a sphere's area is its own.
TEST(AreaLightPower, PerTriangleAndPerSphereAsPbrtV4) {
    const auto r = pbrt::importPbrtText(
        "WorldBegin\nAttributeBegin\nAreaLightSource \"diffuse\" \"float power\" 10\n"
        "Shape \"trianglemesh\" \"point3 P\" [0 0 0  2 0 0  2 1 0  0 1 0] "
        "\"integer indices\" [0 1 2 0 2 3]\nAttributeEnd\n"
        "AttributeBegin\nAreaLightSource \"diffuse\" \"float power\" 10 \"bool twosided\" true "
        "\"rgb L\" [1 2 3]\nScale 3 3 3\nShape \"sphere\" \"float radius\" 2\nAttributeEnd\n",
        "t.pbrt", ".");
    ASSERT_EQ(r.scene.meshes.size(), 1u);
    EXPECT_NEAR(r.scene.meshes[0].emission.x, 10 / M_PI, 1e-5);  // each triangle has area 1
    // The sphere's own area 4π·2², whatever its transform; two-sided.
    ASSERT_EQ(r.scene.spheres.size(), 1u);
    EXPECT_NEAR(r.scene.spheres[0].emission.z, 3 * 10 / (2 * M_PI * 16 * M_PI), 1e-6);
    EXPECT_TRUE(r.scene.spheres[0].twoSided);
    const std::string error = test::inputErrorOf([] {
        pbrt::importPbrtText(
            "WorldBegin\nAreaLightSource \"diffuse\" \"float power\" 10\n"
            "Shape \"trianglemesh\" \"point3 P\" [0 0 0  2 0 0  2 1 0  0 5 0] "
            "\"integer indices\" [0 1 2 0 2 3]\n",
            "t.pbrt", ".");
    });
    EXPECT_EQ(error,
              "t.pbrt:3:1: area light power on a shape whose parts differ in area is not "
              "supported (--lenient substitutes the radiance as given)");
}

}  // namespace
}  // namespace pathlab
