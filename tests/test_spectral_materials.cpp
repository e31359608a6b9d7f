// Spectral mode's coated materials. A coated sphere that loses no energy is
// invisible in a white furnace in every channel; a grey coated material
// (flat spectra) renders as in RGB mode within noise, and its walks draw
// from the sampler.
#include <gtest/gtest.h>

#include <cmath>

#include "render/renderer.h"
#include "sampling/sampler.h"
#include "spectral_test_util.h"

namespace pathlab {
namespace {

using test::channelMeans;
using test::ChannelMeans;
using test::sphereInFurnace;

Material coatedDiffuse(float base, float roughness, float albedo) {
    Material m;
    m.type = MaterialType::CoatedDiffuse;
    m.albedo = Vec3f(base);
    m.coating.roughness = roughness;
    m.coating.thickness = 0.1f;
    m.coating.albedo = Vec3f(albedo);
    m.coating.maxDepth = 500;
    return m;
}

RenderSettings spectralSettings(int spp) {
    RenderSettings s;
    s.sampler = "sobol-owen";
    s.samplesPerPixel = spp;
    s.threads = 2;
    s.spectral = true;
    return s;
}

TEST(SpectralCoated, LosslessCoatedSphereIsInvisibleInAFurnace) {
    // White base, smooth clear coating, a medium that scatters without
    // absorbing: every channel must read the sky's 1 (RGB mode's
    // LayeredRender test, now through the spectral walk).
    const RenderScene scene(sphereInFurnace(coatedDiffuse(1.0f, 0.0f, 1.0f)));
    const ChannelMeans m = channelMeans(render(scene, spectralSettings(64)));
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(m.mean[c], 1.0, 4 * m.standardError[c] + 5e-3) << "channel " << c;
}

TEST(SpectralCoated, GreyCoatedMaterialsAgreeWithRgbModeWithinNoise) {
    // Grey reflectances and a grey conductor are flat spectra: both modes
    // estimate the same image.
    Material conductor = coatedDiffuse(0.5f, 0.3f, 0.4f);
    conductor.type = MaterialType::CoatedConductor;
    conductor.eta = Vec3f(0.4f), conductor.k = Vec3f(1.5f), conductor.roughness = 0.2f;
    for (const Material& m : {coatedDiffuse(0.5f, 0.3f, 0.4f), conductor}) {
        const RenderScene scene(sphereInFurnace(m));
        RenderSettings s = spectralSettings(64);
        const ChannelMeans spectral = channelMeans(render(scene, s));
        s.spectral = false;
        const ChannelMeans rgb = channelMeans(render(scene, s));
        for (int c = 0; c < 3; ++c) {
            const double se = std::hypot(rgb.standardError[c], spectral.standardError[c]);
            EXPECT_LT(rgb.mean[c], 0.95) << "the sphere must show, channel " << c;
            EXPECT_NEAR(spectral.mean[c], rgb.mean[c], 5 * se + 1e-3)
                << int(m.type) << " channel " << c;
        }
    }
}

TEST(SpectralCoated, WalksDrawFromTheSampler) {
    // The spectral walks read the layered blocks after the vertex blocks (as
    // RGB mode's do, moved up by one with them): more dimensions per path
    // than the fixed blocks and the wavelength hold.
    const RenderScene scene(sphereInFurnace(coatedDiffuse(0.5f, 0.3f, 0.4f)));
    RenderSettings s = spectralSettings(4);
    s.maxDepth = 4;
    const RenderOutput spectral = render(scene, s);
    EXPECT_GT(double(spectral.stats.dimensions) / double(spectral.stats.paths),
              double(dims::kDimsPerBounce + 3));
}

TEST(SpectralCoated, SameImageForAnyThreadCount) {
    const RenderScene scene(sphereInFurnace(coatedDiffuse(0.7f, 0.2f, 0.5f)));
    RenderSettings s = spectralSettings(4);
    s.threads = 1;
    const RenderOutput one = render(scene, s);
    s.threads = 2;
    EXPECT_EQ(one.image.rgb, render(scene, s).image.rgb);
}

}  // namespace
}  // namespace pathlab
