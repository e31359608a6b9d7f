// The study's analysis on artificial data, against numbers worked out by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "study/analysis.h"
#include "study/cell_metrics.h"

namespace pathlab {
namespace {

CellRow cell(const std::string& sampler, int spp, int seed, double mse, double seconds) {
    CellRow c;
    c.key = {"scene", sampler, spp, seed};
    c.mse = mse;
    c.rmse = std::sqrt(mse);
    c.relmse = 2 * mse;
    c.seconds = seconds;
    return c;
}

TEST(StudyAnalysis, LeastSquaresSlopeOfThreePoints) {
    // x = 0,1,2; y = 0,−2,−3: x̄ = 1, ȳ = −5/3, Σ(x−x̄)(y−ȳ) = −3, Σ(x−x̄)² = 2.
    const auto slope = leastSquaresSlope({0, 1, 2}, {0, -2, -3});
    ASSERT_TRUE(slope.has_value());
    EXPECT_DOUBLE_EQ(*slope, -1.5);
    EXPECT_FALSE(leastSquaresSlope({1}, {1}).has_value());
    EXPECT_FALSE(leastSquaresSlope({2, 2}, {1, 3}).has_value());
}

TEST(StudyAnalysis, SlopeIsLeastSquaresOfLogMseAboveTheNoiseFloor) {
    // After removing the floor 0.01, the MSE (mean of two seeds) is 1, 1/4, 1/8
    // at 1, 2, 4 spp: log2 points (0,0) (1,−2) (2,−3), slope −1.5 as above.
    const double floor = 0.01;
    const std::vector<CellRow> cells = {
        cell("halton", 1, 0, 0.9 + floor, 1),   cell("halton", 1, 1, 1.1 + floor, 1),
        cell("halton", 2, 0, 0.2 + floor, 2),   cell("halton", 2, 1, 0.3 + floor, 2),
        cell("halton", 4, 0, 0.125 + floor, 4), cell("halton", 4, 1, 0.125 + floor, 4)};
    const ReferenceRow ref{"scene", "independent", 1024, 1,  "key", floor, 0.0,
                           0,       "r.exr",       {},   {}, {}};
    const auto a = analyzeStudy(cells, {ref}, std::nullopt);
    const auto& s = a["scenes"]["scene"];
    EXPECT_DOUBLE_EQ(s["noise_floor_mse"].get<double>(), floor);
    EXPECT_NEAR(s["samplers"]["halton"]["slope_mse"].get<double>(), -1.5, 1e-12);
    const auto& bySpp = s["samplers"]["halton"]["by_spp"];
    EXPECT_NEAR(bySpp["1"]["mse"].get<double>(), 1.0 + floor, 1e-12);
    EXPECT_NEAR(bySpp["1"]["mse_min"].get<double>(), 0.9 + floor, 1e-12);
    EXPECT_NEAR(bySpp["1"]["mse_max"].get<double>(), 1.1 + floor, 1e-12);
    EXPECT_NEAR(bySpp["2"]["mse_corrected"].get<double>(), 0.25, 1e-12);
    EXPECT_FALSE(bySpp["4"]["below_noise_floor"].get<bool>());
    // No `independent` in the study: no ratios; no `standard`: no target.
    EXPECT_TRUE(s["samplers"]["halton"]["mse_ratio_to_independent"].is_null());
    EXPECT_TRUE(s["target_mse"].is_null());
}

TEST(StudyAnalysis, RatiosTargetAndEqualTime) {
    // standard: MSE 0.4 → 0.1 over 1 → 4 spp (1 s → 4 s); independent twice
    // the error; halton reaches 0.1 between 2 s (0.2) and 4 s (0.05).
    const std::vector<CellRow> cells = {
        cell("standard", 1, 0, 0.4, 1),    cell("standard", 4, 0, 0.1, 4),
        cell("independent", 1, 0, 0.8, 1), cell("independent", 4, 0, 0.2, 4),
        cell("halton", 1, 0, 0.2, 2),      cell("halton", 4, 0, 0.05, 4)};
    const auto a = analyzeStudy(cells, {}, 3.0);
    const auto& s = a["scenes"]["scene"];
    EXPECT_DOUBLE_EQ(s["target_mse"].get<double>(), 0.1);
    const auto& halton = s["samplers"]["halton"];
    EXPECT_DOUBLE_EQ(halton["mse_ratio_to_independent"]["1"].get<double>(), 0.25);
    EXPECT_DOUBLE_EQ(halton["mse_ratio_to_independent"]["4"].get<double>(), 0.25);
    // log t = log 2 + (log 0.1 − log 0.2)/(log 0.05 − log 0.2)·(log 4 − log 2) → t = 2·√2.
    EXPECT_NEAR(halton["time_to_target_seconds"].get<double>(), 2 * std::sqrt(2.0), 1e-12);
    EXPECT_NEAR(s["samplers"]["standard"]["time_to_target_seconds"].get<double>(), 4, 1e-12);
    // independent ends at 0.2 > 0.1: never reaches the target.
    EXPECT_TRUE(s["samplers"]["independent"]["time_to_target_seconds"].is_null());
    // Equal time at 3 s for standard: log-log between (1, 0.4) and (4, 0.1):
    // slope −1, so mse = 0.4 / 3.
    EXPECT_NEAR(s["samplers"]["standard"]["error_at_time_budget"]["mse"].get<double>(), 0.4 / 3,
                1e-12);
    EXPECT_NEAR(s["samplers"]["standard"]["slope_mse"].get<double>(), -1.0, 1e-12);
}

// A 10×10 image whose emitter edge is 4 pixels. Floors: edge 0.5, rest 0.01.
// independent: edge MSE 4.5, rest 0.11 → corrected 4 and 0.1; halton: edge
// 1.5, rest 0.06 → corrected 1 and 0.05. Ratios: edge 1/4, rest 1/2. Edge
// share of independent's corrected error: 4·4 / (4·4 + 96·0.1) = 16/25.6.
TEST(StudyAnalysis, RatiosByRegionSubtractEachRegionsFloor) {
    auto regionCell = [](const std::string& sampler, double edge, double rest) {
        CellRow c = cell(sampler, 4, 0, (4 * edge + 96 * rest) / 100, 1);
        c.mseEdge = edge;
        c.mseRest = rest;
        c.width = c.height = 10;
        return c;
    };
    const std::vector<CellRow> cells = {regionCell("independent", 4.5, 0.11),
                                        regionCell("halton", 1.5, 0.06)};
    const ReferenceRow ref{"scene", "independent", 1024, 1,    "key", 0.0, 0.0,
                           0,       "r.exr",       0.5,  0.01, 4};
    const auto a = analyzeStudy(cells, {ref}, std::nullopt);
    const auto& s = a["scenes"]["scene"];
    const auto& byRegion = s["samplers"]["halton"]["mse_ratio_by_region"];
    EXPECT_NEAR(byRegion["edge"]["4"].get<double>(), 0.25, 1e-12);
    EXPECT_NEAR(byRegion["rest"]["4"].get<double>(), 0.5, 1e-12);
    EXPECT_EQ(s["regions"]["edge_pixels"].get<int64_t>(), 4);
    EXPECT_EQ(s["regions"]["pixels"].get<int64_t>(), 100);
    EXPECT_NEAR(s["regions"]["independent_edge_share"]["4"].get<double>(), 16 / 25.6, 1e-12);
    // A study made before the regions: no split, no ratios by region.
    std::vector<CellRow> old = cells;
    for (CellRow& c : old) c.mseEdge.reset(), c.mseRest.reset();
    const ReferenceRow oldRef{"scene", "independent", 1024, 1,  "key", 0.0, 0.0,
                              0,       "r.exr",       {},   {}, {}};
    const auto b = analyzeStudy(old, {oldRef}, std::nullopt);
    EXPECT_TRUE(b["scenes"]["scene"]["regions"].is_null());
    EXPECT_TRUE(
        b["scenes"]["scene"]["samplers"]["halton"]["mse_ratio_by_region"]["edge"].is_null());
}

// The reference's noise floor over each region: the mean of its variance of
// the mean over the region's pixels and channels.
TEST(ReferenceNoise, FloorOfEachRegionIsTheMeanVarianceThere) {
    Image reference(2, 1), variance(2, 1);
    variance.set(0, 0, {3, 3, 6});  // mean 4
    variance.set(1, 0, {1, 1, 1});  // mean 1
    const std::vector<uint8_t> mask = {1, 0};
    const NoiseFloor n = referenceNoise(reference, variance, &mask);
    EXPECT_DOUBLE_EQ(n.mse, 2.5);
    ASSERT_TRUE(n.mseEdge && n.mseRest);
    EXPECT_DOUBLE_EQ(*n.mseEdge, 4.0);
    EXPECT_DOUBLE_EQ(*n.mseRest, 1.0);
    EXPECT_FALSE(referenceNoise(reference, variance).mseEdge.has_value());
}

TEST(StudyAnalysis, TimeAndErrorInterpolationEdges) {
    const std::vector<ErrorPoint> curve = {{1, 1.0}, {2, 0.5}, {4, 0.25}};
    EXPECT_EQ(timeToReach(curve, 2.0), 1.0);  // reached at once
    EXPECT_NEAR(*timeToReach(curve, 0.5), 2.0, 1e-12);
    EXPECT_FALSE(timeToReach(curve, 0.1).has_value());
    EXPECT_NEAR(*errorAtTime(curve, 2.0), 0.5, 1e-12);
    EXPECT_NEAR(*errorAtTime(curve, std::sqrt(2.0)), std::sqrt(0.5), 1e-12);
    EXPECT_FALSE(errorAtTime(curve, 0.5).has_value());
    EXPECT_FALSE(errorAtTime(curve, 8.0).has_value());
}

// A frame whose brightest 4% is an emitter (luminance 100) over grey walls
// (luminance 0.1): the view is exposed for the walls, whose luminance lands
// at 0.9, not for the emitter (which the 99th percentile would pick).
TEST(ViewingExposure, PutsTheWallsNotAVisibleLightAtNinetyPercent) {
    Image img(10, 10);
    for (int i = 0; i < 100; ++i) img.set(i % 10, i / 10, Vec3f(i < 4 ? 100.0f : 0.1f));
    EXPECT_NEAR(viewingExposure(img), std::log2(0.9 / 0.1), 1e-5);
    // Under the walls' level the 95th percentile is what sets it.
    for (int i = 4; i < 90; ++i) img.set(i % 10, i / 10, Vec3f(0.01f));
    EXPECT_NEAR(viewingExposure(img), std::log2(0.9 / 0.1), 1e-5);
    for (int i = 4; i < 100; ++i) img.set(i % 10, i / 10, Vec3f(0.01f));
    EXPECT_NEAR(viewingExposure(img), std::log2(0.9 / 0.01), 1e-5);
}

}  // namespace
}  // namespace pathlab
