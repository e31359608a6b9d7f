// The ray queries behind the renderer: packets and lanes agree with single rays, and the
// recorder sees exactly the rays a render reports.
#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "render/renderer.h"
#include "scene/builtin_scenes.h"
#include "scene/embree_accel.h"
#include "scene/ray_replay.h"

namespace pathlab {
namespace {

TEST(EmbreeAccel, PacketHitsEqualSingleRayHits) {
    const SceneDescription scene = cornellBoxScene();
    const EmbreeAccel accel(scene);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> uniform(-0.35f, 0.35f);
    const Vec3f eye = scene.camera.eye;
    const Vec3f forward = normalize(scene.camera.target - eye);
    int hitCount = 0;
    for (int packet = 0; packet < 500; ++packet) {
        const int count = 1 + packet % kPacketWidth;
        Vec3f dirs[kPacketWidth];
        // Wide cone around the view axis: some rays escape through the open front.
        for (int k = 0; k < count; ++k)
            dirs[k] = normalize(forward + Vec3f(uniform(rng), uniform(rng), uniform(rng)));
        RayHit hits[kPacketWidth];
        bool found[kPacketWidth];
        accel.intersectPacket(eye, dirs, count, hits, found);
        for (int k = 0; k < count; ++k) {
            RayHit single;
            const bool hit =
                accel.intersect(eye, dirs[k], std::numeric_limits<float>::infinity(), &single);
            ASSERT_EQ(found[k], hit) << "packet " << packet << " ray " << k;
            if (!hit) continue;
            ++hitCount;
            EXPECT_EQ(hits[k].geomId, single.geomId);
            EXPECT_EQ(hits[k].primId, single.primId);
            EXPECT_NEAR(hits[k].t, single.t, 1e-5f * single.t);
            EXPECT_NEAR(hits[k].u, single.u, 1e-4f);
            EXPECT_NEAR(hits[k].v, single.v, 1e-4f);
        }
    }
    EXPECT_GT(hitCount, 1000);
}

// Lanes of any origin: inside the box towards random directions, some
// inactive, some shadow rays cut short. Each active lane must answer as the
// single-ray query does (bit for bit: the batched integrator relies on it),
// and no inactive lane may report anything.
TEST(EmbreeAccel, LaneQueriesEqualSingleRayQueries) {
    const SceneDescription scene = cornellBoxScene();
    const EmbreeAccel accel(scene);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const Vec3f lo = accel.boundsMin(), hi = accel.boundsMax();
    int hits = 0, blockedCount = 0, active = 0;
    for (int packet = 0; packet < 400; ++packet) {
        alignas(32) float o[3][kPacketWidth], d[3][kPacketWidth], tMax[kPacketWidth];
        int on[kPacketWidth];
        for (int k = 0; k < kPacketWidth; ++k) {
            for (int a = 0; a < 3; ++a) {
                o[a][k] = lo[a] + (hi[a] - lo[a]) * (0.05f + 0.9f * unit(rng));
                d[a][k] = 2 * unit(rng) - 1;
            }
            tMax[k] = (hi.x - lo.x) * (0.05f + 0.95f * unit(rng));
            on[k] = unit(rng) < 0.7f;
        }
        const int count = 1 + packet % kPacketWidth;
        const RayLanes lanes{o[0], o[1], o[2], d[0], d[1], d[2], tMax, on, count};
        RayHit laneHits[kPacketWidth];
        bool found[kPacketWidth], blocked[kPacketWidth];
        accel.intersectLanes({o[0], o[1], o[2], d[0], d[1], d[2], nullptr, on, count}, laneHits,
                             found);
        accel.occludedLanes(lanes, blocked);
        for (int k = 0; k < count; ++k) {
            if (!on[k]) {
                EXPECT_FALSE(found[k] || blocked[k]);
                continue;
            }
            ++active;
            const Vec3f ok(o[0][k], o[1][k], o[2][k]), dk(d[0][k], d[1][k], d[2][k]);
            RayHit single;
            const bool hit =
                accel.intersect(ok, dk, std::numeric_limits<float>::infinity(), &single);
            ASSERT_EQ(found[k], hit);
            EXPECT_EQ(blocked[k], accel.occluded(ok, dk, tMax[k]));
            hits += hit, blockedCount += blocked[k];
            if (!hit) continue;
            EXPECT_EQ(laneHits[k].geomId, single.geomId);
            EXPECT_EQ(laneHits[k].primId, single.primId);
            EXPECT_EQ(laneHits[k].t, single.t);
            EXPECT_EQ(laneHits[k].u, single.u);
            EXPECT_EQ(laneHits[k].v, single.v);
        }
    }
    // Inside a closed box, most rays hit; the short shadow rays are blocked
    // only sometimes.
    EXPECT_GT(hits, active / 2);
    EXPECT_GT(blockedCount, active / 20);
    EXPECT_LT(blockedCount, active);
}

TEST(EmbreeAccel, RecorderSeesEveryRayTheRenderCounts) {
    RenderScene scene(cornellBoxScene());
    RayRecorder recorder;
    scene.setRayRecorder(&recorder);
    RenderSettings settings;
    settings.samplesPerPixel = 3;  // one packet of 3 per pixel
    settings.resolution = {24, 24};
    settings.threads = 2;
    const RenderOutput out = render(scene, settings);
    scene.setRayRecorder(nullptr);
    const std::vector<RecordedRay> rays = recorder.gather();
    size_t shadow = 0;
    for (const RecordedRay& r : rays) shadow += r.shadow;
    EXPECT_EQ(rays.size(), out.stats.rays + out.stats.shadowRays);
    EXPECT_EQ(shadow, out.stats.shadowRays);
    EXPECT_GT(shadow, 0u);
    // Every path draws its pixel's 2D and at least one vertex block.
    EXPECT_GE(out.stats.dimensions, out.stats.paths * 2);
}

TEST(EmbreeAccel, RecorderMarksTheCameraPacketsCoherent) {
    // The camera rays of a pixel are its only packets traced as coherent;
    // bounce and shadow rays are not.
    RenderScene scene(cornellBoxScene());
    RayRecorder recorder;
    scene.setRayRecorder(&recorder);
    RenderSettings settings;
    settings.samplesPerPixel = 16;  // two camera packets per pixel
    settings.resolution = {8, 8};
    render(scene, settings);
    scene.setRayRecorder(nullptr);
    size_t coherent = 0, coherentShadow = 0;
    for (const RecordedRay& r : recorder.gather()) {
        coherent += r.coherent;
        coherentShadow += r.coherent && r.shadow;
    }
    EXPECT_EQ(coherent, size_t(8 * 8 * 16));
    EXPECT_EQ(coherentShadow, 0u);
}

TEST(EmbreeAccel, ReplayGroupsRaysByKind) {
    // Three coherent closest-hit rays, three incoherent ones, then two shadow
    // rays: three packets (or streams), never a coherent and an incoherent
    // ray in one.
    RenderScene scene(cornellBoxScene());
    const Vec3f eye = scene.description().camera.eye;
    std::vector<RecordedRay> rays;
    for (int k = 0; k < 3; ++k)
        rays.push_back({eye, {0.01f * float(k), 0, -1}, 1e30f, false, true});
    for (int k = 0; k < 3; ++k)
        rays.push_back({eye, {0, 0.01f * float(k), -1}, 1e30f, false, false});
    for (int k = 0; k < 2; ++k) rays.push_back({eye, {0, 0, -1}, 0.5f, true, false});
    EXPECT_EQ(replayRays(scene.accel(), rays, ReplayMode::Packet8, 1).queries, 3u);
    EXPECT_EQ(replayRays(scene.accel(), rays, ReplayMode::Stream, 1).queries, 3u);
    EXPECT_EQ(replayRays(scene.accel(), rays, ReplayMode::Single, 1).queries, rays.size());
}

TEST(EmbreeAccel, ReplayModesAgreeOnARecordedFrame) {
    // Packets and streams group consecutive rays of one kind; every grouping
    // must find the same hits as tracing them one by one.
    RenderScene scene(cornellBoxScene());
    RayRecorder recorder;
    scene.setRayRecorder(&recorder);
    RenderSettings settings;
    settings.samplesPerPixel = 2;
    settings.resolution = {32, 32};
    render(scene, settings);
    scene.setRayRecorder(nullptr);
    const std::vector<RecordedRay> rays = recorder.gather();
    size_t expected = 0;
    for (const RecordedRay& r : rays) {
        RayHit hit;
        expected += r.shadow ? scene.accel().occluded(r.o, r.d, r.tMax)
                             : scene.accel().intersect(r.o, r.d, r.tMax, &hit);
    }
    EXPECT_GT(expected, rays.size() / 4);
    EXPECT_LT(expected, rays.size());
    for (ReplayMode mode : {ReplayMode::Single, ReplayMode::Packet8, ReplayMode::Stream}) {
        const ReplayResult r = replayRays(scene.accel(), rays, mode, 2);
        EXPECT_EQ(r.rays, rays.size()) << replayModeName(mode);
        EXPECT_EQ(r.hits, expected) << replayModeName(mode);
    }
}

}  // namespace
}  // namespace pathlab
