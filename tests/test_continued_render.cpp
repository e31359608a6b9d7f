// Continued renders (RenderSettings::resume): a progressive sampler's render
// of N spp continued to M spp is, bit for bit, a render of M spp — what
// `pathlab view` relies on to show exactly `pathlab render`'s image after
// every pass.
#include <gtest/gtest.h>

#include <cstring>

#include "core/error.h"
#include "image_test_util.h"
#include "render/renderer.h"
#include "sampling/registry.h"
#include "scene/builtin_scenes.h"

namespace pathlab {
namespace {

using testing::sameBytes;

RenderSettings smallCornell(const std::string& sampler, int spp, bool weightedFilm) {
    RenderSettings s;
    s.sampler = sampler;
    s.samplesPerPixel = spp;
    s.seed = 5;
    s.resolution = {20, 16};
    s.maxDepth = 4;
    s.weightedFilm = weightedFilm;
    return s;
}

TEST(ContinuedRender, EveryPassEqualsARenderOfItsSpp) {
    const RenderScene scene(cornellBoxScene());
    for (const SamplerInfo& info : samplerInfos()) {
        if (!info.progressive) continue;
        for (bool weighted : {false, true}) {
            RunningSums sums;
            uint64_t paths = 0;
            for (int spp : {1, 2, 5, 9}) {
                RenderSettings s = smallCornell(info.name, spp, weighted);
                s.resume = &sums;
                const RenderOutput continued = render(scene, s);
                paths += continued.stats.paths;
                EXPECT_EQ(sums.spp, spp);
                const RenderOutput alone = render(scene, smallCornell(info.name, spp, weighted));
                EXPECT_TRUE(sameBytes(continued.image, alone.image))
                    << info.name << (weighted ? " weighted" : "") << " at " << spp;
                EXPECT_TRUE(sameBytes(continued.varianceOfMean, alone.varianceOfMean))
                    << info.name << " at " << spp;
            }
            EXPECT_EQ(paths, 20u * 16u * 9u) << "each sample is traced once";
        }
    }
}

TEST(ContinuedRender, RefusesWhatCannotContinue) {
    const RenderScene scene(cornellBoxScene());
    RunningSums sums;
    RenderSettings s = smallCornell("stratified", 2, false);
    s.resume = &sums;
    EXPECT_NO_THROW(render(scene, s)) << "a first pass needs no progressive sampler";
    s.samplesPerPixel = 4;
    EXPECT_THROW(render(scene, s), InputError) << "stratified's strata depend on the spp";
    sums = {};
    s.sampler = "independent";
    s.samplesPerPixel = 3;
    render(scene, s);
    EXPECT_THROW(render(scene, s), InputError) << "no samples to add";
}

TEST(ContinuedRender, CancellingEmptiesTheSums) {
    const RenderScene scene(cornellBoxScene());
    RunningSums sums;
    RenderControl control;
    RenderSettings s = smallCornell("independent", 2, false);
    s.resume = &sums;
    render(scene, s);
    control.cancel = true;
    s.control = &control;
    s.samplesPerPixel = 4;
    EXPECT_THROW(render(scene, s), RenderCancelled);
    EXPECT_EQ(sums.spp, 0);
    EXPECT_TRUE(sums.plain.empty());
}

}  // namespace
}  // namespace pathlab
