// Sample ranges (RenderSettings::sampleRange): a range draws exactly the
// samples the whole render draws for it, whatever the sampler, so ranges
// rendered apart and added in order (addRunningSums) make the whole render's
// image up to the rounding of the additions, and the same bits each time.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/error.h"
#include "image_test_util.h"
#include "render/renderer.h"
#include "sampling/registry.h"
#include "scene/builtin_scenes.h"

namespace pathlab {
namespace {

RenderSettings smallCornell(const std::string& sampler, int spp, bool weightedFilm) {
    RenderSettings s;
    s.sampler = sampler;
    s.samplesPerPixel = spp;
    s.seed = 3;
    s.resolution = {20, 16};
    s.maxDepth = 4;
    s.weightedFilm = weightedFilm;
    return s;
}

RunningSums renderRange(const RenderScene& scene, RenderSettings s, SampleRange range) {
    RunningSums sums;
    s.sampleRange = range;
    s.resume = &sums;
    render(scene, s);
    return sums;
}

using testing::sameBytes;

template <typename T>
bool sameBytes(const std::vector<T>& a, const std::vector<T>& b) {
    // memcmp must not see the null data() of an empty vector.
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Largest difference relative to the pixel's value.
float largestRelativeDifference(const Image& a, const Image& b) {
    float worst = 0;
    for (size_t i = 0; i < a.rgb.size(); ++i)
        if (a.rgb[i] != b.rgb[i])
            worst = std::max(worst, std::abs(a.rgb[i] - b.rgb[i]) / std::abs(a.rgb[i]));
    return worst;
}

TEST(SampleRanges, MergedRangesAreTheWholeRenderForEverySampler) {
    const RenderScene scene(cornellBoxScene());
    // Ranges of any length, not only whole batches of samples.
    const std::vector<SampleRange> ranges = {{0, 40}, {40, 64}, {64, 100}};
    for (const SamplerInfo& info : samplerInfos()) {
        for (bool weighted : {false, true}) {
            const RenderSettings s = smallCornell(info.name, 100, weighted);
            RunningSums total;
            for (const SampleRange& r : ranges) {
                const RunningSums sums = renderRange(scene, s, r);
                EXPECT_EQ(sums.first, r.first);
                EXPECT_EQ(sums.spp, r.count());
                addRunningSums(total, sums);
            }
            ASSERT_EQ(total.spp, 100);
            const RenderOutput merged = imageOfRunningSums(scene, s, total);
            const RenderOutput whole = render(scene, s);
            // Other samples would differ by the noise of 100 spp, ~1e-1.
            EXPECT_LT(largestRelativeDifference(whole.image, merged.image), 1e-5f)
                << info.name << (weighted ? " weighted" : "");
            EXPECT_LT(largestRelativeDifference(whole.varianceOfMean, merged.varianceOfMean), 1e-4f)
                << info.name;
        }
    }
}

TEST(SampleRanges, OneRangeOfAllSamplesIsTheRenderBitForBit) {
    const RenderScene scene(cornellBoxScene());
    for (const char* sampler : {"stratified", "zsobol", "sobol-owen"}) {
        const RenderSettings s = smallCornell(sampler, 24, false);
        const RenderOutput whole = render(scene, s);
        const RenderOutput fromSums = imageOfRunningSums(scene, s, renderRange(scene, s, {0, 24}));
        EXPECT_TRUE(sameBytes(whole.image, fromSums.image)) << sampler;
        EXPECT_TRUE(sameBytes(whole.varianceOfMean, fromSums.varianceOfMean)) << sampler;
    }
}

TEST(SampleRanges, ARangesSumsDoNotDependOnTheThreadCount) {
    const RenderScene scene(cornellBoxScene());
    for (bool weighted : {false, true}) {
        RenderSettings one = smallCornell("pmj02", 64, weighted), three = one;
        one.threads = 1;
        three.threads = 3;
        const RunningSums a = renderRange(scene, one, {16, 48});
        const RunningSums b = renderRange(scene, three, {16, 48});
        EXPECT_TRUE(sameBytes(a.plain, b.plain));
        EXPECT_TRUE(sameBytes(a.weighted, b.weighted));
        EXPECT_EQ(weighted, !a.weighted.empty());
    }
}

TEST(SampleRanges, AddingRefusesRangesOutOfOrder) {
    const RenderScene scene(cornellBoxScene());
    const RenderSettings s = smallCornell("independent", 8, false);
    RunningSums total = renderRange(scene, s, {0, 4});
    EXPECT_THROW(addRunningSums(total, renderRange(scene, s, {5, 8})), std::logic_error);
    EXPECT_EQ(total.spp, 4);
}

TEST(SampleRanges, RefusesRangesThatCannotBeRendered) {
    const RenderScene scene(cornellBoxScene());
    RenderSettings s = smallCornell("independent", 8, false);
    RunningSums sums;
    s.sampleRange = SampleRange{0, 4};
    EXPECT_THROW(render(scene, s), InputError) << "no sums to leave them in";
    s.resume = &sums;
    for (SampleRange bad : {SampleRange{4, 4}, SampleRange{-1, 4}, SampleRange{2, 9}}) {
        s.sampleRange = bad;
        EXPECT_THROW(render(scene, s), InputError) << bad.first << "…" << bad.end;
    }
    s.sampleRange = SampleRange{2, 4};
    render(scene, s);
    // A range's sums start at its first sample: they are no render to continue.
    s.sampleRange.reset();
    EXPECT_THROW(render(scene, s), InputError);
}

}  // namespace
}  // namespace pathlab
