// The batched Lambertian vertex (render/diffuse_batch.h) against the scalar
// code it replaces: every output bit for bit, lane by lane, and whole renders
// with and without batching byte for byte.
#include <gtest/gtest.h>

#include <cstring>
#include <iostream>
#include <random>

#include "render/diffuse_batch.h"
#include "render/path_integrator.h"
#include "render/renderer.h"
#include "sampling/registry.h"
#include "scene/builtin_scenes.h"

namespace pathlab {
namespace {

// Bitwise equality: -0 and +0 differ, as they would in an image.
bool same(float a, float b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}
void expectSame(Vec3f expected, float x, float y, float z, const char* what, int lane) {
    EXPECT_TRUE(same(expected.x, x) && same(expected.y, y) && same(expected.z, z))
        << what << " of lane " << lane << ": (" << expected.x << ", " << expected.y << ", "
        << expected.z << ") against (" << x << ", " << y << ", " << z << ")";
}

// The scalar next-event estimate and bounce of estimateRadiance at a
// Lambertian vertex lit by one area light sampled by area.
struct ScalarVertex {
    bool shadow = false;
    Vec3f shadowOrigin, shadowDir, direct{0.0f};
    std::optional<BsdfSample> bounce;
    Vec3f bounceDir, bounceOrigin;
};
ScalarVertex scalarVertex(const RenderScene& scene, const AreaLight& light,
                          const SurfaceInteraction& si, Vec3f dir, Vec3f albedo, Vec2f uLight,
                          Vec2f uDirection) {
    ScalarVertex v;
    const Frame frame(si.ns);
    const Vec3f wo = frame.toLocal(-dir);
    const Bsdf bsdf = Bsdf::diffuse(albedo);
    if (const auto ls = sampleByArea(light, si.p, uLight, 1.0f)) {
        const Vec3f wi = frame.toLocal(ls->wi);
        const Vec3f f = bsdf.f(wo, wi) * absCosTheta(wi);
        if (!isBlack(f)) {
            v.shadow = true;
            v.shadowOrigin = scene.offsetOrigin(si, ls->wi);
            v.shadowDir = si.p + ls->wi * ls->distance - v.shadowOrigin;
            const float weight = powerHeuristic(ls->pdf, bsdf.pdf(wo, wi));
            v.direct = f * ls->radiance * (weight / ls->pdf);
        }
    }
    v.bounce = bsdf.sample(wo, 0, uDirection);
    if (v.bounce) {
        v.bounceDir = frame.toWorld(v.bounce->wi);
        v.bounceOrigin = scene.offsetOrigin(si, v.bounceDir);
    }
    return v;
}

// Lights of each kind the kernel distinguishes: the Cornell box's one-sided
// parallelogram, a one-sided triangle, and both made two-sided.
std::vector<AreaLight> testLights(const AreaLight& cornell) {
    AreaLight triangle = cornell;
    triangle.parallelogram = false;
    triangle.rectangle = false;
    triangle.area = cornell.area / 2;
    std::vector<AreaLight> lights = {cornell, triangle};
    for (AreaLight l : {cornell, triangle}) {
        l.twoSided = true;
        lights.push_back(l);
    }
    return lights;
}

TEST(DiffuseBatch, MatchesTheScalarVertexBitForBit) {
    if (!batchUsesAvx2()) std::cout << "(this processor has no AVX2: SSE only)\n";
    const RenderScene scene(cornellBoxScene());
    ASSERT_TRUE(scene.batchesDiffusePaths());
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    auto point = [&] { return Vec3f(unit(rng) * 560, unit(rng) * 560, unit(rng) * 560); };
    auto direction = [&] {
        return normalize(Vec3f(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f));
    };
    // A draw, sometimes exactly 0 or ½ (the concentric disk's centre and axes).
    auto draw = [&] {
        const float u = unit(rng);
        return u < 0.05f ? 0.0f : (u < 0.1f ? 0.5f : unit(rng));
    };
    int shadows = 0, bounces = 0, lanesChecked = 0;
    // Both instruction sets (Best is AVX2 where the processor has it).
    for (BatchIsa isa : {BatchIsa::Best, BatchIsa::Sse})
        for (const AreaLight& light : testLights(*scene.lights().onlyAreaLight())) {
            for (int round = 0; round < 500; ++round) {
                const int lanes = 1 + round % kBatchLanes;
                DiffuseBatchInput in{};
                SurfaceInteraction si[kBatchLanes];
                Vec3f dir[kBatchLanes], albedo[kBatchLanes];
                Vec2f uLight[kBatchLanes], uDirection[kBatchLanes];
                for (int k = 0; k < lanes; ++k) {
                    si[k].p = point();
                    si[k].ng = direction();
                    // A shading normal off the geometric one (smooth shading), on its side.
                    si[k].ns = normalize(si[k].ng + direction() * 0.5f);
                    if (dot(si[k].ns, si[k].ng) < 0) si[k].ns = -si[k].ns;
                    dir[k] = direction();
                    albedo[k] = Vec3f(unit(rng), round % 7 == 0 ? 0.0f : unit(rng), unit(rng));
                    if (round % 11 == 0) albedo[k] = Vec3f(0.0f);
                    uLight[k] = {draw(), draw()};
                    uDirection[k] = {draw(), draw()};
                    setBatchLane(in, k, si[k], dir[k], albedo[k], uLight[k], uDirection[k]);
                }
                DiffuseBatchOutput out;
                shadeDiffuseBatch(light, scene.epsilon(), in, lanes, out, isa);
                for (int k = 0; k < lanes; ++k) {
                    const ScalarVertex v = scalarVertex(scene, light, si[k], dir[k], albedo[k],
                                                        uLight[k], uDirection[k]);
                    ++lanesChecked;
                    ASSERT_EQ(v.shadow, out.shadow[k] != 0) << "lane " << k << " round " << round;
                    if (v.shadow) {
                        ++shadows;
                        expectSame(v.shadowOrigin, out.sox[k], out.soy[k], out.soz[k],
                                   "shadow origin", k);
                        expectSame(v.shadowDir, out.sdx[k], out.sdy[k], out.sdz[k], "shadow ray",
                                   k);
                        expectSame(v.direct, out.directR[k], out.directG[k], out.directB[k],
                                   "direct", k);
                    }
                    ASSERT_EQ(v.bounce.has_value(), out.bounce[k] != 0) << "lane " << k;
                    if (!v.bounce) continue;
                    ++bounces;
                    expectSame(v.bounceDir, out.wx[k], out.wy[k], out.wz[k], "bounce direction", k);
                    expectSame(v.bounceOrigin, out.ox[k], out.oy[k], out.oz[k], "bounce origin", k);
                    expectSame(v.bounce->weight(), out.weightR[k], out.weightG[k], out.weightB[k],
                               "bounce weight", k);
                    EXPECT_TRUE(same(v.bounce->pdf, out.pdf[k])) << "bounce pdf of lane " << k;
                }
            }
        }
    // Both outcomes of each test were met, not only one.
    EXPECT_GT(shadows, lanesChecked / 8);
    EXPECT_LT(shadows, lanesChecked);
    EXPECT_GT(bounces, lanesChecked / 2);
}

std::vector<float> renderImage(const RenderScene& scene, RenderSettings s, bool batch,
                               RenderStats* stats) {
    s.batchDiffusePaths = batch;
    const RenderOutput out = render(scene, s);
    *stats = out.stats;
    std::vector<float> pixels = out.image.rgb;
    pixels.insert(pixels.end(), out.varianceOfMean.rgb.begin(), out.varianceOfMean.rgb.end());
    return pixels;
}

void expectSameRender(const RenderScene& scene, const RenderSettings& s) {
    RenderStats scalarStats, batchStats;
    const auto scalar = renderImage(scene, s, false, &scalarStats);
    const auto batch = renderImage(scene, s, true, &batchStats);
    ASSERT_EQ(scalar.size(), batch.size());
    EXPECT_EQ(0, std::memcmp(scalar.data(), batch.data(), scalar.size() * sizeof(float)))
        << s.sampler << ", " << s.samplesPerPixel << " spp, depth " << s.maxDepth
        << (s.russianRoulette ? ", roulette" : ", no roulette");
    EXPECT_EQ(scalarStats.rays, batchStats.rays);
    EXPECT_EQ(scalarStats.shadowRays, batchStats.shadowRays);
    EXPECT_EQ(scalarStats.dimensions, batchStats.dimensions);
}

TEST(DiffuseBatch, RendersTheScalarIntegratorsImageWithEverySampler) {
    const RenderScene scene(cornellBoxScene());
    for (const SamplerInfo& info : samplerInfos()) {
        RenderSettings s;
        s.sampler = info.name;
        s.resolution = {20, 20};
        s.samplesPerPixel = 16;
        expectSameRender(scene, s);
    }
}

TEST(DiffuseBatch, RendersTheScalarIntegratorsImageForEverySetting) {
    // A partial last packet (13 spp), no roulette, a short and a long path.
    SceneDescription desc = cornellBoxScene();
    const RenderScene scene(desc);
    for (int spp : {1, 13})
        for (bool roulette : {false, true})
            for (int depth : {1, 3, 20}) {
                RenderSettings s;
                s.resolution = {16, 16};
                s.samplesPerPixel = spp;
                s.russianRoulette = roulette;
                s.maxDepth = depth;
                expectSameRender(scene, s);
            }
}

TEST(DiffuseBatch, RendersTheScalarIntegratorsImageWithTexturesAndSmoothNormals) {
    // The Cornell box with a checkered texture on one material and vertex
    // normals bent off the faces of every mesh: still batched.
    SceneDescription desc = cornellBoxScene();
    Texture checker;
    checker.width = checker.height = 4;
    for (int i = 0; i < 16; ++i)
        checker.texels.push_back((i + i / 4) % 2 ? Vec3f(0.9f, 0.2f, 0.1f)
                                                 : Vec3f(0.1f, 0.8f, 0.3f));
    desc.textures.push_back(checker);
    desc.materials[0].texture = 0;
    for (Mesh& m : desc.meshes) {
        if (!isBlack(m.emission)) continue;
        m.normals.clear();
        m.uvs.clear();
        for (const Vec3f& p : m.positions) {
            m.normals.push_back(normalize(Vec3f(std::sin(p.x), std::cos(p.y), std::sin(p.z + 1))));
            m.uvs.push_back({p.x / 137, p.z / 91});
        }
    }
    const RenderScene scene(desc);
    ASSERT_TRUE(scene.batchesDiffusePaths());
    RenderSettings s;
    s.resolution = {24, 24};
    s.samplesPerPixel = 16;
    expectSameRender(scene, s);
}

TEST(DiffuseBatch, OnlyLambertianScenesWithOneAreaLightAreBatched) {
    EXPECT_TRUE(RenderScene(cornellBoxScene()).batchesDiffusePaths());
    SceneDescription mirror = cornellBoxScene();
    mirror.materials[0].type = MaterialType::Mirror;
    EXPECT_FALSE(RenderScene(mirror).batchesDiffusePaths());
    SceneDescription sky = cornellBoxScene();
    sky.environment = Vec3f(0.1f);
    EXPECT_FALSE(RenderScene(sky).batchesDiffusePaths());
    EXPECT_FALSE(RenderScene(cornellBoxScene(), LightSampling::SolidAngle).batchesDiffusePaths());
}

}  // namespace
}  // namespace pathlab
