// The error spectrum of real renders: a flat diffuse plane under a uniform
// sky, where every pixel's exact value is known, rendered at 1 spp. Samplers
// that spread their samples over the screen (zsobol: Ahmed & Wonka 2020;
// blue-noise: Georgiev & Fajardo 2016) leave less low-frequency error than
// independent samples, whose error is white.
#include <gtest/gtest.h>

#include <cstdio>

#include "metrics/error_spectrum.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace pathlab {
namespace {

constexpr float kAlbedo = 0.5f, kSky = 1.0f;

// A Lambertian plane filling the view, seen from above, under a constant
// environment: at depth 1 its radiance is albedo·sky everywhere.
SceneDescription planeUnderUniformSky() {
    SceneDescription s;
    s.materials.push_back(Material{"plane", MaterialType::Diffuse, Vec3f(kAlbedo)});
    Mesh plane;
    plane.positions = {{-10, -10, 0}, {10, -10, 0}, {10, 10, 0}, {-10, 10, 0}};
    plane.indices = {0, 1, 2, 0, 2, 3};
    s.meshes = {plane};
    s.environment = Vec3f(kSky);
    s.camera = Camera{{0, 0, 2}, {0, 0, 0}, {0, 1, 0}, 40};
    s.resolution = {128, 128};
    return s;
}

TEST(ErrorSpectrumRender, ScreenSpaceSamplersHalveTheLowFrequencyFractionAtOneSpp) {
    const RenderScene scene(planeUnderUniformSky());
    RenderSettings s;
    s.maxDepth = 1;
    s.samplesPerPixel = 1;
    Image reference(128, 128);
    std::fill(reference.rgb.begin(), reference.rgb.end(), kAlbedo * kSky);
    const auto fraction = [&](const char* sampler) {
        s.sampler = sampler;
        double mean = 0;
        for (uint64_t seed : {1, 2}) {  // average out the periodogram's own noise
            s.seed = seed;
            mean += lowFrequencyErrorFraction(reference, render(scene, s).image) / 2;
        }
        std::printf("%s: low-frequency error fraction %.4f\n", sampler, mean);
        return mean;
    };
    const double white = fraction("independent");
    EXPECT_NEAR(white, M_PI / 64, 0.012);  // the area ratio, as for synthetic white noise
    EXPECT_LE(fraction("zsobol"), white / 2);
    EXPECT_LE(fraction("blue-noise"), white / 2);
}

}  // namespace
}  // namespace pathlab
