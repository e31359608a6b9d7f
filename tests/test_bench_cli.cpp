// `pathlab bench` from the outside: what it reports is the median of the
// runs it made, and its counts are those of the frame it was asked for.
// (Speed itself is never checked by a test.)
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "cli_runner.h"

namespace pathlab {
namespace {

using testing::runPathlab;

double medianOf(const nlohmann::json& values) {
    std::vector<double> v = values.get<std::vector<double>>();
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

// The frame's time split: Embree's part is the frame's rays at the best raw
// rate, the sampler's its dimensions at the cost model's rate on two threads,
// and the three parts make up the frame's time.
void expectTimeSplitAddsUp(const nlohmann::json& scene) {
    const auto& limit = scene["ray_limit"];
    double best = 0;
    for (const auto& [mode, rate] : limit["raw_rays_per_second"].items()) {
        best = std::max(best, rate.get<double>());
        // A mode's rate is the fastest of its replays.
        const auto runs = limit["raw_rays_per_second_runs"][mode].get<std::vector<double>>();
        ASSERT_FALSE(runs.empty()) << mode;
        EXPECT_EQ(rate.get<double>(), *std::max_element(runs.begin(), runs.end())) << mode;
    }
    EXPECT_EQ(limit["best_raw_rays_per_second"].get<double>(), best);
    const auto& split = scene["time_split"];
    EXPECT_DOUBLE_EQ(split["embree_seconds"].get<double>(), scene["rays"].get<double>() / best);
    // A path of the Cornell box draws its two pixel dimensions and more.
    EXPECT_GT(split["dimensions"].get<double>(), 2.0 * scene["paths"].get<double>());
    EXPECT_GT(split["sampler_ns_per_dimension"].get<double>(), 0.0);
    EXPECT_DOUBLE_EQ(split["sampler_seconds"].get<double>(),
                     split["sampler_ns_per_dimension"].get<double>() * 1e-9 *
                         split["dimensions"].get<double>() / 2);
    EXPECT_NEAR(split["embree_seconds"].get<double>() + split["sampler_seconds"].get<double>() +
                    split["rest_seconds"].get<double>(),
                scene["seconds"].get<double>(), 1e-12);
}

TEST(BenchCli, ReportsTheMedianOfItsRuns) {
    const auto dir = testing::scratchDirectory("bench");
    for (int runs : {3, 4}) {
        const auto r = runPathlab(
            "bench --json --scene cornell-box --size 16 --spp 2 --threads 2 "
            "--runs " +
                std::to_string(runs),
            dir);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const auto out = nlohmann::json::parse(r.out);
        ASSERT_EQ(out["scenes"].size(), 1u);
        const auto& scene = out["scenes"][0];
        EXPECT_EQ(scene["runs"], runs);
        ASSERT_EQ(scene["seconds_runs"].size(), size_t(runs));
        EXPECT_EQ(scene["seconds"].get<double>(), medianOf(scene["seconds_runs"]));
        EXPECT_EQ(scene["paths"], 16 * 16 * 2);
        EXPECT_DOUBLE_EQ(scene["paths_per_second"].get<double>(),
                         512.0 / scene["seconds"].get<double>());
        EXPECT_DOUBLE_EQ(scene["rays_per_second"].get<double>(),
                         scene["rays"].get<double>() / scene["seconds"].get<double>());
        // One single-thread frame after each two-thread frame; the efficiency
        // is the median of the pairs' ratios.
        const auto& scaling = scene["scaling"];
        ASSERT_EQ(scaling["efficiency_runs"].size(), size_t(runs));
        EXPECT_EQ(scaling["efficiency"].get<double>(), medianOf(scaling["efficiency_runs"]));
        for (size_t i = 0; i < size_t(runs); ++i)
            EXPECT_GT(scaling["efficiency_runs"][i].get<double>(), 0.0);
        expectTimeSplitAddsUp(scene);
    }
    std::filesystem::remove_all(dir);
}

// --samplers: every sampler's frame, independent's included, is compared with
// the mean of the independent frames just before and just after it; a round's
// consecutive comparisons share that frame, so one round is a chain
// I S I S … I over all samplers in its rotated order.
TEST(BenchCli, ComparesEachSamplerWithTheIndependentFramesAroundIt) {
    const auto dir = testing::scratchDirectory("bench-samplers");
    const int rounds = 2;
    const auto r = runPathlab(
        "bench --json --samplers --no-scaling --scene cornell-box --size 8 --spp 1 --threads 2 "
        "--runs 1 --rounds " +
            std::to_string(rounds),
        dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto rows = nlohmann::json::parse(r.out)["samplers"];
    ASSERT_GE(rows.size(), 2u);
    const size_t count = rows.size();
    for (size_t i = 0; i < count; ++i) {
        const auto& row = rows[i];
        SCOPED_TRACE(row["sampler"].get<std::string>());
        ASSERT_EQ(row["cpu_seconds_runs"].size(), size_t(rounds));
        ASSERT_EQ(row["independent_before_runs"].size(), size_t(rounds));
        ASSERT_EQ(row["independent_after_runs"].size(), size_t(rounds));
        std::vector<double> ratios;
        for (int k = 0; k < rounds; ++k) {
            const double before = row["independent_before_runs"][k].get<double>();
            const double after = row["independent_after_runs"][k].get<double>();
            EXPECT_GT(before, 0.0);
            EXPECT_GT(after, 0.0);
            ratios.push_back(row["cpu_seconds_runs"][k].get<double>() / ((before + after) / 2));
        }
        EXPECT_DOUBLE_EQ(row["vs_independent"].get<double>(), medianOf(ratios) - 1);
    }
    // Round k starts at sampler k (registry order): sampler i's frame after
    // is sampler i+1's frame before, except where the round's chain ends.
    for (int k = 0; k < rounds; ++k)
        for (size_t step = 0; step + 1 < count; ++step) {
            const size_t i = (step + size_t(k)) % count, next = (i + 1) % count;
            EXPECT_EQ(rows[i]["independent_after_runs"][k],
                      rows[next]["independent_before_runs"][k]);
        }
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace pathlab
