// pbrt-v4's sensor semantics (spectral/white_balance.h, Film "whitebalance",
// the camera's shutter interval): the Bradford adaptation against published
// values, the daylight illuminants against the CIE's tabulated ones, and
// renders whose white balance and exposure are exactly the matrix and the
// factor applied to the unbalanced, unexposed image.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>

#include "cli_runner.h"
#include "core/error.h"
#include "render/renderer.h"
#include "scene/pbrt/importer.h"
#include "scene/validate.h"
#include "scene_test_util.h"
#include "spectral/named_illuminants.h"
#include "spectral/white_balance.h"

namespace pathlab {
namespace {

using namespace spectral;

Vec2d xyOfXyz(double x, double y, double z) {
    return chromaticity(Vec3d{x, y, z});
}

TEST(WhiteBalance, SameWhiteIsTheIdentity) {
    const Vec2d d65 = chromaticity(linearSrgb().whiteXyz);
    const Mat3d m = bradfordWhiteBalance(d65, d65);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            EXPECT_NEAR(m[size_t(i)][size_t(j)], i == j ? 1.0 : 0.0, 1e-12) << i << "," << j;
}

TEST(WhiteBalance, TheSensorsWhiteBecomesTheColourSpacesWhite) {
    // Balanced for T, the film shows a white surface under D(T) as RGB white.
    for (double kelvin : {2700.0, 4500.0, 9000.0}) {
        const Vec3d xyz = spectrumXyz(daylightIlluminant(kelvin));
        const Vec3d rgb =
            multiply(linearSrgb().xyzToRgb, Vec3d{xyz[0] / xyz[1], 1.0, xyz[2] / xyz[1]});
        const Vec3d balanced = multiply(whiteBalanceRgbMatrix(kelvin, linearSrgb()), rgb);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(balanced[size_t(c)], 1.0, 1e-9) << kelvin;
    }
}

TEST(WhiteBalance, BradfordD50ToD65MatchesLindbloomsTable) {
    // B. Lindbloom, "Chromatic Adaptation" (brucelindbloom.com), Bradford
    // D50 → D65 with whites XYZ (0.96422, 1, 0.82521) and (0.95047, 1,
    // 1.08883), to 7 decimals.
    const Mat3d expected{{{0.9555766, -0.0230393, 0.0631636},
                          {-0.0282895, 1.0099416, 0.0210077},
                          {0.0122982, -0.0204830, 1.3299098}}};
    const Mat3d m =
        bradfordWhiteBalance(xyOfXyz(0.96422, 1, 0.82521), xyOfXyz(0.95047, 1, 1.08883));
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            EXPECT_NEAR(m[size_t(i)][size_t(j)], expected[size_t(i)][size_t(j)], 6e-8)
                << i << "," << j;
    // A colour at the source white goes to the target white.
    const Vec3d white = multiply(m, Vec3d{0.96422, 1, 0.82521});
    EXPECT_NEAR(white[0], 0.95047, 1e-12);
    EXPECT_NEAR(white[1], 1.0, 1e-12);
    EXPECT_NEAR(white[2], 1.08883, 1e-12);
}

TEST(WhiteBalance, DaylightIlluminantsHaveTheTabulatedWhites) {
    // D65 and D50 are the daylight series at 6504 K and 5003 K (CIE 15:2004:
    // 6500 and 5000 K on the old radiation constant, which daylightIlluminant
    // converts from). Their S-basis reconstructions agree with the tabulated
    // spectra's chromaticities to the rounding of the CIE's M1, M2.
    for (const auto& [kelvin, name] :
         {std::pair{6500.0, "stdillum-D65"}, std::pair{5000.0, "stdillum-D50"}}) {
        const Vec2d daylight = chromaticity(spectrumXyz(daylightIlluminant(kelvin)));
        const Vec2d table = chromaticity(spectrumXyz(*namedIlluminant(name)));
        EXPECT_NEAR(daylight[0], table[0], 1e-4) << name;
        EXPECT_NEAR(daylight[1], table[1], 1e-4) << name;
    }
    // Below 4000 K the series is undefined and a blackbody of the converted
    // temperature (3000 × 1.4388/1.4380 K) stands in; its chromaticity, from
    // Planck's law and the same CIE tables in an independent script, is
    // (0.43680, 0.40403).
    const Vec2d warm = chromaticity(spectrumXyz(daylightIlluminant(3000)));
    EXPECT_NEAR(warm[0], 0.43680, 2e-5);
    EXPECT_NEAR(warm[1], 0.40403, 2e-5);
}

TEST(WhiteBalance, BadTemperaturesAreRefused) {
    EXPECT_TRUE(linearSrgbWhiteBalance(0).identity);
    EXPECT_FALSE(linearSrgbWhiteBalance(5000).identity);
    for (double bad : {-1.0, double(NAN), double(INFINITY)}) {
        const std::string message = test::inputErrorOf([&] { linearSrgbWhiteBalance(bad); });
        EXPECT_NE(message.find("white balance"), std::string::npos) << message;
    }
}

// The pbrt-v4 Cornell box with `camera` and `film` parameters added.
SceneDescription cornellPbrt(const std::string& camera, const std::string& film) {
    std::string text = testing::slurpFile(PATHLAB_SOURCE_DIR "/scenes/cornell-box.pbrt");
    const auto insert = [&](const std::string& after, const std::string& what) {
        const size_t at = text.find(after);
        EXPECT_NE(at, std::string::npos) << after;
        text.insert(at + after.size(), " " + what);
    };
    insert("Camera \"perspective\"", camera);
    insert("Film \"rgb\"", film);
    SceneDescription scene =
        pbrt::importPbrtText(text, "cornell-box.pbrt", PATHLAB_SOURCE_DIR "/scenes").scene;
    validateScene(scene, "cornell-box.pbrt");
    return scene;
}

RenderOutput renderSmall(SceneDescription desc, bool spectralMode) {
    const RenderScene scene(std::move(desc));
    RenderSettings s;
    s.sampler = "sobol-owen";
    s.samplesPerPixel = 4;
    s.resolution = {16, 16};
    s.spectral = spectralMode;
    return render(scene, s);
}

TEST(WhiteBalance, RenderIsTheMatrixTimesTheUnbalancedRender) {
    const Mat3d m = whiteBalanceRgbMatrix(3000, linearSrgb());
    for (bool spectralMode : {false, true}) {
        const RenderOutput plain = renderSmall(cornellPbrt("", ""), spectralMode);
        const RenderOutput balanced =
            renderSmall(cornellPbrt("", "\"float whitebalance\" 3000"), spectralMode);
        double mean[3] = {}, expectedMean[3] = {};
        for (size_t p = 0; p < plain.image.rgb.size(); p += 3) {
            const float* c = &plain.image.rgb[p];
            for (int i = 0; i < 3; ++i) {
                const double e =
                    m[size_t(i)][0] * c[0] + m[size_t(i)][1] * c[1] + m[size_t(i)][2] * c[2];
                // The matrix multiplies every sample; the pixel is their mean.
                EXPECT_NEAR(balanced.image.rgb[p + size_t(i)], e, 1e-5 * (1 + std::abs(e)));
                mean[i] += balanced.image.rgb[p + size_t(i)], expectedMean[i] += e;
            }
        }
        for (int i = 0; i < 3; ++i)
            EXPECT_NEAR(mean[i], expectedMean[i], 1e-5 * expectedMean[i])
                << "channel " << i << (spectralMode ? " spectral" : " rgb");
    }
}

TEST(Exposure, ShutterIntervalOfTwoDoublesTheImageExactly) {
    for (bool spectralMode : {false, true}) {
        const RenderOutput once = renderSmall(cornellPbrt("", ""), spectralMode);
        const RenderOutput twice = renderSmall(
            cornellPbrt("\"float shutteropen\" 0.5 \"float shutterclose\" 2.5", ""), spectralMode);
        ASSERT_EQ(once.image.rgb.size(), twice.image.rgb.size());
        for (size_t i = 0; i < once.image.rgb.size(); ++i)
            ASSERT_EQ(twice.image.rgb[i], 2 * once.image.rgb[i]) << i;
    }
    // ISO multiplies with it, as pbrt-v4's imaging ratio exposure · ISO / 100.
    const SceneDescription both = cornellPbrt("\"float shutterclose\" 2", "\"float iso\" 50");
    EXPECT_EQ(both.film.scale, 1.0f);
}

TEST(PbrtSensor, OtherSensorsAreOneLineNamingTheMissingData) {
    const std::string message =
        test::inputErrorOf([] { cornellPbrt("", "\"string sensor\" \"canon_eos_100d\""); });
    EXPECT_NE(message.find("canon_eos_100d"), std::string::npos) << message;
    EXPECT_NE(message.find("measured camera curves"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    const std::string negative =
        test::inputErrorOf([] { cornellPbrt("", "\"float whitebalance\" -5"); });
    EXPECT_NE(negative.find("whitebalance"), std::string::npos) << negative;
}

}  // namespace
}  // namespace pathlab
