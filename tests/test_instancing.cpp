// Embree instancing (SceneDescription::objects / instances): an instanced
// scene answers rays and renders as the same scene flattened into world-space
// copies does, spheres included; its memory grows with the unique geometry;
// its images do not depend on the thread count.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "image_test_util.h"
#include "instancing_test_util.h"
#include "metrics/image_metrics.h"
#include "render/renderer.h"
#include "scene/mesh_utils.h"

namespace pathlab {
namespace {

using test::flattened;
using test::instancedScene;

constexpr float kInf = std::numeric_limits<float>::infinity();

// Rays from a sphere around the scene towards random points in random
// instances' boxes, so that most of them hit instanced geometry.
struct RandomRays {
    std::mt19937 rng{17};
    std::uniform_real_distribution<float> unit{0.0f, 1.0f};
    std::vector<Bounds3f> targets;

    explicit RandomRays(const SceneDescription& s) {
        for (const ObjectInstance& inst : s.instances)
            targets.push_back(
                transformBounds(objectBounds(s.objects[size_t(inst.object)]), inst.objectToWorld));
    }
    std::pair<Vec3f, Vec3f> next() {
        const Vec3f o = Vec3f(0, 1, 0) +
                        normalize(Vec3f(2 * unit(rng) - 1, unit(rng), 2 * unit(rng) - 1)) * 9.0f;
        const Bounds3f& b = targets[size_t(unit(rng) * float(targets.size())) % targets.size()];
        const Vec3f e = b.extent();
        const Vec3f p = b.lo + Vec3f(e.x * unit(rng), e.y * unit(rng), e.z * unit(rng));
        return {o, p - o};
    }
};

bool same(Vec3f a, Vec3f b) {
    return a.x == b.x && a.y == b.y && a.z == b.z;
}

float relDiff(Vec3f a, Vec3f b) {
    return length(a - b) / std::max(1.0f, length(b));
}

TEST(Instancing, HitsMatchTheFlattenedScene) {
    const SceneDescription desc = instancedScene();
    const RenderScene inst(desc), flat(flattened(desc));
    RandomRays rays(desc);
    int hits = 0, instanceHits = 0, mirrored = 0, spheres = 0;
    for (int i = 0; i < 20000; ++i) {
        const auto [o, d] = rays.next();
        RayHit hi, hf;
        const bool foundI = inst.accel().intersect(o, d, kInf, &hi);
        ASSERT_EQ(foundI, flat.accel().intersect(o, d, kInf, &hf)) << "ray " << i;
        if (!foundI) continue;
        ++hits;
        EXPECT_NEAR(hi.t, hf.t, 1e-4f * hf.t) << "ray " << i;
        SurfaceInteraction si, sf;
        ASSERT_TRUE(inst.intersect(o, d, &si));
        ASSERT_TRUE(flat.intersect(o, d, &sf));
        EXPECT_LT(relDiff(si.p, sf.p), 1e-4f) << "ray " << i;
        EXPECT_LT(length(si.ng - sf.ng), 1e-4f) << "ray " << i;
        EXPECT_LT(length(si.ns - sf.ns), 1e-4f) << "ray " << i;
        EXPECT_NEAR(si.uv.x, sf.uv.x, 1e-4f);
        EXPECT_NEAR(si.uv.y, sf.uv.y, 1e-4f);
        EXPECT_EQ(si.material, sf.material);
        EXPECT_EQ(si.light, sf.light);
        if (hi.instId == RTC_INVALID_GEOMETRY_ID) continue;
        ++instanceHits;
        const size_t which = inst.accel().instanceIndex(hi.instId);
        ASSERT_LT(which, desc.instances.size());
        mirrored += which == 1 || which == 4;
        spheres += desc.instances[which].object == 1;
    }
    // Every kind of instance was hit many times, the mirrored ones included.
    EXPECT_GT(instanceHits, 8000);
    EXPECT_GT(mirrored, 2000);
    EXPECT_GT(spheres, 2000);
    EXPECT_GT(hits, instanceHits);  // the floor too
}

TEST(Instancing, MirroredInstanceKeepsTheGeometricNormalOutward) {
    // The blob is closed and wound outwards: a ray from outside must meet its
    // front side (ng against the ray) in every instance, mirrored or not, as
    // transformMesh's winding flip keeps it in a flattened copy.
    SceneDescription desc = instancedScene();
    desc.meshes.clear();
    const RenderScene inst(desc);
    RandomRays rays(desc);
    int checked = 0;
    for (int i = 0; i < 5000; ++i) {
        const auto [o, d] = rays.next();
        SurfaceInteraction si;
        if (!inst.intersect(o, d, &si)) continue;
        EXPECT_LT(dot(si.ng, d), 0) << "ray " << i;
        EXPECT_GT(dot(si.ns, si.ng), 0) << "ray " << i;
        ++checked;
    }
    EXPECT_GT(checked, 2000);
}

bool isSphere(const RenderScene& scene, const SceneDescription& desc, const RayHit& hit) {
    if (hit.instId == RTC_INVALID_GEOMETRY_ID)
        return hit.geomId == scene.accel().sphereGeometryId();
    const size_t object = size_t(desc.instances[scene.accel().instanceIndex(hit.instId)].object);
    return hit.geomId == scene.accel().objectSphereGeometryId(object);
}

TEST(Instancing, PacketsAndLanesReportTheInstance) {
    // The batched integrator's queries (rtcIntersect8) must name the instance
    // as the single-ray query does, and fill the same interaction.
    const SceneDescription desc = instancedScene();
    const RenderScene scene(desc);
    RandomRays rays(desc);
    int instanceHits = 0;
    for (int packet = 0; packet < 500; ++packet) {
        alignas(32) float o[3][kPacketWidth], d[3][kPacketWidth];
        int on[kPacketWidth], to[kPacketWidth];
        for (int k = 0; k < kPacketWidth; ++k) {
            const auto [ok, dk] = rays.next();
            for (int a = 0; a < 3; ++a) o[a][k] = ok[a], d[a][k] = dk[a];
            on[k] = (packet + k) % 5 != 0;
            to[k] = kPacketWidth - 1 - k;
        }
        const RayLanes lanes{o[0], o[1], o[2], d[0], d[1], d[2], nullptr, on, kPacketWidth};
        RayHit laneHits[kPacketWidth];
        bool laneFound[kPacketWidth];
        scene.accel().intersectLanes(lanes, laneHits, laneFound);
        SurfaceInteraction si[kPacketWidth];
        bool found[kPacketWidth];
        scene.intersectLanes(lanes, to, si, found);
        for (int k = 0; k < kPacketWidth; ++k) {
            if (!on[k]) continue;
            const Vec3f ok(o[0][k], o[1][k], o[2][k]), dk(d[0][k], d[1][k], d[2][k]);
            RayHit single;
            SurfaceInteraction ss;
            const bool hit = scene.accel().intersect(ok, dk, kInf, &single);
            ASSERT_EQ(laneFound[k], hit);
            ASSERT_EQ(found[to[k]], scene.intersect(ok, dk, &ss));
            if (!hit) continue;
            EXPECT_EQ(laneHits[k].instId, single.instId);
            EXPECT_EQ(laneHits[k].geomId, single.geomId);
            EXPECT_EQ(laneHits[k].primId, single.primId);
            // Triangles bit for bit, as at the top level; spheres only
            // nearly (Embree's packet and single-ray sphere tests round t
            // differently), but the interaction, recomputed from the ray,
            // bit for bit: so the batched integrator's images equal the
            // scalar one's byte for byte.
            if (!isSphere(scene, desc, single)) {
                EXPECT_EQ(laneHits[k].t, single.t);
                EXPECT_EQ(laneHits[k].u, single.u);
                EXPECT_EQ(laneHits[k].v, single.v);
            }
            EXPECT_NEAR(laneHits[k].t, single.t, 1e-5f * single.t);
            EXPECT_TRUE(same(si[to[k]].p, ss.p));
            EXPECT_TRUE(same(si[to[k]].ng, ss.ng));
            EXPECT_TRUE(same(si[to[k]].ns, ss.ns));
            instanceHits += single.instId != RTC_INVALID_GEOMETRY_ID;
        }
        // One origin, as the camera's packets: intersectPacket.
        const Vec3f eye(o[0][0], o[1][0], o[2][0]);
        Vec3f dirs[kPacketWidth];
        for (int k = 0; k < kPacketWidth; ++k) dirs[k] = {d[0][k], d[1][k], d[2][k]};
        RayHit packetHits[kPacketWidth];
        bool packetFound[kPacketWidth];
        scene.accel().intersectPacket(eye, dirs, kPacketWidth, packetHits, packetFound);
        for (int k = 0; k < kPacketWidth; ++k) {
            RayHit single;
            ASSERT_EQ(packetFound[k], scene.accel().intersect(eye, dirs[k], kInf, &single));
            if (!packetFound[k]) continue;
            EXPECT_EQ(packetHits[k].instId, single.instId);
            EXPECT_EQ(packetHits[k].geomId, single.geomId);
            EXPECT_EQ(packetHits[k].primId, single.primId);
            if (!isSphere(scene, desc, single)) {
                EXPECT_EQ(packetHits[k].t, single.t);
            }
        }
    }
    EXPECT_GT(instanceHits, 1500);
}

TEST(Instancing, SphereUnderNonUniformScaleIsAnEllipsoid) {
    // No flattened sphere can stand in for this one: check against the
    // ellipsoid's own equation and gradient.
    const Affine xf = Affine::translation({0.3f, 1, -0.2f}) * Affine::rotation({0, 0, 1}, 30) *
                      Affine::scaling({2.0f, 0.5f, -1.0f});
    const Sphere ball{{0.1f, 0.2f, 0}, 0.7f, 0};
    SceneDescription desc;
    desc.materials.push_back(Material{});
    desc.objects.push_back(InstancedObject{"egg", {}, {ball}});
    desc.instances.push_back({0, xf});
    const RenderScene scene(desc);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    const Vec3f centre = xf.point(ball.center);
    int hits = 0;
    for (int i = 0; i < 5000; ++i) {
        const Vec3f o = centre + normalize(Vec3f(unit(rng), unit(rng), unit(rng))) * 5.0f;
        const Vec3f d = centre + Vec3f(unit(rng), unit(rng), unit(rng)) * 1.2f - o;
        SurfaceInteraction si;
        if (!scene.intersect(o, d, &si)) continue;
        ++hits;
        // Back in object space the point lies on the sphere ...
        double q[3] = {si.p.x - xf.t.x, si.p.y - xf.t.y, si.p.z - xf.t.z};
        // (solve M·x = q by Cramer's rule, in double)
        const Affine& a = xf;
        const auto det3 = [](const double m[3][3]) {
            return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                   m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                   m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        };
        double m[3][3];
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) m[r][c] = a.m[r][c];
        const double det = det3(m);
        double x[3];
        for (int c = 0; c < 3; ++c) {
            double mc[3][3];
            std::memcpy(mc, m, sizeof m);
            for (int r = 0; r < 3; ++r) mc[r][c] = q[r];
            x[c] = det3(mc) / det;
        }
        const Vec3f local(float(x[0] - ball.center.x), float(x[1] - ball.center.y),
                          float(x[2] - ball.center.z));
        EXPECT_NEAR(length(local), ball.radius, 1e-4f * ball.radius) << "ray " << i;
        // ... and the normal is the gradient M⁻ᵀ·(x − c), pointing outwards.
        EXPECT_LT(length(si.ng - xf.normal(local)), 1e-4f) << "ray " << i;
        EXPECT_GT(dot(si.ng, si.p - centre), 0) << "ray " << i;
        EXPECT_LT(dot(si.ng, d), 0) << "ray " << i;
    }
    EXPECT_GT(hits, 1000);
}

RenderOutput renderWith(const RenderScene& scene, int threads, uint64_t seed = 0,
                        bool batch = true) {
    RenderSettings s;
    s.samplesPerPixel = 16;
    s.maxDepth = 5;
    s.threads = threads;
    s.seed = seed;
    s.batchPaths = batch;
    return render(scene, s);
}

TEST(Instancing, RendersTheFlattenedScenesImage) {
    // Same sampler, same seed: the two renders draw the same random numbers,
    // and their paths differ only where Embree's object-space hits round
    // differently from world-space ones (and by the ray offset, which
    // instancing makes a little larger). That difference must be far below
    // the render's own noise, measured as two seeds' relMSE.
    const SceneDescription desc = instancedScene();
    const RenderScene inst(desc), flat(flattened(desc));
    const Image a = renderWith(inst, 2).image, b = renderWith(flat, 2).image;
    const double diff = relativeMeanSquaredError(b, a);
    const double noise = relativeMeanSquaredError(b, renderWith(flat, 2, 1).image);
    std::printf("relMSE instanced vs flattened %.3g, seed-to-seed %.3g\n", diff, noise);
    EXPECT_LT(diff, 1e-3 * noise);
    EXPECT_LT(diff, 1e-5);
    // Not trivially equal: the instanced scene is a different one to Embree.
    EXPECT_GT(noise, 1e-3);
}

using testing::sameBytes;

TEST(Instancing, BatchedAndScalarIntegratorsAgree) {
    // As for top-level geometry (docs/rendering.md), byte for byte: the
    // packet queries answer as single rays do, and instanced sphere hits are
    // recomputed from the ray alone.
    const RenderScene scene(instancedScene());
    EXPECT_TRUE(
        sameBytes(renderWith(scene, 2, 0, true).image, renderWith(scene, 2, 0, false).image));
}

TEST(Instancing, ImageDoesNotDependOnTheThreadCount) {
    const RenderScene scene(instancedScene());
    const RenderOutput one = renderWith(scene, 1);
    for (int threads : {2, 8}) {
        EXPECT_TRUE(sameBytes(one.image, renderWith(scene, threads).image))
            << threads << " threads";
    }
}

TEST(Instancing, SceneBoundsIncludeInstances) {
    SceneDescription desc = instancedScene();
    desc.meshes.clear();
    const Bounds3f b = sceneBounds(desc);
    const Bounds3f f = sceneBounds(flattened(desc));
    // The corners of transformed boxes hold every flattened vertex; under
    // rotation they are a little larger, never smaller.
    for (int a = 0; a < 3; ++a) {
        EXPECT_LE(b.lo[a], f.lo[a]);
        EXPECT_GE(b.hi[a], f.hi[a]);
        EXPECT_LT(f.lo[a] - b.lo[a], 1.0f);
        EXPECT_LT(b.hi[a] - f.hi[a], 1.0f);
    }
    // Placing the unused object far away extends them.
    desc.instances.push_back({2, Affine::translation({100, 0, 0})});
    EXPECT_GE(sceneBounds(desc).hi.x, 101.0f);
}

TEST(Instancing, RayOffsetCoversTheInstancesFloatError) {
    // A plane modelled at y = 10⁴ and moved back to the origin: world bounds
    // of about 1, but Embree intersects it in object space, where the ray's
    // origin along the plane's normal is about 10⁴ and carries an error of
    // ulp(10⁴) ≈ 10⁻³, different for every ray. A ray leaving the plane,
    // nudged off by the scene's epsilon, must never hit it again; nudged by
    // what the world bounds alone suggest, many do.
    SceneDescription desc;
    desc.materials.push_back(Material{});
    Mesh plane;
    appendQuad(plane, {0, 1e4f, 0}, {0, 1e4f, 1}, {1, 1e4f, 1}, {1, 1e4f, 0});
    desc.objects.push_back(InstancedObject{"far", {plane}, {}});
    const Affine turn = Affine::rotation({1, 0, 1}, 20);
    desc.instances.push_back(
        {0, Affine::translation(Vec3f(0, 0.3f, 0) - turn.vector({0, 1e4f, 0})) * turn});
    const RenderScene scene(desc);
    const Vec3f lo = scene.accel().boundsMin(), hi = scene.accel().boundsMax();
    const float worldOnly = 2e-5f * std::max({1.0f, std::abs(lo.x), std::abs(lo.y), std::abs(lo.z),
                                              std::abs(hi.x), std::abs(hi.y), std::abs(hi.z)});
    ASSERT_GT(scene.epsilon(), 10 * worldOnly);
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    int hits = 0, selfHits = 0, selfHitsWorldOnly = 0;
    const Vec3f c = (lo + hi) * 0.5f;
    for (int i = 0; i < 4000; ++i) {
        const Vec3f o = c + Vec3f(unit(rng) - 0.5f, 2, unit(rng) - 0.5f);
        const Vec3f d = c + Vec3f(unit(rng) - 0.5f, 0, unit(rng) - 0.5f) * 0.6f - o;
        SurfaceInteraction si;
        if (!scene.intersect(o, d, &si)) continue;
        ++hits;
        // Back to the side the ray came from, in a random direction.
        const Vec3f out = dot(si.ng, d) < 0 ? si.ng : -si.ng;
        const Vec3f w =
            normalize(out + Vec3f(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f) * 0.8f);
        SurfaceInteraction again;
        selfHits += scene.intersect(scene.offsetOrigin(si, w), w, &again);
        selfHitsWorldOnly += scene.intersect(si.p + out * worldOnly, w, &again);
    }
    std::printf("%d hits; self-hits %d with the scene's offset %g, %d with %g\n", hits, selfHits,
                scene.epsilon(), selfHitsWorldOnly, worldOnly);
    EXPECT_GT(hits, 3000);
    EXPECT_EQ(selfHits, 0);
    EXPECT_GT(selfHitsWorldOnly, hits / 20);
}

TEST(Instancing, MemoryGrowsWithTheUniqueGeometryNotTheInstanceCount) {
    // Measured as Embree's own count of the bytes it holds (its device's
    // memory monitor: BVH nodes and geometry buffers), which depends only on
    // what was built; the process's resident size also moves with the
    // allocator's caches and whatever else the test binary did (bench/
    // bench_instances.cpp measures that too). The renderer's other
    // per-instance data is one InstanceFrame (52 bytes) per instance.
    SceneDescription base;
    base.materials.push_back(Material{});
    base.objects.push_back(InstancedObject{"grid", {test::gridMesh(318)}, {}});
    ASSERT_GT(base.objects[0].meshes[0].triangleCount(), 200000u);
    const auto placed = [&](int n) {
        SceneDescription s = base;
        for (int i = 0; i < n; ++i)
            s.instances.push_back({0, Affine::translation({float(i % 10), 0, float(i / 10)}) *
                                          Affine::rotation({0, 1, 0}, float(7 * i))});
        return s;
    };
    const SceneDescription sceneOne = placed(1), sceneHundred = placed(100);
    const EmbreeAccel one(sceneOne), hundred(sceneHundred);
    std::printf("Embree bytes: 1 instance %zu, 100 instances %zu (+%.2f%%)\n", one.embreeBytes(),
                hundred.embreeBytes(),
                100.0 * (double(hundred.embreeBytes()) / double(one.embreeBytes()) - 1));
    EXPECT_LT(double(hundred.embreeBytes()), 1.05 * double(one.embreeBytes()));
    // The count does follow the geometry: two flattened copies cost about
    // twice as much as one.
    const SceneDescription sceneTwo = flattened(placed(2));
    const EmbreeAccel two(sceneTwo);
    std::printf("Embree bytes: 2 flattened copies %zu\n", two.embreeBytes());
    EXPECT_GT(double(two.embreeBytes()), 1.8 * double(one.embreeBytes()));
}

}  // namespace
}  // namespace pathlab
