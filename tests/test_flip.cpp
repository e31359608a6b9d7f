// FLIP: each building block against values worked out by hand from the
// formulas of Andersson et al. (HPG 2020, EG 2021), then the whole metric.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numeric>

#include "core/error.h"
#include "core/hash.h"
#include "core/image.h"
#include "metrics/colormap.h"
#include "metrics/error_map.h"
#include "metrics/flip.h"
#include "metrics/flip_color.h"

namespace pathlab {
namespace {

using flip::Color;

// A deterministic, platform-independent value in [0,1) (integer hash only).
float hash01(uint32_t x) {
    return float(pathlab::hash32(x) >> 8) * (1.0f / 16777216.0f);
}

// Gradients, a disk and a checker patch; `light` adds a bright HDR spot.
Image patternImage(int w, int h, float light) {
    Image img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float u = (x + 0.5f) / float(w), v = (y + 0.5f) / float(h);
            Vec3f c{0.1f + 0.8f * u, 0.2f + 0.6f * v, 0.6f - 0.4f * u * v};
            const float dx = u - 0.35f, dy = v - 0.45f;
            if (dx * dx + dy * dy < 0.04f) c = {0.8f, 0.15f, 0.1f};
            if (u > 0.6f && v > 0.55f && ((x / 3 + y / 3) % 2 == 0)) c = c * 0.1f;
            const float lx = u - 0.75f, ly = v - 0.25f;
            if (light > 0 && lx * lx + ly * ly < 0.01f) c = c * light;
            img.set(x, y, c);
        }
    return img;
}

// Adds uniform noise of the given amplitude: additive, or multiplicative
// (for HDR, where additive noise would go negative).
Image withNoise(const Image& in, float amplitude, uint32_t seed, bool multiplicative) {
    Image out = in;
    for (size_t i = 0; i < out.rgb.size(); ++i) {
        const float n = amplitude * (2.0f * hash01(uint32_t(i) * 3u + seed * 0x9e3779b9u) - 1.0f);
        out.rgb[i] =
            multiplicative ? out.rgb[i] * (1.0f + n) : std::clamp(out.rgb[i] + n, 0.0f, 1.0f);
    }
    return out;
}

Image uniformImage(int w, int h, Vec3f c) {
    Image img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) img.set(x, y, c);
    return img;
}

void expectColorNear(Color actual, Color expected, float tolerance) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

// ---- Viewing conditions ----

TEST(FlipViewing, DefaultPixelsPerDegreeIsFourKMonitorAt70cm) {
    // 0.7 m · (3840 px / 0.7 m) · π/180 = 67.0206 px per degree.
    EXPECT_NEAR(flip::defaultPixelsPerDegree(), 67.0206f, 1e-3f);
    EXPECT_NEAR(flip::pixelsPerDegree(1.0f, 0.5f, 1920.0f), 1920.0f / 0.5f * 3.14159265f / 180.0f,
                1e-3f);
}

// ---- Colour spaces ----

TEST(FlipColor, SrgbTransferFunctionKnownValues) {
    EXPECT_FLOAT_EQ(srgbToLinear(0.0f), 0.0f);
    EXPECT_FLOAT_EQ(srgbToLinear(1.0f), 1.0f);
    EXPECT_NEAR(srgbToLinear(0.5f), 0.2140411f, 1e-6f);  // ((0.5+0.055)/1.055)^2.4
    EXPECT_NEAR(srgbToLinear(0.04045f), 0.04045f / 12.92f, 1e-7f);
    for (float v : {0.001f, 0.2f, 0.7f}) EXPECT_NEAR(linearToSrgb(srgbToLinear(v)), v, 1e-6f);
}

TEST(FlipColor, LinearRgbToXyzMapsWhiteToD65AndRedToItsPrimary) {
    expectColorNear(flip::linearRgbToXyz({1, 1, 1}), {0.95043f, 1.0f, 1.08890f}, 1e-5f);
    // sRGB red primary: x = 0.64, y = 0.33 with luminance 0.2126.
    const Color red = flip::linearRgbToXyz({1, 0, 0});
    EXPECT_NEAR(red.y, 0.2126f, 1e-4f);
    EXPECT_NEAR(red.x / (red.x + red.y + red.z), 0.64f, 1e-4f);
    EXPECT_NEAR(red.y / (red.x + red.y + red.z), 0.33f, 1e-4f);
    expectColorNear(flip::xyzToLinearRgb(flip::linearRgbToXyz({0.3f, 0.6f, 0.1f})),
                    {0.3f, 0.6f, 0.1f}, 1e-6f);
}

TEST(FlipColor, YcxczIsLinearLabWithWhiteAt100) {
    expectColorNear(flip::linearRgbToYcxcz({1, 1, 1}), {100, 0, 0}, 1e-4f);
    expectColorNear(flip::linearRgbToYcxcz({0, 0, 0}), {-16, 0, 0}, 1e-6f);
    // Grey 0.18: Yy = 116·0.18 − 16 = 4.88, no opponent signal.
    expectColorNear(flip::linearRgbToYcxcz({0.18f, 0.18f, 0.18f}), {4.88f, 0, 0}, 1e-4f);
    const Color xyz{0.2f, 0.3f, 0.4f};
    expectColorNear(flip::ycxczToXyz(flip::xyzToYcxcz(xyz)), xyz, 1e-6f);
}

TEST(FlipColor, LabOfKnownColours) {
    expectColorNear(flip::linearRgbToLab({1, 1, 1}), {100, 0, 0}, 1e-3f);
    expectColorNear(flip::linearRgbToLab({0, 0, 0}), {0, 0, 0}, 1e-4f);
    // L* of linear 0.18 = 116·0.18^(1/3) − 16.
    EXPECT_NEAR(flip::linearRgbToLab({0.18f, 0.18f, 0.18f}).x, 49.4961f, 1e-3f);
    // CIELAB (D65) of the sRGB primaries.
    expectColorNear(flip::linearRgbToLab({1, 0, 0}), {53.2369f, 80.0935f, 67.2005f}, 2e-3f);
    expectColorNear(flip::linearRgbToLab({0, 1, 0}), {87.7362f, -86.1787f, 83.1826f}, 2e-3f);
    expectColorNear(flip::linearRgbToLab({0, 0, 1}), {32.2982f, 79.1936f, -107.8586f}, 2e-3f);
}

TEST(FlipColor, HuntScalesChromaByLightness) {
    expectColorNear(flip::huntAdjust({50, 20, -10}), {50, 10, -5}, 1e-6f);
    expectColorNear(flip::huntAdjust({0, 20, -10}), {0, 0, 0}, 1e-6f);
}

TEST(FlipColor, HyabIsCityBlockInLightnessPlusEuclideanInChroma) {
    EXPECT_FLOAT_EQ(flip::hyab({50, 10, 0}, {40, 13, 4}), 10.0f + 5.0f);
    EXPECT_FLOAT_EQ(flip::hyab({40, 13, 4}, {50, 10, 0}), 15.0f);
    EXPECT_FLOAT_EQ(flip::hyab({30, 1, 2}, {30, 1, 2}), 0.0f);
}

TEST(FlipColor, MaxDistanceIsHuntedGreenToBlue) {
    // Hunt-adjusted green (87.7362, −75.6094, 72.9794) and blue
    // (32.2982, 25.5777, −34.8364): HyAB = 55.4380 + 147.8637 = 203.3017;
    // c_max = 203.3017^0.7.
    EXPECT_NEAR(flip::maxColorDistance(), 41.27610f, 2e-3f);
}

TEST(FlipColor, RemappingHasItsKneeAtPcTimesCmax) {
    const float cmax = flip::maxColorDistance();
    EXPECT_FLOAT_EQ(flip::remapColorDifference(0.0f, cmax), 0.0f);
    EXPECT_NEAR(flip::remapColorDifference(0.4f * cmax, cmax), 0.95f, 1e-6f);
    EXPECT_NEAR(flip::remapColorDifference(cmax, cmax), 1.0f, 1e-6f);
    EXPECT_NEAR(flip::remapColorDifference(0.2f * cmax, cmax), 0.475f, 1e-6f);
    EXPECT_NEAR(flip::remapColorDifference(0.7f * cmax, cmax), 0.975f, 1e-6f);
}

// ---- Filters ----

TEST(FlipFilters, CsfWeightsSumToOneAndFollowTheGaussians) {
    const float ppd = flip::defaultPixelsPerDegree();
    const flip::CsfFilters f = flip::makeCsfFilters(ppd);
    // 3·sqrt(b_max / 2π²)·ppd with b_max = 0.04 → ⌈9.05⌉ = 10.
    EXPECT_EQ(f.radius, 10);
    ASSERT_EQ(f.achromatic.size(), 21u);
    const auto sum = [](const std::vector<float>& v) {
        return std::accumulate(v.begin(), v.end(), 0.0);
    };
    EXPECT_NEAR(sum(f.achromatic), 1.0, 1e-6);
    EXPECT_NEAR(sum(f.redGreen), 1.0, 1e-6);
    // The 2-D blue–yellow kernel Σ_xy g1(x)g1(y) + g2(x)g2(y) sums to 1.
    const double s1 = sum(f.blueYellow1), s2 = sum(f.blueYellow2);
    EXPECT_NEAR(s1 * s1 + s2 * s2, 1.0, 1e-6);
    // Neighbouring taps of exp(−π²x²/b), x in degrees: ratio exp(−π²/(b·ppd²)).
    const double pi2 = 9.8696044;
    EXPECT_NEAR(f.achromatic[11] / f.achromatic[10], std::exp(-pi2 / (0.0047 * ppd * ppd)), 1e-5);
    EXPECT_NEAR(f.redGreen[12] / f.redGreen[10], std::exp(-4 * pi2 / (0.0053 * ppd * ppd)), 1e-5);
    EXPECT_NEAR(f.blueYellow2[11] / f.blueYellow2[10], std::exp(-pi2 / (0.025 * ppd * ppd)), 1e-5);
    // Relative weight of the two blue–yellow lobes: sqrt(a·sqrt(π/b)).
    EXPECT_NEAR(
        f.blueYellow1[10] / f.blueYellow2[10],
        std::sqrt(34.1 * std::sqrt(M_PI / 0.04)) / std::sqrt(13.5 * std::sqrt(M_PI / 0.025)), 1e-5);
    for (int i = 0; i < 21; ++i) EXPECT_FLOAT_EQ(f.achromatic[i], f.achromatic[20 - i]);
}

TEST(FlipFilters, FeatureDerivativeFiltersAreNormalisedPerSign) {
    const flip::FeatureFilters f = flip::makeFeatureFilters(flip::defaultPixelsPerDegree());
    // σ = 0.5·0.082·67.02 = 2.748 px, radius ⌈3σ⌉ = 9.
    EXPECT_EQ(f.radius, 9);
    double g = 0, d1Pos = 0, d1Neg = 0, d2Pos = 0, d2Neg = 0;
    for (int i = 0; i < 19; ++i) {
        g += f.gaussian[i];
        (f.firstDerivative[i] > 0 ? d1Pos : d1Neg) += f.firstDerivative[i];
        (f.secondDerivative[i] > 0 ? d2Pos : d2Neg) += f.secondDerivative[i];
        EXPECT_FLOAT_EQ(f.firstDerivative[i], -f.firstDerivative[18 - i]);
        EXPECT_FLOAT_EQ(f.secondDerivative[i], f.secondDerivative[18 - i]);
    }
    EXPECT_NEAR(g, 1.0, 1e-6);
    EXPECT_NEAR(d1Pos, 1.0, 1e-6);
    EXPECT_NEAR(d1Neg, -1.0, 1e-6);
    EXPECT_NEAR(d2Pos, 1.0, 1e-6);
    EXPECT_NEAR(d2Neg, -1.0, 1e-6);
    // −x·G(x): positive left of the centre; (x²/σ² − 1)·G(x): negative centre.
    EXPECT_GT(f.firstDerivative[8], 0.0f);
    EXPECT_EQ(f.firstDerivative[9], 0.0f);
    EXPECT_LT(f.secondDerivative[9], 0.0f);
    EXPECT_GT(f.secondDerivative[0], 0.0f);  // |x| = 9 > σ
    const double sigma = 0.5 * 0.082 * flip::defaultPixelsPerDegree();
    EXPECT_NEAR(f.gaussian[10] / f.gaussian[9], std::exp(-1.0 / (2 * sigma * sigma)), 1e-6);
}

TEST(FlipFeatures, StepEdgeGivesUnitEdgeResponseAtTheStep) {
    // Dark left half, white right half: at the two pixels beside the step the
    // x-derivative filter sees all of its negative lobe, so |∇| = 1 exactly
    // (the y-Gaussian of a constant column is 1); far from it, 0.
    const int w = 64, h = 16, step = 32;
    std::vector<float> y(size_t(w) * h);
    for (int r = 0; r < h; ++r)
        for (int x = 0; x < w; ++x) y[size_t(r) * w + x] = x >= step ? 1.0f : 0.0f;
    const flip::FeatureMaps m = flip::detectFeatures(y, w, h, flip::defaultPixelsPerDegree());
    for (int r : {0, 7, 15}) {
        const float* edge = &m.edge[size_t(r) * w];
        EXPECT_NEAR(edge[step], 1.0f, 1e-5f);
        EXPECT_NEAR(edge[step - 1], 1.0f, 1e-5f);
        EXPECT_LT(edge[step + 2], edge[step + 1]);
        EXPECT_LT(edge[step + 1], edge[step]);
        EXPECT_NEAR(edge[step - 12], 0.0f, 1e-6f);  // beyond the radius (9)
        EXPECT_NEAR(edge[step + 12], 0.0f, 1e-6f);
        EXPECT_NEAR(m.point[size_t(r) * w + step + 12], 0.0f, 1e-6f);
    }
}

TEST(FlipFeatures, IsolatedPointGivesPointResponseAndNoEdgeAtItsCentre) {
    // A single white pixel: at its centre ∂x = ∂y = 0 (antisymmetric filter),
    // and ∂²x = ∂²y = d2[0]·g[0], so |point| = √2·|d2[0]|·g[0].
    const int w = 31, h = 31, c = 15;
    std::vector<float> y(size_t(w) * h, 0.0f);
    y[size_t(c) * w + c] = 1.0f;
    const float ppd = flip::defaultPixelsPerDegree();
    const flip::FeatureMaps m = flip::detectFeatures(y, w, h, ppd);
    const flip::FeatureFilters f = flip::makeFeatureFilters(ppd);
    const float centreD2 = f.secondDerivative[f.radius], centreG = f.gaussian[f.radius];
    EXPECT_NEAR(m.edge[size_t(c) * w + c], 0.0f, 1e-7f);
    EXPECT_NEAR(m.point[size_t(c) * w + c], std::sqrt(2.0f) * std::fabs(centreD2) * centreG, 1e-7f);
    EXPECT_GT(m.edge[size_t(c) * w + c + 2], 0.0f);  // edges ring around the point
    EXPECT_NEAR(m.point[0], 0.0f, 1e-7f);
}

// ---- Tone mapping and exposures (EG 2021) ----

TEST(FlipHdr, AcesCurveValues) {
    // (0.9036x² + 0.018x) / (0.8748x² + 0.354x + 0.14) with the 0.6 pre-scale folded in.
    EXPECT_FLOAT_EQ(flip::acesToneMap(0.0f), 0.0f);
    EXPECT_NEAR(flip::acesToneMap(1.0f), (0.9036 + 0.018) / (0.8748 + 0.354 + 0.14), 1e-6);
    EXPECT_NEAR(flip::acesToneMap(1000.0f), 0.9036 / 0.8748, 1e-3);
}

TEST(FlipHdr, AutomaticExposureRangeFromMaxAndMedianLuminance) {
    // The tone curve reaches 0.85 at x_0.85 = 2.11883 (root of
    // 0.16002x² − 0.2829x − 0.119 = 0). Luminances 1, 2, 4, 8 (grey pixels):
    // start = log2(x/8), stop = log2(x/median) with median = luminances[2] = 4.
    Image img(4, 1);
    const float values[4] = {2, 8, 1, 4};
    for (int x = 0; x < 4; ++x) img.set(x, 0, Vec3f(values[x]));
    const flip::ExposureRange r = flip::automaticExposureRange(img);
    const double knee = (0.2829 + std::sqrt(0.2829 * 0.2829 + 4 * 0.16002 * 0.119)) / (2 * 0.16002);
    EXPECT_NEAR(r.start, std::log2(knee / 8), 1e-4);
    EXPECT_NEAR(r.stop, std::log2(knee / 4), 1e-4);
    EXPECT_EQ(r.count, 2);  // max(2, ⌈1⌉)
    EXPECT_NEAR(flip::acesToneMap(float(knee)), 0.85, 1e-5);
}

TEST(FlipHdr, BlackReferenceGetsAFiniteRange) {
    const flip::ExposureRange r = flip::automaticExposureRange(uniformImage(4, 4, Vec3f(0.0f)));
    EXPECT_TRUE(std::isfinite(r.start) && std::isfinite(r.stop));
    EXPECT_GE(r.count, 2);
}

// ---- Pooling ----

TEST(FlipPooling, WeightedPercentilesWeighEachErrorByItself) {
    // Sorted 0.1, 0.2, 0.3, 0.4 (sum 1): running sums 0.1, 0.3, 0.6, 1.0.
    // q1: first > 0.25 → 0.2; median: first > 0.5 → 0.3; q3: first > 0.75 → 0.4.
    const flip::Statistics s = flip::poolErrors({0.3f, 0.1f, 0.4f, 0.2f});
    EXPECT_NEAR(s.mean, 0.25, 1e-7);
    EXPECT_FLOAT_EQ(float(s.q1), 0.2f);
    EXPECT_FLOAT_EQ(float(s.weightedMedian), 0.3f);
    EXPECT_FLOAT_EQ(float(s.q3), 0.4f);
    EXPECT_FLOAT_EQ(float(s.min), 0.1f);
    EXPECT_FLOAT_EQ(float(s.max), 0.4f);
    EXPECT_FLOAT_EQ(float(flip::weightedPercentile({0.3f, 0.1f, 0.4f, 0.2f}, 0.5)), 0.3f);
    const flip::Statistics zero = flip::poolErrors({0.0f, 0.0f});
    EXPECT_EQ(zero.weightedMedian, 0.0);
    EXPECT_EQ(zero.max, 0.0);
}

// ---- The whole metric ----

TEST(FlipMetric, IdenticalImagesGiveZeroInBothModes) {
    const Image img = patternImage(40, 30, 20.0f);
    for (flip::Mode mode : {flip::Mode::Ldr, flip::Mode::Hdr}) {
        flip::Options o;
        o.mode = mode;
        const flip::Result r = flip::evaluate(img, img, o);
        EXPECT_EQ(r.stats.mean, 0.0);
        EXPECT_EQ(r.stats.max, 0.0);
    }
}

TEST(FlipMetric, UniformImagesGiveTheRemappedColourDistance) {
    // No features in flat images, so FLIP = remap(HyAB(Hunt(L*a*b*))^0.7),
    // worked out by hand: black vs white, HyAB = 100 → 0.96738; linear greys
    // 0.2 vs 0.25 → HyAB 5.23821 → 0.18340; (0.5,0.2,0.1) vs (0.4,0.25,0.1) → 0.28920.
    struct Case {
        Vec3f a, b;
        double expected;
    } cases[] = {{Vec3f(0.0f), Vec3f(1.0f), 0.96738},
                 {Vec3f(0.2f), Vec3f(0.25f), 0.18340},
                 {{0.5f, 0.2f, 0.1f}, {0.4f, 0.25f, 0.1f}, 0.28920}};
    for (const Case& c : cases) {
        const flip::Result r =
            flip::evaluate(uniformImage(24, 24, c.a), uniformImage(24, 24, c.b), flip::Options{});
        EXPECT_NEAR(r.stats.mean, c.expected, 1e-3);
        EXPECT_NEAR(r.stats.max - r.stats.min, 0.0, 1e-3);
    }
}

TEST(FlipMetric, MoreNoiseGivesLargerMeanLdrAndHdr) {
    const Image ldr = patternImage(64, 48, 0.0f), hdr = patternImage(64, 48, 30.0f);
    double previousLdr = 0, previousHdr = 0;
    for (float amplitude : {0.02f, 0.05f, 0.1f, 0.2f, 0.4f}) {
        flip::Options o;
        const double l = flip::evaluate(ldr, withNoise(ldr, amplitude, 1, false), o).stats.mean;
        o.mode = flip::Mode::Hdr;
        const double h = flip::evaluate(hdr, withNoise(hdr, amplitude, 2, true), o).stats.mean;
        EXPECT_GT(l, previousLdr) << "amplitude " << amplitude;
        EXPECT_GT(h, previousHdr) << "amplitude " << amplitude;
        previousLdr = l, previousHdr = h;
    }
}

TEST(FlipMetric, LdrModeClampsAndHdrModeSeesHighlights) {
    // Differences above 1 are invisible to LDR-FLIP (inputs clamped) but not
    // to HDR-FLIP (lower exposures bring them into range).
    Image a = uniformImage(16, 16, Vec3f(0.5f)), b = a;
    for (int x = 4; x < 12; ++x)
        for (int y = 4; y < 12; ++y) a.set(x, y, Vec3f(4.0f)), b.set(x, y, Vec3f(8.0f));
    flip::Options o;
    EXPECT_EQ(flip::evaluate(a, b, o).stats.max, 0.0);
    o.mode = flip::Mode::Hdr;
    EXPECT_GT(flip::evaluate(a, b, o).stats.max, 0.05);
}

TEST(FlipMetric, RejectsMismatchedSizesAndBadExposures) {
    EXPECT_THROW(flip::evaluate(Image(4, 4), Image(4, 5), flip::Options{}), InputError);
    flip::Options o;
    o.mode = flip::Mode::Hdr;
    o.startExposure = 2.0f, o.stopExposure = 1.0f;
    EXPECT_THROW(flip::evaluate(Image(4, 4), Image(4, 4), o), InputError);
}

TEST(FlipMetric, MatchesNvidiaReferenceImplementation) {
    // Mean FLIP of these generated pairs computed with NVIDIA's reference
    // (github.com/NVlabs/flip v1.6, FLIP.h FLIP::evaluate, default parameters,
    // built with g++ -O3 on x86-64, images passed as float arrays, mean in
    // double). Our error maps matched that build bit for bit.
    const Image ldr = patternImage(64, 48, 0.0f), hdr = patternImage(64, 48, 30.0f);
    flip::Options o;
    EXPECT_NEAR(flip::evaluate(ldr, withNoise(ldr, 0.1f, 1, false), o).stats.mean, 0.111275466,
                1e-6);
    o.mode = flip::Mode::Hdr;
    const flip::Result h = flip::evaluate(hdr, withNoise(hdr, 0.3f, 2, true), o);
    EXPECT_NEAR(h.stats.mean, 0.111393817, 1e-6);
    EXPECT_NEAR(h.exposures.start, -2.7616849, 1e-5);
    EXPECT_NEAR(h.exposures.stop, 2.2864814, 1e-5);
    EXPECT_EQ(h.exposures.count, 6);
}

TEST(FlipMetric, APreparedReferenceGivesEachTestItsOwnResult) {
    // A study prepares its reference once and measures hundreds of cells with
    // it: each result must equal that of a reference prepared for that test
    // alone, whatever was measured before.
    const Image hdr = patternImage(40, 32, 30.0f);
    const Image tests[] = {withNoise(hdr, 0.3f, 5, true), withNoise(hdr, 0.05f, 6, true),
                           withNoise(hdr, 0.3f, 5, true)};
    for (flip::Mode mode : {flip::Mode::Ldr, flip::Mode::Hdr}) {
        flip::Options o;
        o.mode = mode;
        const flip::PreparedReference shared(hdr, o);
        std::vector<double> means;
        for (const Image& test : tests) {
            const flip::Result a = shared.evaluate(test);
            const flip::Result b = flip::PreparedReference(hdr, o).evaluate(test);
            ASSERT_EQ(a.errorMap, b.errorMap);
            EXPECT_EQ(a.exposures.count, b.exposures.count);
            means.push_back(a.stats.mean);
        }
        EXPECT_EQ(means[0], means[2]);
        EXPECT_GT(means[0], means[1]);
    }
    EXPECT_THROW(flip::PreparedReference(hdr, flip::Options{}).evaluate(Image(40, 31)), InputError);
}

// ---- Error map ----

TEST(FlipErrorMap, MagmaEndpointsAndExactPngEncoding) {
    // matplotlib's magma: first and last entries.
    const auto lo = magmaSrgb(0.0f), hi = magmaSrgb(1.0f);
    EXPECT_FLOAT_EQ(lo[0], 0.001462f);
    EXPECT_FLOAT_EQ(lo[2], 0.013866f);
    EXPECT_FLOAT_EQ(hi[0], 0.987053f);
    EXPECT_FLOAT_EQ(hi[1], 0.991438f);
    // Every entry survives the PNG writer's sRGB encoding as its own 8-bit code.
    std::vector<float> ramp(256);
    for (int i = 0; i < 256; ++i) ramp[i] = float(i) / 255.0f;
    const Image img = errorMapImage(ramp, 256, 1, ImageFormat::Png);
    for (int i = 0; i < 256; ++i) {
        const auto c = magmaSrgb(ramp[i]);
        for (int k = 0; k < 3; ++k)
            EXPECT_EQ(std::lround(linearToSrgb(img.rgb[3 * i + k]) * 255.0f),
                      int(c[k] * 255.0f + 0.5f))
                << "entry " << i;
    }
    // EXR error maps keep the raw values.
    EXPECT_FLOAT_EQ(errorMapImage({0.25f}, 1, 1, ImageFormat::Exr).rgb[1], 0.25f);
}

}  // namespace
}  // namespace pathlab
