// `pathlab view`'s reference from the study's cache: one a study rendered is
// found for the same scene and settings (and only for them), and one built
// from the page is `pathlab render` of the study's reference settings, stored
// under the key a study of the same scene computes, so the study reuses it.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "metrics/image_metrics.h"
#include "scene/loader.h"
#include "study/reference_cache.h"
#include "study_test_util.h"
#include "view/reference_lookup.h"
#include "view_test_util.h"

namespace pathlab {
namespace {

using testing::renderedLike;
using testing::sameBytes;
using testing::smallViewSettings;

class ViewReference : public ::testing::Test {
  protected:
    void SetUp() override {
        dir = testing::scratchDirectory("view-reference");
        testing::usePrivateCache(dir);
    }
    void TearDown() override { std::filesystem::remove_all(dir); }

    // The study's spec for the view's small settings, reference at `spp`.
    std::string studySpec(int spp) const {
        return "name = \"view\"\nscenes = [\"cornell-box\"]\nsamplers = [\"independent\"]\n"
               "spp = [1]\nresolution = [32, 24]\nmax_depth = 4\nmetrics = [\"mse\"]\n"
               "[reference]\nspp = " +
               std::to_string(spp) + "\n";
    }
    std::filesystem::path dir;
};

// Waits (a bounded number of short sleeps) for the live error to start.
std::vector<view::ErrorPoint> waitForErrorPoints(const view::ViewSession& session) {
    for (int waited = 0; waited < 4000; ++waited) {
        std::vector<view::ErrorPoint> points = session.errorPoints();
        if (!points.empty()) return points;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return {};
}

TEST_F(ViewReference, AStudysCachedReferenceIsFoundForItsSettingsOnly) {
    const auto spec = testing::writeSpec(dir, "spec.toml", studySpec(16));
    const auto study =
        testing::runPathlab("study " + spec.string() + " -o " + (dir / "study").string(), dir);
    ASSERT_EQ(study.exitCode, 0) << study.err;
    const Image studyReference = readImage((dir / "study/references/cornell-box.exr").string());

    view::ViewSettings v = smallViewSettings("independent");
    v.maxSpp = 8;
    const auto scene = view::loadViewScene(v.scene);
    view::ViewSession session(v, scene, 2);
    const std::vector<view::ErrorPoint> points = waitForErrorPoints(session);
    ASSERT_FALSE(points.empty()) << "the cached reference is used";
    const view::SessionStatus status = session.status();
    EXPECT_TRUE(status.reference);
    EXPECT_EQ(status.referenceSource, "cache");
    EXPECT_EQ(status.referenceSpp, 16);
    EXPECT_EQ(points[0].mseA,
              meanSquaredError(studyReference, renderedLike(*scene, v, v.sampler, points[0].spp)))
        << "measured against the study's reference";

    // Another depth is another reference: none in the cache.
    session.update({{"max_depth", 3}});
    session.waitForSpp(1);
    EXPECT_FALSE(session.status().reference);
    const view::ReferenceTarget other{v.scene, v.size, 3, true};
    EXPECT_FALSE(view::findCachedReference(ReferenceCache::standard(), *scene, other));
}

// A study's light sampler is part of its reference: the view finds it with
// the same light sampler only (and the scene loaded choosing by it). Its
// [reference] ranges, in the key too, are read from the entry.
TEST_F(ViewReference, AStudysLightSamplerIsPartOfItsReference) {
    std::string text = studySpec(16) + "ranges = 3\n";
    text.insert(text.find("[reference]"), "light_sampler = \"uniform\"\n");
    const auto spec = testing::writeSpec(dir, "spec.toml", text);
    const auto study =
        testing::runPathlab("study " + spec.string() + " -o " + (dir / "study").string(), dir);
    ASSERT_EQ(study.exitCode, 0) << study.err;
    const view::ViewSettings v = smallViewSettings("independent");
    const auto find = [&](const std::string& lightSampler) {
        const auto scene = view::loadViewScene(v.scene, lightSampler);
        view::ReferenceTarget target{v.scene, v.size, v.maxDepth, v.russianRoulette};
        target.lightSampler = lightSampler;
        return view::findCachedReference(ReferenceCache::standard(), *scene, target);
    };
    const auto found = find("uniform");
    ASSERT_TRUE(found);
    EXPECT_EQ(found->spp, 16);
    EXPECT_TRUE(sameBytes(found->reference.image,
                          readImage((dir / "study/references/cornell-box.exr").string())));
    EXPECT_FALSE(find(""));
    EXPECT_FALSE(find("bvh"));
}

TEST_F(ViewReference, APageBuiltReferenceIsTheRenderAndTheStudysCacheEntry) {
    view::ViewSettings v = smallViewSettings("independent");
    v.maxSpp = 4;
    const auto scene = view::loadViewScene(v.scene);
    view::ViewSession session(v, scene, 2);
    EXPECT_FALSE(session.status().reference) << "an empty cache";
    EXPECT_THROW(session.buildReference(0), InputError);
    session.buildReference(16);
    session.waitForReference();
    session.update({{"max_spp", 8}});  // passes again, now measured
    ASSERT_FALSE(waitForErrorPoints(session).empty());
    const view::SessionStatus status = session.status();
    EXPECT_EQ(status.referenceSource, "page");
    EXPECT_EQ(status.referenceSpp, 16);
    EXPECT_TRUE(status.referenceError.empty()) << status.referenceError;

    // `pathlab render` at the study's reference sampler and seed, bit for bit.
    view::ViewSettings r = v;
    r.seed = kDefaultReferenceSeed;
    const Image rendered = renderedLike(*scene, r, ReferenceSpec{}.sampler, 16);
    const view::ReferenceTarget target{v.scene, v.size, v.maxDepth, v.russianRoulette};
    const auto cached = view::findCachedReference(ReferenceCache::standard(), *scene, target);
    ASSERT_TRUE(cached);
    EXPECT_TRUE(sameBytes(cached->reference.image, rendered));

    // Stored under the key a study of this scene and settings looks for.
    const StudySpec spec = parseStudySpec(studySpec(16), "spec.toml", dir.string());
    const std::string key = referenceCacheKey(loadScene("cornell-box"), spec.scenes[0], spec);
    EXPECT_TRUE(ReferenceCache::standard().contains(key));
}

}  // namespace
}  // namespace pathlab
