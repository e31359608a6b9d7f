// `pathlab view`'s accumulation: after every pass the image is `pathlab
// render`'s at that spp, for progressive samplers (continued) and others
// (re-rendered), A and B at equal spp; render settings restart it, display
// settings do not.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "metrics/image_metrics.h"
#include "render/accumulation.h"
#include "view_test_util.h"

namespace pathlab {
namespace {

using testing::renderedLike;
using testing::sameBytes;
using testing::smallViewSettings;

TEST(ViewAccumulation, PassesEqualRendersOfTheirSpp) {
    const view::ViewSettings v = smallViewSettings("sobol-owen");
    const auto scene = view::loadViewScene(v.scene);
    for (const std::string sampler : {"sobol-owen", "pmj02"}) {  // progressive, not
        RenderSettings s;
        s.sampler = sampler, s.seed = v.seed, s.resolution = v.size, s.maxDepth = v.maxDepth;
        Accumulation acc(s);
        for (int spp : {1, 2, 4, 7}) {
            if (!acc.progressive() && spp == 7) continue;  // pmj02 passes double
            acc.advance(*scene, spp);
            EXPECT_EQ(acc.spp(), spp);
            EXPECT_TRUE(sameBytes(acc.image(), renderedLike(*scene, v, sampler, spp)))
                << sampler << " at " << spp;
        }
    }
}

TEST(ViewSession, FramesEqualRendersForBothSamplers) {
    const view::ViewSettings v = smallViewSettings("independent", "stratified");
    const auto scene = view::loadViewScene(v.scene);
    view::ViewSession session(v, scene, 2);
    const view::Frame frame = session.waitForSpp(4);
    ASSERT_TRUE(frame.a && frame.b);
    EXPECT_TRUE(sameBytes(*frame.a, renderedLike(*scene, v, "independent", frame.spp)));
    EXPECT_TRUE(sameBytes(*frame.b, renderedLike(*scene, v, "stratified", frame.spp)));
}

TEST(ViewSession, RenderSettingsRestartDisplaySettingsDoNot) {
    view::ViewSettings v = smallViewSettings("independent");
    const auto scene = view::loadViewScene(v.scene);
    view::ViewSession session(v, scene, 2);
    const view::Frame before = session.waitForSpp(2);
    const view::SessionStatus shown = session.update({{"exposure", 1.5}, {"tone_map", "aces"}});
    EXPECT_EQ(shown.generation, before.generation) << "display changes keep the sums";
    EXPECT_GE(shown.spp, before.spp);
    EXPECT_EQ(shown.settings.toneMap, view::ToneMap::Aces);
    const view::SessionStatus restarted = session.update({{"sampler", "halton"}});
    EXPECT_EQ(restarted.generation, before.generation + 1);
    const view::Frame after = session.waitForSpp(1);
    EXPECT_EQ(after.generation, before.generation + 1);
    v.sampler = "halton";
    EXPECT_TRUE(sameBytes(*after.a, renderedLike(*scene, v, "halton", after.spp)));
}

// The light sampler and spectral mode are render settings: each restarts,
// and the frames are `pathlab render --light-sampler … [--spectral]` of the
// scene at that spp. On 200 lights of unequal power the three strategies
// make three different images, so a view that ignored the setting fails.
TEST(ViewSession, LightSamplerAndSpectralAreRenderSettings) {
    view::ViewSettings v = smallViewSettings("sobol-owen");
    v.scene = std::string(PATHLAB_SOURCE_DIR) + "/scenes/pbrt/many-lights.pbrt";
    v.lightSampler = "uniform";
    view::ViewSession session(v, view::loadViewScene(v.scene, v.lightSampler), 2);
    const auto renderedWith = [&](const view::ViewSettings& like, int spp) {
        const auto scene = view::loadViewScene(like.scene, like.lightSampler);
        RenderSettings s;
        s.sampler = like.sampler, s.samplesPerPixel = spp, s.seed = like.seed;
        s.resolution = like.size, s.maxDepth = like.maxDepth, s.spectral = like.spectral;
        return render(*scene, s).image;
    };
    view::Frame frame = session.waitForSpp(2);
    EXPECT_TRUE(sameBytes(*frame.a, renderedWith(v, frame.spp)));
    uint64_t generation = frame.generation;
    for (const nlohmann::json& change :
         {nlohmann::json{{"light_sampler", "bvh"}}, nlohmann::json{{"spectral", true}},
          nlohmann::json{{"light_sampler", nullptr}}}) {  // back to the scene's: power
        const view::ViewSettings before = v;
        const view::SessionStatus s = session.update(change);
        EXPECT_EQ(s.generation, generation + 1) << change.dump();
        v = s.settings;
        frame = session.waitForSpp(2);
        generation = frame.generation;
        EXPECT_TRUE(sameBytes(*frame.a, renderedWith(v, frame.spp))) << change.dump();
        EXPECT_FALSE(sameBytes(*frame.a, renderedWith(before, frame.spp))) << change.dump();
    }
    EXPECT_EQ(v.lightSampler, "");
    EXPECT_TRUE(v.spectral);
    EXPECT_THROW(session.update({{"light_sampler", "nearest"}}), InputError);
    EXPECT_THROW(session.update({{"spectral", "yes"}}), InputError);
    EXPECT_EQ(session.status().generation, generation);
}

TEST(ViewSession, BadSettingsChangeNothing) {
    const view::ViewSettings v = smallViewSettings("independent");
    view::ViewSession session(v, view::loadViewScene(v.scene), 2);
    const uint64_t generation = session.waitForSpp(1).generation;
    for (const char* bad :
         {R"({"sampler": "no-such-sampler"})", R"({"max_depth": -1})",
          R"({"scene": "no-such-scene.json"})", R"({"colour": 1})", R"({"exposure": "bright"})",
          R"({"tone_map": "filmic"})", R"({"seed": "-3"})", R"([1, 2])"}) {
        EXPECT_THROW(session.update(nlohmann::json::parse(bad)), InputError) << bad;
    }
    const view::SessionStatus s = session.status();
    EXPECT_EQ(s.generation, generation);
    EXPECT_EQ(s.settings.sampler, "independent");
    EXPECT_EQ(s.settings.maxDepth, v.maxDepth);
}

TEST(ViewSession, PauseStopsPassesUntilResumed) {
    const view::ViewSettings v = smallViewSettings("independent");
    view::ViewSession session(v, view::loadViewScene(v.scene), 2);
    session.waitForSpp(1);
    session.update({{"paused", true}});
    session.waitUntilIdle();  // a pass under way lands first
    const int paused = session.status().spp;
    EXPECT_FALSE(session.status().running);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    EXPECT_EQ(session.status().spp, paused) << "no pass while paused";
    session.update({{"paused", false}});
    EXPECT_GT(session.waitForSpp(paused + 1).spp, paused);
}

TEST(ViewSession, ErrorAgainstAReferenceAtPowersOfTwo) {
    const view::ViewSettings v = smallViewSettings("independent", "sobol-owen");
    const auto scene = view::loadViewScene(v.scene);
    const auto reference =
        std::make_shared<const Image>(renderedLike(*scene, v, "sobol-owen", 256));
    view::ViewSession session(v, scene, 2, reference);
    std::vector<view::ErrorPoint> points;
    for (int waited = 0; waited < 2000 && (points.empty() || points.back().spp < 8); ++waited) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        points = session.errorPoints();
    }
    ASSERT_GE(points.size(), 3u);
    EXPECT_EQ(points.front().spp, 1);
    for (size_t i = 1; i < points.size(); ++i) {
        int power = 1;
        while (power <= points[i - 1].spp) power *= 2;
        EXPECT_GE(points[i].spp, power) << "one point per power of two";
        EXPECT_LT(points[i].spp, 3 * power) << "a pass at most triples the count";
    }
    for (const view::ErrorPoint& p : points) {
        EXPECT_EQ(p.mseA, meanSquaredError(*reference, renderedLike(*scene, v, v.sampler, p.spp)));
        EXPECT_EQ(p.mseB, meanSquaredError(*reference, renderedLike(*scene, v, v.compare, p.spp)));
        EXPECT_GT(p.flipA, 0);
        EXPECT_LT(p.flipA, 1);
    }
    EXPECT_LT(points.back().mseA, points.front().mseA);
    EXPECT_TRUE(session.status().reference);
}

TEST(ViewSession, ErrorMapsOfTheFrameAgainstTheReference) {
    // A 2×1 reference and tests whose errors are known: the relative squared
    // error (t − r)² / (r² + ε) maps 10^-4 … 1 onto 0 … 1 by its log10.
    Image reference(2, 1), test(2, 1);
    reference.set(0, 0, Vec3f(1.0f)), reference.set(1, 0, Vec3f(0.5f));
    test.set(0, 0, Vec3f(1.1f)), test.set(1, 0, Vec3f(0.5f));
    const view::ErrorHistory history(std::make_shared<const Image>(reference));
    const std::vector<float> relse = history.errorMap(test, view::ErrorMapKind::RelativeSquared);
    ASSERT_EQ(relse.size(), 2u);
    const double e = double(1.1f - 1.0f) * double(1.1f - 1.0f) / (1.0 + kRelMseEpsilon);
    EXPECT_NEAR(relse[0], (std::log10(e) + 4) / 4, 1e-6);
    EXPECT_EQ(relse[1], 0.0f) << "no error: the bottom of the map";
    EXPECT_EQ(history.errorMap(reference, view::ErrorMapKind::Flip), std::vector<float>(2, 0.0f));

    // The session's map of a frame is ꟻLIP's map of that image, and there is
    // none for a scene the reference does not show.
    view::ViewSettings v = smallViewSettings("independent");
    const auto scene = view::loadViewScene(v.scene);
    const auto full = std::make_shared<const Image>(renderedLike(*scene, v, "sobol-owen", 64));
    view::ViewSession session(v, scene, 2, full);
    const view::Frame frame = session.waitForSpp(2);
    ASSERT_TRUE(frame.a);
    flip::Options hdr;
    hdr.mode = flip::Mode::Hdr;
    EXPECT_EQ(session.errorMap(*frame.a, view::ErrorMapKind::Flip),
              flip::evaluate(*full, *frame.a, hdr).errorMap);
    session.update(nlohmann::json{{"width", 16}});
    const view::Frame smaller = session.waitForSpp(1);
    ASSERT_TRUE(smaller.a);
    EXPECT_TRUE(session.errorMap(*smaller.a, view::ErrorMapKind::Flip).empty());
}

}  // namespace
}  // namespace pathlab
