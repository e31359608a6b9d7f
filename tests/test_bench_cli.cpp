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
    for (const auto& [mode, rate] : limit["raw_rays_per_second"].items())
        best = std::max(best, rate.get<double>());
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

}  // namespace
}  // namespace pathlab
