// Spectral mode (RenderSettings::spectral, render/colour/): the same
// integrator, materials, lights and samplers carrying four sampled
// wavelengths instead of RGB.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "render/renderer.h"
#include "scene/loader.h"
#include "scene_test_util.h"
#include "spectral_test_util.h"
#include "study/spec.h"

namespace pathlab {
namespace {

using test::channelMeans;
using test::ChannelMeans;

TEST(SpectralFurnace, GreyEnclosureUnderWhiteLightStaysWhite) {
    // White light is the colour space's illuminant (D65) and the film is
    // balanced to it, and a grey reflectance is the same at every wavelength:
    // every channel must be Le/(1 − a), as in RGB mode, with the wavelengths'
    // noise on top.
    const float a = 0.5f, Le = 1.0f;
    const RenderScene scene(furnaceCube(a, Le));
    RenderSettings s;
    s.sampler = "sobol-owen";
    s.samplesPerPixel = 64;
    s.maxDepth = 100;
    s.spectral = true;
    const ChannelMeans m = channelMeans(render(scene, s));
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(m.mean[c], Le / (1 - a), 5 * m.standardError[c] + 2e-3) << "channel " << c;
}

// The Cornell box with every colour replaced by its grey of the same mean:
// spectra of greys are flat, so spectral and RGB mode estimate one image.
SceneDescription greyCornellBox() {
    SceneDescription desc = loadScene("cornell-box");
    const auto grey = [](Vec3f c) { return Vec3f((c.x + c.y + c.z) / 3); };
    for (Material& m : desc.materials) m.albedo = grey(m.albedo);
    for (Mesh& mesh : desc.meshes) mesh.emission = grey(mesh.emission);
    desc.resolution = {32, 32};
    return desc;
}

TEST(SpectralRender, GreySceneAgreesWithRgbModeWithinNoise) {
    const RenderScene scene(greyCornellBox());
    RenderSettings s;
    s.sampler = "sobol-owen";
    s.samplesPerPixel = 64;
    const ChannelMeans rgb = channelMeans(render(scene, s));
    s.spectral = true;
    const ChannelMeans spectral = channelMeans(render(scene, s));
    for (int c = 0; c < 3; ++c) {
        const double se = std::hypot(rgb.standardError[c], spectral.standardError[c]);
        EXPECT_GT(rgb.mean[c], 0.05) << "channel " << c;
        EXPECT_NEAR(spectral.mean[c], rgb.mean[c], 5 * se + 1e-3 * rgb.mean[c]) << "channel " << c;
    }
}

TEST(SpectralRender, SaturatedColoursDifferFromRgbMode) {
    // The reason for spectral mode: a product of saturated RGB reflectances
    // is not the product of their spectra. The red and green walls' light,
    // bounced, is where the two modes part; the test only asks that spectral
    // mode is not RGB mode in disguise.
    SceneDescription desc = loadScene("cornell-box");
    desc.resolution = {32, 32};
    const RenderScene scene(std::move(desc));
    RenderSettings s;
    s.samplesPerPixel = 4;
    const RenderOutput rgb = render(scene, s);
    s.spectral = true;
    const RenderOutput spectral = render(scene, s);
    EXPECT_NE(rgb.image.rgb, spectral.image.rgb);
    for (float v : spectral.image.rgb) ASSERT_TRUE(std::isfinite(v));
}

TEST(SpectralRender, SameImageForAnyThreadCount) {
    SceneDescription desc = loadScene("cornell-box");
    desc.resolution = {40, 24};
    const RenderScene scene(std::move(desc));
    RenderSettings s;
    s.sampler = "zsobol";
    s.samplesPerPixel = 8;
    s.spectral = true;
    s.threads = 1;
    const RenderOutput one = render(scene, s);
    s.threads = 2;
    const RenderOutput two = render(scene, s);
    EXPECT_EQ(one.image.rgb, two.image.rgb);
    EXPECT_EQ(one.varianceOfMean.rgb, two.varianceOfMean.rgb);
    EXPECT_EQ(one.stats.rays, two.stats.rays);
}

TEST(SpectralRender, WavelengthsComeFromTheirOwnDimension) {
    // The wavelength dimension sits before the bounces' blocks, which move up
    // by one: a spectral path draws one dimension per sample more than the
    // RGB path it follows would (the grey furnace's paths do not depend on
    // the wavelengths, so they are the same paths).
    const RenderScene scene(furnaceCube(0.5f, 1.0f));
    RenderSettings s;
    s.samplesPerPixel = 4;
    s.maxDepth = 3;
    s.russianRoulette = false;
    s.batchPaths = false;
    const RenderOutput rgb = render(scene, s);
    s.spectral = true;
    const RenderOutput spectral = render(scene, s);
    EXPECT_EQ(spectral.stats.dimensions, rgb.stats.dimensions + spectral.stats.paths);
}

TEST(SpectralStudySpec, SpectralKeyParsesAndRoundTrips) {
    const std::string base = "scenes = [\"cornell-box\"]\nsamplers = [\"sobol\"]\nspp = [1, 4]\n";
    const StudySpec plain = parseStudySpec(base, "spec.toml", "/tmp");
    EXPECT_FALSE(plain.spectral);
    const StudySpec spectral = parseStudySpec(base + "spectral = true\n", "spec.toml", "/tmp");
    EXPECT_TRUE(spectral.spectral);
    EXPECT_EQ(firstSpecDifference(plain, spectral), "spectral");
    const StudySpec again = parseStudySpec(studySpecToToml(spectral), "spec.toml", "/tmp");
    EXPECT_EQ(firstSpecDifference(spectral, again), "");
    EXPECT_THROW(parseStudySpec(base + "spectral = 3\n", "spec.toml", "/tmp"), InputError);
}

}  // namespace
}  // namespace pathlab
