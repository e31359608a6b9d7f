// Blackbody emission: Planck's law peaks where Wien's displacement law says,
// the fitted CIE functions give the published chromaticities of blackbodies
// (CIE illuminant A, points of the Planckian locus), the RGB has luminance 1
// as pbrt-v4 normalises it, and the pbrt-v4 reader takes "blackbody" values.
#include <gtest/gtest.h>

#include "core/math.h"
#include "scene/blackbody.h"
#include "scene/pbrt/importer.h"
#include "scene_test_util.h"

namespace pathlab {
namespace {

TEST(Blackbody, PlanckPeaksAtWiensWavelength) {
    for (double kelvin : {3000.0, 5000.0, 6500.0}) {
        const double wien = 2.897771955e6 / kelvin;  // nm
        int best = 0;
        for (int l = 300; l <= 1200; ++l)
            if (planck(l, kelvin) > planck(best, kelvin) || best == 0) best = l;
        EXPECT_NEAR(best, wien, 0.5) << kelvin;
    }
}

// CIE 1931 chromaticity (x, y) of a blackbody.
std::pair<double, double> chromaticity(double kelvin) {
    const Xyz c = blackbodyXyz(kelvin);
    const double sum = c.x + c.y + c.z;
    return {c.x / sum, c.y / sum};
}

TEST(Blackbody, ChromaticitiesOfThePlanckianLocus) {
    // CIE standard illuminant A: a Planckian radiator at 2856 K, (0.44757, 0.40745).
    const auto [ax, ay] = chromaticity(2856);
    EXPECT_NEAR(ax, 0.44757, 2e-3);
    EXPECT_NEAR(ay, 0.40745, 2e-3);
    // Planckian locus at 5000 K, (0.3451, 0.3516), and 6500 K, (0.3135, 0.3237)
    // (Wyszecki & Stiles, Color Science, table 1(3.3.4)).
    const auto [bx, by] = chromaticity(5000);
    EXPECT_NEAR(bx, 0.3451, 2e-3);
    EXPECT_NEAR(by, 0.3516, 2e-3);
    const auto [cx, cy] = chromaticity(6500);
    EXPECT_NEAR(cx, 0.3135, 2e-3);
    EXPECT_NEAR(cy, 0.3237, 2e-3);
}

TEST(Blackbody, RgbHasUnitLuminanceAndWarmsAsItCools) {
    for (double kelvin : {3000.0, 5500.0, 8000.0}) {
        const Vec3f rgb = blackbodyRgb(kelvin);
        // sRGB's luminance row (IEC 61966-2-1).
        EXPECT_NEAR(0.2126 * rgb.x + 0.7152 * rgb.y + 0.0722 * rgb.z, 1.0, 2e-3) << kelvin;
    }
    const Vec3f warm = blackbodyRgb(2700), cool = blackbodyRgb(9000);
    EXPECT_GT(warm.x, warm.z * 2);
    EXPECT_GT(cool.z, cool.x);
    // Near D65's white, near white.
    const Vec3f d65 = blackbodyRgb(6504);
    EXPECT_NEAR(d65.x / d65.z, 1.0, 0.1);
}

TEST(Blackbody, PbrtLightsTakeBlackbodyValues) {
    const auto r = pbrt::importPbrtText(
        "WorldBegin\nLightSource \"point\" \"blackbody I\" [3000] \"float scale\" 2\n"
        "AttributeBegin\nAreaLightSource \"diffuse\" \"blackbody L\" [5500]\n"
        "Shape \"trianglemesh\" \"point3 P\" [0 0 0  1 0 0  0 1 0] \"integer indices\" [0 1 2]\n"
        "AttributeEnd\n",
        "t.pbrt", ".");
    ASSERT_EQ(r.scene.punctualLights.size(), 1u);
    const Vec3f expected = blackbodyRgb(3000) * 2.0f;
    EXPECT_EQ(r.scene.punctualLights[0].intensity.x, expected.x);
    EXPECT_EQ(r.scene.punctualLights[0].intensity.z, expected.z);
    ASSERT_EQ(r.scene.meshes.size(), 1u);
    EXPECT_EQ(r.scene.meshes[0].emission.y, blackbodyRgb(5500).y);
    const std::string error = test::inputErrorOf([] {
        pbrt::importPbrtText("WorldBegin\nLightSource \"point\" \"blackbody I\" [-10]\n", "t.pbrt",
                             ".");
    });
    EXPECT_EQ(error,
              "t.pbrt:2:21: parameter 'I': blackbody takes one positive temperature in kelvin");
}

}  // namespace
}  // namespace pathlab
