// Prefix images: a progressive sampler's first N samples of an M-spp render
// are exactly an N-spp render, which is what lets a study render all of a
// sampler's spp at once. Checked both ways: the flag where it is claimed, and
// that the samplers not flagged really do depend on the spp they were built
// for (so the flag is not merely conservative).
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

RenderSettings smallCornell(const std::string& sampler, int spp) {
    RenderSettings s;
    s.sampler = sampler;
    s.samplesPerPixel = spp;
    s.seed = 3;
    s.resolution = {24, 20};
    s.maxDepth = 5;
    return s;
}

// Do the first `fewer` samples of every pixel, over the first dimensions of
// a path, come out the same from samplers built for `fewer` and for `more` spp?
bool samplesIndependentOfSpp(const std::string& name, int fewer, int more) {
    const Vec2i resolution{16, 16};
    AnySampler a = makeSampler(name, SamplerConfig{fewer, 7, resolution});
    AnySampler b = makeSampler(name, SamplerConfig{more, 7, resolution});
    for (int y = 0; y < resolution.y; y += 3)
        for (int x = 0; x < resolution.x; x += 3)
            for (int i = 0; i < fewer; ++i)
                for (int d = 0; d < 24; d += 2) {
                    const Vec2f u = std::visit(
                        [&](auto& s) {
                            return sampleDimensions(s, Vec2i{x, y}, i, d, d + 1);
                        },
                        a);
                    const Vec2f v = std::visit(
                        [&](auto& s) {
                            return sampleDimensions(s, Vec2i{x, y}, i, d, d + 1);
                        },
                        b);
                    if (u.x != v.x || u.y != v.y) return false;
                }
    return true;
}

TEST(PrefixRender, ProgressiveFlagMatchesWhatTheSamplersDo) {
    for (const SamplerInfo& info : samplerInfos()) {
        // 4 of 4 against 4 of 64 (even log2), 2 of 2 against 2 of 8 (odd).
        const bool same =
            samplesIndependentOfSpp(info.name, 4, 64) && samplesIndependentOfSpp(info.name, 2, 8);
        EXPECT_EQ(same, info.progressive) << info.name;
    }
}

TEST(PrefixRender, PrefixesAreBitIdenticalToRendersOfThatSpp) {
    const RenderScene scene(cornellBoxScene());
    for (const SamplerInfo& info : samplerInfos()) {
        if (!info.progressive) continue;
        RenderSettings s = smallCornell(info.name, 16);
        s.prefixSpp = {1, 2, 5, 8};
        const RenderOutput whole = render(scene, s);
        ASSERT_EQ(whole.prefixes.size(), 4u);
        EXPECT_TRUE(sameBytes(whole.image, render(scene, smallCornell(info.name, 16)).image))
            << info.name << ": asking for prefixes changed the full image";
        double previousSeconds = 0;
        for (const PrefixImage& p : whole.prefixes) {
            const RenderOutput alone = render(scene, smallCornell(info.name, p.spp));
            EXPECT_TRUE(sameBytes(p.image, alone.image)) << info.name << " at " << p.spp;
            EXPECT_TRUE(sameBytes(p.varianceOfMean, alone.varianceOfMean))
                << info.name << " at " << p.spp;
            EXPECT_EQ(p.nonFinite, alone.stats.nonFinite);
            EXPECT_GE(p.seconds, previousSeconds) << "more samples never take less time";
            EXPECT_LE(p.seconds, whole.stats.seconds);
            previousSeconds = p.seconds;
        }
    }
}

TEST(PrefixRender, RefusesNonProgressiveSamplersAndUnorderedCounts) {
    const RenderScene scene(cornellBoxScene());
    RenderSettings s = smallCornell("zsobol", 16);
    s.prefixSpp = {4};
    EXPECT_THROW(render(scene, s), InputError);
    s.sampler = "sobol";
    for (const std::vector<int>& bad : std::vector<std::vector<int>>{{4, 2}, {16}, {0}, {3, 3}}) {
        s.prefixSpp = bad;
        EXPECT_THROW(render(scene, s), InputError);
    }
    s.prefixSpp = {1, 15};
    EXPECT_NO_THROW(render(scene, s));
}

}  // namespace
}  // namespace pathlab
