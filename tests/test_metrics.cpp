// MSE, RMSE, relMSE, PSNR, input validation and FLIP mode selection.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/error.h"
#include "core/image.h"
#include "metrics/flip.h"
#include "metrics/image_metrics.h"

namespace pathlab {
namespace {

Image gradientImage(int w, int h) {
    Image img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            img.set(
                x, y,
                {float(x) / float(w), float(y) / float(h), float((x * 7 + y * 3) % 11) / 10.0f});
    return img;
}

// Two pixels: reference (0,0,0), (1,0.5,0.25); test (0.25,0,0), (1,0.5,0.75).
// Channel differences 0.25 and 0.5, the other four 0.
struct TinyPair {
    Image reference{2, 1}, test{2, 1};
    TinyPair() {
        reference.set(0, 0, {0, 0, 0}), reference.set(1, 0, {1, 0.5f, 0.25f});
        test.set(0, 0, {0.25f, 0, 0}), test.set(1, 0, {1, 0.5f, 0.75f});
    }
};

TEST(PixelMetric, IdenticalImagesGiveZero) {
    const Image img = gradientImage(17, 9);
    EXPECT_EQ(meanSquaredError(img, img), 0.0);
    EXPECT_EQ(rootMeanSquaredError(img, img), 0.0);
    EXPECT_EQ(relativeMeanSquaredError(img, img), 0.0);
    EXPECT_EQ(peakSignalToNoiseRatio(img, img), std::numeric_limits<double>::infinity());
}

TEST(PixelMetric, MseAndRmseByHand) {
    const TinyPair p;
    // (0.25² + 0.5²) / 6 = 0.3125 / 6.
    EXPECT_DOUBLE_EQ(meanSquaredError(p.reference, p.test), 0.3125 / 6);
    EXPECT_DOUBLE_EQ(rootMeanSquaredError(p.reference, p.test), std::sqrt(0.3125 / 6));
    EXPECT_DOUBLE_EQ(meanSquaredError(p.test, p.reference), 0.3125 / 6);
}

// 3×1 image, channel errors: pixel 0 (1,0,0), pixel 1 (0,2,0), pixel 2 (0,0,3).
// Region {1}: MSE 4/3; region {0, 2}: (1 + 9)/6 = 5/3; whole image 14/9.
TEST(PixelMetric, MseByRegionByHand) {
    Image reference(3, 1), test(3, 1);
    test.set(0, 0, {1, 0, 0});
    test.set(1, 0, {0, 2, 0});
    test.set(2, 0, {0, 0, 3});
    const RegionMse r = meanSquaredErrorByRegion(reference, test, {0, 1, 0});
    ASSERT_TRUE(r.inside && r.outside);
    EXPECT_DOUBLE_EQ(*r.inside, 4.0 / 3.0);
    EXPECT_DOUBLE_EQ(*r.outside, 5.0 / 3.0);
    EXPECT_EQ(r.insidePixels, 1u);
    EXPECT_EQ(r.outsidePixels, 2u);
    // Weighted by their pixel counts the regions give the whole image's MSE.
    EXPECT_DOUBLE_EQ((*r.inside * 1 + *r.outside * 2) / 3, meanSquaredError(reference, test));
    // An empty region has no MSE; a mask of another size is refused.
    const RegionMse all = meanSquaredErrorByRegion(reference, test, {1, 1, 1});
    EXPECT_FALSE(all.outside.has_value());
    EXPECT_DOUBLE_EQ(*all.inside, 14.0 / 9.0);
    EXPECT_THROW(meanSquaredErrorByRegion(reference, test, {1, 0}), std::invalid_argument);
}

TEST(PixelMetric, RelMseByHand) {
    const TinyPair p;
    // 0.25²/(0² + 0.01) = 6.25 and 0.5²/(0.25² + 0.01) = 0.25/0.0725, over 6 channels.
    const double expected = (6.25 + 0.25 / 0.0725) / 6;
    EXPECT_NEAR(relativeMeanSquaredError(p.reference, p.test), expected, 1e-9);
    EXPECT_EQ(kRelMseEpsilon, 0.01);
    // A larger ε: 0.0625/1 + 0.25/1.0625.
    EXPECT_NEAR(relativeMeanSquaredError(p.reference, p.test, 1.0), (0.0625 + 0.25 / 1.0625) / 6,
                1e-9);
}

TEST(PixelMetric, PsnrByHand) {
    const TinyPair p;
    // 10·log10(1 / (0.3125/6)) = 10·log10(19.2) = 12.8330 dB.
    EXPECT_NEAR(peakSignalToNoiseRatio(p.reference, p.test), 12.833012, 1e-5);
    EXPECT_NEAR(psnrFromMse(0.01), 20.0, 1e-12);
    EXPECT_NEAR(psnrFromMse(1e-4), 40.0, 1e-12);
    EXPECT_NEAR(psnrFromMse(1.0, 255.0), 20 * std::log10(255.0), 1e-12);
}

TEST(PixelMetric, ResultsDoNotDependOnThreadCount) {
    const Image a = gradientImage(301, 157);
    Image b = a;
    for (size_t i = 0; i < b.rgb.size(); i += 7) b.rgb[i] += 0.01f * float(i % 13);
    double mse1, rel1;
    std::vector<float> map1;
    {
        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        mse1 = meanSquaredError(a, b), rel1 = relativeMeanSquaredError(a, b);
        map1 = flip::evaluate(a, b, flip::Options{}).errorMap;
    }
    tbb::global_control four(tbb::global_control::max_allowed_parallelism, 4);
    EXPECT_EQ(meanSquaredError(a, b), mse1);
    EXPECT_EQ(relativeMeanSquaredError(a, b), rel1);
    EXPECT_EQ(flip::evaluate(a, b, flip::Options{}).errorMap, map1);
}

TEST(PixelMetric, CountsNonFinitePixels) {
    Image img = gradientImage(4, 4);
    img.rgb[0] = std::numeric_limits<float>::quiet_NaN();
    img.rgb[2] = std::numeric_limits<float>::infinity();    // same pixel
    img.rgb[10] = -std::numeric_limits<float>::infinity();  // pixel 3
    img.rgb[20] = std::numeric_limits<float>::quiet_NaN();  // pixel 6
    EXPECT_EQ(countNonFinitePixels(img), 3u);
    EXPECT_EQ(countNonFinitePixels(gradientImage(4, 4)), 0u);
}

TEST(PixelMetric, RequireComparableNamesTheProblem) {
    const Image good = gradientImage(4, 4);
    Image bad = good;
    bad.rgb[5] = std::numeric_limits<float>::quiet_NaN();
    bad.rgb[40] = std::numeric_limits<float>::infinity();
    try {
        requireComparable(good, bad, "ref.exr", "test.exr");
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("test.exr"), std::string::npos) << msg;
        EXPECT_NE(msg.find("2 of 16"), std::string::npos) << msg;
    }
    try {
        requireComparable(good, gradientImage(4, 5), "a.png", "b.png");
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("4x5"), std::string::npos) << e.what();
    }
    EXPECT_THROW(meanSquaredError(good, gradientImage(5, 4)), InputError);
    EXPECT_NO_THROW(requireComparable(good, good, "a", "b"));
}

TEST(PixelMetric, FlipModeFollowsFileTypes) {
    EXPECT_EQ(flipModeForFiles("a.png", "b.png"), flip::Mode::Ldr);
    EXPECT_EQ(flipModeForFiles("A.PNG", "dir/b.Png"), flip::Mode::Ldr);
    EXPECT_EQ(flipModeForFiles("a.exr", "b.exr"), flip::Mode::Hdr);
    EXPECT_EQ(flipModeForFiles("a.exr", "b.png"), flip::Mode::Hdr);
    EXPECT_EQ(flipModeForFiles("a.png", "b.pfm"), flip::Mode::Hdr);
    EXPECT_THROW(flipModeForFiles("a.jpg", "b.png"), InputError);
}

}  // namespace
}  // namespace pathlab
