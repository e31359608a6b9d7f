// Samplers inside the renderer: none is biased on the Cornell box, and the
// screen-space samplers spread a 1-spp render's error as blue noise.
#include <gtest/gtest.h>

#include "metrics/error_spectrum.h"
#include "render/renderer.h"
#include "sampling/registry.h"
#include "sampling/spectrum.h"
#include "scene/builtin_scenes.h"

namespace pathlab {
namespace {

// At 1024 spp every sampler's Cornell box matches independent's: the mean of
// the whole image agrees within 4 standard errors and per-pixel differences
// are no larger than their noise (mean z² near or below 1; low-discrepancy
// samplers overstate their own variance, so only an upper bound is checked).
TEST(SamplerRender, NoSamplerIsBiasedOnTheCornellBox) {
    const RenderScene scene(cornellBoxScene());
    RenderSettings s;
    s.resolution = {20, 20};
    s.samplesPerPixel = 1024;
    s.seed = 5;
    const RenderOutput reference = render(scene, s);
    for (const SamplerInfo& info : samplerInfos()) {
        if (info.name == "independent") continue;
        s.sampler = info.name;
        s.seed = 6;
        const RenderOutput out = render(scene, s);
        double diff = 0, var = 0, sumZ2 = 0;
        const size_t n = out.image.rgb.size();
        for (size_t i = 0; i < n; ++i) {
            const double d = double(out.image.rgb[i]) - reference.image.rgb[i];
            const double v = double(out.varianceOfMean.rgb[i]) + reference.varianceOfMean.rgb[i];
            diff += d;
            var += v;
            sumZ2 += d * d / std::max(v, 1e-12);
        }
        EXPECT_LT(std::abs(diff), 4 * std::sqrt(var)) << info.name;
        EXPECT_LT(sumZ2 / double(n), 1.3) << info.name;
    }
}

// A diffuse plane lit from the side, seen head-on: at 1 spp and depth 1 the
// error is the light-sampling noise of each pixel.
SceneDescription litPlane() {
    SceneDescription s;
    s.materials.push_back(Material{"plane", MaterialType::Diffuse, Vec3f(0.5f)});
    Mesh plane;
    plane.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    plane.indices = {0, 1, 2, 0, 2, 3};
    Mesh light;
    light.positions = {
        {1.5f, -0.5f, 1.5f}, {1.5f, 0.5f, 1.5f}, {2.5f, 0.5f, 1.5f}, {2.5f, -0.5f, 1.5f}};
    light.indices = {0, 1, 2, 0, 2, 3};
    light.emission = Vec3f(5.0f);
    s.meshes = {plane, light};
    s.camera = Camera{{0, 0, 2.5f}, {0, 0, 0}, {0, 1, 0}, 40};
    s.resolution = {64, 64};
    return s;
}

// Mean spectral power at low frequencies (rings 1..N/8) over that at high
// frequencies (N/4..N/2) of the luminance error image.
double lowToHighPowerRatio(const Image& test, const Image& reference) {
    std::vector<double> error(test.pixelCount());
    for (size_t i = 0; i < error.size(); ++i)
        error[i] = luminance(test.at(int(i) % test.width, int(i) / test.width)) -
                   luminance(reference.at(int(i) % test.width, int(i) / test.width));
    const std::vector<double> p = radialPowerSpectrum(error, test.width, test.height);
    const int n = test.width;
    double low = 0, high = 0;
    int nl = 0, nh = 0;
    for (int r = 1; r <= n / 8; ++r) low += p[size_t(r)], ++nl;
    for (int r = n / 4; r < int(p.size()) && r <= n / 2; ++r) high += p[size_t(r)], ++nh;
    return (low / nl) / (high / nh);
}

TEST(SamplerRender, ScreenSpaceSamplersGiveBlueNoiseErrorAtOneSpp) {
    const RenderScene scene(litPlane());
    RenderSettings s;
    s.maxDepth = 1;
    s.samplesPerPixel = 1024;
    s.seed = 77;
    const Image reference = render(scene, s).image;
    s.samplesPerPixel = 1;
    for (const char* name : {"independent", "zsobol", "blue-noise", "sobol-bluenoise"}) {
        s.sampler = name;
        double ratio = 0;
        for (uint64_t seed : {1, 2, 3}) {  // average out the periodogram's own noise
            s.seed = seed;
            ratio += lowToHighPowerRatio(render(scene, s).image, reference) / 3;
        }
        if (std::string(name) == "independent") {
            EXPECT_GT(ratio, 0.6) << name;  // white: flat spectrum
            EXPECT_LT(ratio, 1.6) << name;
        } else {
            EXPECT_LT(ratio, 0.5) << name;  // blue: little low-frequency power
        }
        std::printf("%s: low/high error power %.3f\n", name, ratio);
    }
}

// sobol-bluenoise's ranking keeps its error blue past 1 spp: on the lit
// plane its low-frequency error fraction at 1 and 4 spp is at most half
// sobol-owen's (white), at 16 spp at most 3/4 of it (0.6 measured; the
// unranked prefixes were white there), with the same MSE within 5% — the keys only arrange
// the same per-pixel nets over the screen. (zsobol is bluer still at 4 and
// 16 spp: docs/samplers.md.)
TEST(SamplerRender, SobolBlueNoiseErrorStaysBlueAtOneFourAndSixteenSpp) {
    const RenderScene scene(litPlane());
    RenderSettings s;
    s.maxDepth = 1;
    s.samplesPerPixel = 1024;
    s.sampler = "sobol-owen";
    s.seed = 77;
    const Image reference = render(scene, s).image;
    for (int spp : {1, 4, 16}) {
        s.samplesPerPixel = spp;
        double fraction[2] = {0, 0}, mse[2] = {0, 0};
        for (int which : {0, 1}) {
            s.sampler = which ? "sobol-bluenoise" : "sobol-owen";
            for (uint64_t seed : {1, 2, 3}) {
                s.seed = seed;
                const Image image = render(scene, s).image;
                fraction[which] += lowFrequencyErrorFraction(reference, image) / 3;
                for (size_t i = 0; i < image.rgb.size(); ++i)
                    mse[which] += (double(image.rgb[i]) - reference.rgb[i]) *
                                  (double(image.rgb[i]) - reference.rgb[i]);
            }
        }
        std::printf("%d spp: low-frequency fraction %.4f (sobol-owen %.4f), MSE ratio %.3f\n", spp,
                    fraction[1], fraction[0], mse[1] / mse[0]);
        EXPECT_LT(fraction[1], (spp < 16 ? 0.5 : 0.75) * fraction[0]) << spp << " spp";
        EXPECT_LT(mse[1], 1.05 * mse[0]) << spp << " spp";
    }
}

}  // namespace
}  // namespace pathlab
