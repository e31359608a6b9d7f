// Hero-wavelength sampling (Wilkie et al. 2014) as spectral mode's option:
// its wavelengths and pdfs for a given u, a render that agrees with pbrt-v4's
// visible sampling within noise, and the option's bad values on the command
// line and in a study spec.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "cli_runner.h"
#include "core/error.h"
#include "render/renderer.h"
#include "scene/loader.h"
#include "scene_test_util.h"
#include "spectral/sampled_wavelengths.h"
#include "study/reference_cache.h"
#include "study/spec.h"

namespace pathlab {
namespace {

using spectral::SampledWavelengths;
using spectral::WavelengthSampling;

TEST(HeroWavelengths, ExactWavelengthsAndPdfsForAGivenU) {
    // u = 3/8: the hero at 360 + 470·3/8 = 536.25 nm, the others a quarter of
    // the 470-nm range (117.5 nm) apart, wrapping past 830 nm. Every value is
    // a multiple of 1/4, exact in float.
    const SampledWavelengths w = SampledWavelengths::sample(WavelengthSampling::Hero, 0.375f);
    const float expected[4] = {536.25f, 653.75f, 771.25f, 418.75f};
    for (int i = 0; i < spectral::kSpectrumSamples; ++i) {
        EXPECT_EQ(w.lambda(i), expected[i]) << "lane " << i;
        EXPECT_EQ(w.pdf(i), 1.0f / 470.0f) << "lane " << i;
    }
    // u = 0 puts the hero at 360 nm and a lane exactly on each quarter.
    const SampledWavelengths zero = SampledWavelengths::sample(WavelengthSampling::Hero, 0.0f);
    for (int i = 0; i < spectral::kSpectrumSamples; ++i)
        EXPECT_EQ(zero.lambda(i), 360.0f + 117.5f * float(i));
}

TEST(HeroWavelengths, ModeSelectsTheSampler) {
    for (float u : {0.0f, 0.2f, 0.61f, 0.999f}) {
        const SampledWavelengths v = SampledWavelengths::sample(WavelengthSampling::Visible, u);
        const SampledWavelengths h = SampledWavelengths::sample(WavelengthSampling::Hero, u);
        const SampledWavelengths v0 = SampledWavelengths::sampleVisible(u);
        const SampledWavelengths h0 = SampledWavelengths::sampleHero(u);
        for (int i = 0; i < spectral::kSpectrumSamples; ++i) {
            EXPECT_EQ(v.lambda(i), v0.lambda(i));
            EXPECT_EQ(v.pdf(i), v0.pdf(i));
            EXPECT_EQ(h.lambda(i), h0.lambda(i));
            EXPECT_EQ(h.pdf(i), h0.pdf(i));
        }
    }
}

TEST(HeroWavelengths, NamesParseAndBadNamesAreRefused) {
    EXPECT_EQ(spectral::parseWavelengthSampling("hero", "--wavelengths"), WavelengthSampling::Hero);
    EXPECT_EQ(spectral::parseWavelengthSampling("visible", "--wavelengths"),
              WavelengthSampling::Visible);
    EXPECT_EQ(
        test::inputErrorOf([] { spectral::parseWavelengthSampling("Hero", "--wavelengths"); }),
        "--wavelengths must be visible or hero, got 'Hero'");
}

struct Pooled {
    double mean[3] = {}, variance[3] = {};  // of the image mean
};
// The image means of `seeds` renders pooled: each channel's mean over the
// renders and the variance of that mean (pixels and seeds are independent).
Pooled pooledMeans(const RenderScene& scene, RenderSettings s, int seeds) {
    Pooled p;
    for (int seed = 0; seed < seeds; ++seed) {
        s.seed = uint64_t(seed);
        const RenderOutput out = render(scene, s);
        const double pixels = double(out.image.width) * double(out.image.height);
        for (size_t i = 0; i < out.image.rgb.size(); ++i) {
            p.mean[i % 3] += out.image.rgb[i] / (pixels * seeds);
            p.variance[i % 3] += out.varianceOfMean.rgb[i] / (pixels * pixels * seeds * seeds);
        }
    }
    return p;
}

TEST(HeroWavelengths, RenderAgreesWithVisibleSamplingWithinNoise) {
    // The Cornell box's saturated walls make the image depend on the
    // wavelengths; both densities are unbiased, so the means must agree.
    SceneDescription desc = loadScene("cornell-box");
    desc.resolution = {20, 20};
    const RenderScene scene(std::move(desc));
    RenderSettings s;
    s.sampler = "sobol-owen";
    s.samplesPerPixel = 16;
    s.spectral = true;
    const Pooled visible = pooledMeans(scene, s, 4);
    s.wavelengths = WavelengthSampling::Hero;
    const Pooled hero = pooledMeans(scene, s, 4);
    // Hero's uniform density against pbrt-v4's visible one: the pixels'
    // variance, per channel, for docs/rendering.md.
    std::printf("hero / visible pixel variance: R %.3f  G %.3f  B %.3f\n",
                hero.variance[0] / visible.variance[0], hero.variance[1] / visible.variance[1],
                hero.variance[2] / visible.variance[2]);
    for (int c = 0; c < 3; ++c) {
        const double se = std::sqrt(visible.variance[c] + hero.variance[c]);
        EXPECT_GT(visible.mean[c], 0.02) << "channel " << c;
        EXPECT_NEAR(hero.mean[c], visible.mean[c], 4 * se) << "channel " << c;
    }
}

TEST(HeroWavelengths, RenderDiffersFromVisibleAndNeedsSpectralMode) {
    SceneDescription desc = loadScene("cornell-box");
    desc.resolution = {8, 8};
    const RenderScene scene(std::move(desc));
    RenderSettings s;
    s.samplesPerPixel = 2;
    s.spectral = true;
    const RenderOutput visible = render(scene, s);
    s.wavelengths = WavelengthSampling::Hero;
    EXPECT_NE(render(scene, s).image.rgb, visible.image.rgb);
    s.spectral = false;
    EXPECT_EQ(test::inputErrorOf([&] { render(scene, s); }),
              "wavelength sampling 'hero' needs spectral mode (--spectral)");
}

TEST(HeroWavelengthsCli, BadValuesAreOneLineAndExitTwo) {
    const auto dir = testing::scratchDirectory("hero-cli");
    const std::string out = (dir / "x.exr").string();
    for (const char* args : {"--spectral --wavelengths uniform", "--wavelengths hero"}) {
        const auto r = testing::runPathlab(
            "render --scene cornell-box --spp 1 --size 4x4 " + std::string(args) + " -o " + out,
            dir);
        EXPECT_EQ(r.exitCode, 2) << args;
        EXPECT_EQ(r.errLines(), 1) << args << ": " << r.err;
        EXPECT_NE(r.err.find("wavelength"), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(out)) << args;
    }
    std::filesystem::remove_all(dir);
}

const std::string kBase =
    "scenes = [\"cornell-box\"]\nsamplers = [\"sobol\"]\nspp = [1, 4]\nspectral = true\n";

TEST(HeroWavelengthsSpec, KeyParsesRoundTripsAndIsRefusedWhenWrong) {
    const StudySpec visible = parseStudySpec(kBase, "spec.toml", "/tmp");
    EXPECT_EQ(visible.wavelengths, WavelengthSampling::Visible);
    const StudySpec hero = parseStudySpec(kBase + "wavelengths = \"hero\"\n", "spec.toml", "/tmp");
    EXPECT_EQ(hero.wavelengths, WavelengthSampling::Hero);
    EXPECT_EQ(firstSpecDifference(visible, hero), "wavelengths");
    const StudySpec again = parseStudySpec(studySpecToToml(hero), "spec.toml", "/tmp");
    EXPECT_EQ(firstSpecDifference(hero, again), "");
    EXPECT_EQ(studyRenderSettings(hero, 1).wavelengths, WavelengthSampling::Hero);
    for (const std::string& bad :
         {kBase + "wavelengths = \"uniform\"\n", kBase + "wavelengths = 1\n",
          std::string("scenes = [\"cornell-box\"]\nsamplers = [\"sobol\"]\nspp = [1]\n"
                      "wavelengths = \"hero\"\n")}) {
        const std::string message =
            test::inputErrorOf([&] { parseStudySpec(bad, "spec.toml", "/tmp"); });
        EXPECT_NE(message.find("wavelengths"), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

TEST(HeroWavelengthsSpec, InTheReferenceKeyOnlyWhenNotTheDefault) {
    const SceneDescription scene = loadScene("cornell-box");
    const StudySpec implicit = parseStudySpec(kBase, "spec.toml", "/tmp");
    const StudySpec explicitVisible =
        parseStudySpec(kBase + "wavelengths = \"visible\"\n", "spec.toml", "/tmp");
    const StudySpec hero = parseStudySpec(kBase + "wavelengths = \"hero\"\n", "spec.toml", "/tmp");
    const StudyScene& source = implicit.scenes[0];
    EXPECT_EQ(referenceCacheKey(scene, source, explicitVisible),
              referenceCacheKey(scene, source, implicit));
    EXPECT_NE(referenceCacheKey(scene, source, hero), referenceCacheKey(scene, source, implicit));
}

}  // namespace
}  // namespace pathlab
