// `pathlab view`'s A/B at equal render time: the pass scheduler gives each
// sampler the same share of render time (so the cheaper one gets more passes
// and a higher spp), at equal spp it brings both to the same count, and the
// session's frames are still `pathlab render`'s at each sampler's own spp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "view/pass_scheduler.h"
#include "view_test_util.h"

namespace pathlab {
namespace {

using testing::renderedLike;
using testing::sameBytes;
using testing::smallViewSettings;
using view::EqualBy;
using view::Pass;
using view::PassScheduler;

// Runs the schedule with a made-up cost per sample for A and B (a
// progressive sampler pays for its new samples, another for all of them),
// for `passes` passes or until done; counts each sampler's passes.
struct Simulation {
    int passes[2] = {0, 0};
    double largestPass = 0;
    std::vector<Pass> log;
};

Simulation simulate(PassScheduler& plan, const double cost[2], bool progressive, int passes) {
    Simulation sim;
    for (int n = 0; n < passes && !plan.done(); ++n) {
        const Pass pass = plan.next();
        double seconds[2] = {0, 0};
        for (int i : {0, 1}) {
            if (pass.target[i] == 0) continue;
            const int samples = progressive ? pass.target[i] - plan.spp(i) : pass.target[i];
            seconds[i] = samples * cost[i];
            sim.largestPass = std::max(sim.largestPass, seconds[i]);
            ++sim.passes[i];
        }
        plan.finished(pass, seconds[0], seconds[1]);
        sim.log.push_back(pass);
    }
    return sim;
}

// A pass costs a fixed part and a part per sample (at 512² on two cores, for
// sobol-owen: ≈ 83 ms and 44.5 ms a sample). The first passes stay short, so
// a restart shows images at once; then the passes grow with the render time,
// so the fixed parts cost under 5% of a long render's time (they would cost
// 24% at 1024 spp with passes of 8), and no pass exceeds 2 × kLongestPass.
TEST(ViewPassScheduler, PassesGrowSoTheirFixedCostFallsBelowFivePercent) {
    const double fixed = 0.083, perSample = 0.0445;
    for (int total : {1024, 4096}) {
        PassScheduler plan(EqualBy::Spp, false, true, true, total);
        double seconds = 0, longest = 0;
        int passes = 0;
        while (!plan.done()) {
            const Pass pass = plan.next();
            if (passes == 0) {
                EXPECT_EQ(pass.target[0], 1) << "an image at once";
            }
            const double s = fixed + perSample * (pass.target[0] - plan.spp(0));
            if (passes < 4) {
                EXPECT_LT(s, 0.5) << "pass " << passes;
            }
            plan.finished(pass, s, 0);
            seconds += s, longest = std::max(longest, s), ++passes;
        }
        EXPECT_EQ(plan.spp(0), total);
        const double oneRender = fixed + perSample * total;
        EXPECT_LT(seconds / oneRender, 1.05) << total << " spp in " << passes << " passes";
        EXPECT_LE(longest, 2 * PassScheduler::kLongestPass) << total;
    }
}

TEST(ViewPassScheduler, EqualSppBringsBothToTheSameCount) {
    const double cost[2] = {3e-3, 1e-3};
    for (bool progressive : {true, false}) {
        PassScheduler plan(EqualBy::Spp, true, progressive, progressive, 1 << 12);
        const Simulation sim = simulate(plan, cost, progressive, 40);
        for (const Pass& p : sim.log) {
            EXPECT_GT(p.target[0], 0);
            EXPECT_EQ(p.target[0], p.target[1]);
        }
        EXPECT_EQ(plan.spp(0), plan.spp(1));
        EXPECT_EQ(sim.passes[0], sim.passes[1]);
    }
}

TEST(ViewPassScheduler, EqualTimeGivesTheCheaperSamplerMorePasses) {
    const double cost[2] = {3e-3, 1e-3};  // B's samples are three times cheaper
    for (bool progressive : {true, false}) {
        PassScheduler plan(EqualBy::Time, true, progressive, progressive, 1 << 16);
        const Simulation sim = simulate(plan, cost, progressive, 30);
        for (const Pass& p : sim.log)
            EXPECT_TRUE((p.target[0] == 0) != (p.target[1] == 0)) << "one sampler per pass";
        EXPECT_GT(sim.passes[1], sim.passes[0]) << "progressive " << progressive;
        EXPECT_GT(plan.spp(1), 2 * plan.spp(0)) << "progressive " << progressive;
        // Whoever is behind goes next, so the shares differ by at most one pass.
        EXPECT_LE(std::abs(plan.seconds(0) - plan.seconds(1)), sim.largestPass);
    }
}

TEST(ViewPassScheduler, EqualTimeAlternatesAtEqualCostAndFinishesBoth) {
    const double cost[2] = {1e-3, 1e-3};
    PassScheduler plan(EqualBy::Time, true, true, true, 64);
    const Simulation sim = simulate(plan, cost, true, 1000);
    ASSERT_GE(sim.log.size(), 4u);
    for (size_t i = 0; i < 4; ++i)
        EXPECT_NE(sim.log[i].target[i % 2], 0) << "A, B, A, B at equal cost: pass " << i;
    EXPECT_TRUE(plan.done());
    EXPECT_EQ(plan.spp(0), 64);
    EXPECT_EQ(plan.spp(1), 64);
}

TEST(ViewPassScheduler, WithoutCompareEveryPassIsA) {
    const double cost[2] = {1e-3, 0};
    PassScheduler plan(EqualBy::Time, false, true, true, 32);
    const Simulation sim = simulate(plan, cost, true, 1000);
    EXPECT_EQ(sim.passes[1], 0);
    EXPECT_TRUE(plan.done());
    EXPECT_EQ(plan.spp(0), 32);
}

TEST(ViewSession, EqualTimeFramesAreRendersOfEachSamplersSpp) {
    view::ViewSettings v = smallViewSettings("independent", "pmj02");
    v.equal = EqualBy::Time;
    const auto scene = view::loadViewScene(v.scene);
    view::ViewSession session(v, scene, 2);
    view::Frame frame;
    for (int waited = 0; waited < 4000; ++waited) {
        frame = session.frame();
        if (frame.a && frame.b && frame.spp >= 2 && frame.sppB >= 2) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    ASSERT_TRUE(frame.a && frame.b);
    EXPECT_TRUE(sameBytes(*frame.a, renderedLike(*scene, v, v.sampler, frame.spp)));
    EXPECT_TRUE(sameBytes(*frame.b, renderedLike(*scene, v, v.compare, frame.sppB)));
    EXPECT_EQ(session.status().settings.equal, EqualBy::Time);

    const uint64_t generation = session.status().generation;
    EXPECT_THROW(session.update({{"equal", "fast"}}), InputError);
    EXPECT_EQ(session.status().generation, generation) << "a bad mode changes nothing";
    const view::SessionStatus equalSpp = session.update({{"equal", "spp"}});
    EXPECT_EQ(equalSpp.generation, generation + 1) << "the mode restarts accumulation";
    const view::Frame after = session.waitForSpp(2);
    EXPECT_EQ(after.spp, after.sppB);
}

}  // namespace
}  // namespace pathlab
