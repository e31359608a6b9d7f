// The bytes of the messages between the ranks of a study across MPI
// (study/mpi_messages.h): every field comes back as it was sent, bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "study/mpi_messages.h"

namespace pathlab {
namespace {

bool sameBits(double a, double b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

bool sameBits(const std::optional<double>& a, const std::optional<double>& b) {
    return a.has_value() == b.has_value() && (!a || sameBits(*a, *b));
}

TEST(MpiMessages, RenderTaskComesBackWhole) {
    RenderTask task;
    task.scene = 3;
    task.cells.sampler = "halton-owen";
    task.cells.seed = 7;
    task.cells.spp = {1, 4, 16, 4096};
    task.cells.cells = {{"wolf", "halton-owen", 4, 7}, {"wolf", "halton-owen", 4096, 9}};
    const RenderTask back = decodeTask(encodeTask(task));
    EXPECT_EQ(back.scene, 3);
    EXPECT_EQ(back.cells.sampler, "halton-owen");
    EXPECT_EQ(back.cells.seed, 7);
    EXPECT_EQ(back.cells.spp, task.cells.spp);
    EXPECT_EQ(back.cells.cells, task.cells.cells);
}

TEST(MpiMessages, MeasurementsComeBackBitForBit) {
    study_steps::MeasuredCell a;
    a.key = {"cornell-box", "standard", 16, 1};
    a.seconds = 0.1 + 0.2;  // not a short decimal
    a.nonFinite = (uint64_t(1) << 40) + 3;
    a.metrics.mse = std::nextafter(1e-3, 1.0);
    a.metrics.rmse = std::sqrt(a.metrics.mse);
    a.metrics.psnr = std::numeric_limits<double>::infinity();  // identical images
    a.metrics.flip = std::numeric_limits<double>::denorm_min();
    a.metrics.bias = -0.0;
    a.metrics.mseEdge = std::nullopt;
    a.metrics.mseRest = 42.0;
    a.metrics.flipMap = {1.0f, 2.0f};  // stays with the images: not sent
    study_steps::MeasuredCell b;
    b.key = {"wolf", "independent", 1, 0};
    b.metrics.relmse = std::numeric_limits<double>::quiet_NaN();
    const auto back = decodeMeasured(encodeMeasured({a, b}));
    ASSERT_EQ(back.size(), 2u);
    for (size_t i = 0; i < 2; ++i) {
        const study_steps::MeasuredCell& sent = i == 0 ? a : b;
        const study_steps::MeasuredCell& got = back[i];
        EXPECT_EQ(got.key, sent.key);
        EXPECT_TRUE(sameBits(got.seconds, sent.seconds));
        EXPECT_EQ(got.nonFinite, sent.nonFinite);
        const CellMetrics &m = got.metrics, &s = sent.metrics;
        EXPECT_TRUE(sameBits(m.mse, s.mse));
        EXPECT_TRUE(sameBits(m.rmse, s.rmse));
        for (auto field :
             {&CellMetrics::relmse, &CellMetrics::flip, &CellMetrics::flipMedian,
              &CellMetrics::psnr, &CellMetrics::mseEdge, &CellMetrics::mseRest, &CellMetrics::bias})
            EXPECT_TRUE(sameBits(m.*field, s.*field)) << i;
        EXPECT_TRUE(m.flipMap.empty());
    }
}

TEST(MpiMessages, ReferenceImageComesBackBitForBit) {
    Image image(3, 2);
    for (size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = float(i) / 7.0f;
    image.rgb[4] = -0.0f;
    float exposure = 0;
    Image back;
    decodeReferenceImage(encodeReferenceImage(image, -1.25f), back, exposure);
    EXPECT_EQ(back.width, 3);
    EXPECT_EQ(back.height, 2);
    EXPECT_EQ(exposure, -1.25f);
    ASSERT_EQ(back.rgb.size(), image.rgb.size());
    EXPECT_EQ(std::memcmp(back.rgb.data(), image.rgb.data(), image.rgb.size() * sizeof(float)), 0);
}

TEST(MpiMessages, TruncatedMessageIsRefused) {
    RenderTask task;
    task.cells.sampler = "standard";
    task.cells.spp = {1};
    task.cells.cells = {{"cornell-box", "standard", 1, 0}};
    std::vector<char> bytes = encodeTask(task);
    bytes.resize(bytes.size() - 3);
    EXPECT_THROW(decodeTask(bytes), std::runtime_error);
    std::vector<char> image = encodeReferenceImage(Image(2, 2), 0.0f);
    image.resize(image.size() - 4);
    Image back;
    float exposure = 0;
    EXPECT_THROW(decodeReferenceImage(image, back, exposure), std::runtime_error);
}

TEST(MpiMessages, ReferenceRangesComeBackBitForBit) {
    EXPECT_EQ(decodeRangeTask(encodeRangeTask({2, 11})), (RangeTask{2, 11}));
    RangeSums sums;
    sums.index = 3;
    sums.seconds = 0.1 + 0.2;
    sums.sums.first = 192;
    sums.sums.spp = 64;
    sums.sums.weighted.resize(2);
    sums.sums.weighted[1].w2L2[2] = 1.0 / 3.0;
    const std::vector<std::string> keys = {"a", "b"};
    int scene = -1;
    const RangeSums back = decodeRangeResult(encodeRangeResult(1, sums, "b"), scene, keys);
    EXPECT_EQ(scene, 1);
    EXPECT_EQ(back.index, 3);
    EXPECT_TRUE(sameBits(back.seconds, sums.seconds));
    EXPECT_EQ(back.sums.first, 192);
    EXPECT_EQ(back.sums.spp, 64);
    ASSERT_EQ(back.sums.weighted.size(), 2u);
    EXPECT_TRUE(sameBits(back.sums.weighted[1].w2L2[2], 1.0 / 3.0));
    // Sums sent for another scene's reference, or for no scene, are refused.
    EXPECT_THROW(decodeRangeResult(encodeRangeResult(0, sums, "b"), scene, keys),
                 std::runtime_error);
    EXPECT_THROW(decodeRangeResult(encodeRangeResult(2, sums, "b"), scene, keys),
                 std::runtime_error);
}

}  // namespace
}  // namespace pathlab
