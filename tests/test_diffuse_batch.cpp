// The batched Lambertian vertex (render/diffuse_batch.h) against the scalar
// code it replaces: every output bit for bit, lane by lane, and whole renders
// with and without batching byte for byte.
#include <gtest/gtest.h>

#include <cstring>
#include <iostream>
#include <random>

#include "render/batched_paths.h"
#include "render/diffuse_batch.h"
#include "render/renderer.h"
#include "sampling/registry.h"
#include "scene/builtin_scenes.h"
#include "scene/loader.h"

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

// What estimateRadiance computes at a Lambertian vertex lit by `light`: its
// next-event sample (sampleDirect) and its bounce.
struct ScalarVertex {
    std::optional<DirectSample> direct;
    std::optional<BsdfSample> bounce;
    Vec3f bounceDir, bounceOrigin;
};
ScalarVertex scalarVertex(const RenderScene& scene, const SurfaceInteraction& si, Vec3f dir,
                          Vec3f albedo, float uChoice, Vec2f uLight, Vec2f uDirection) {
    ScalarVertex v;
    const Frame frame(si.ns);
    const Vec3f wo = frame.toLocal(-dir);
    const Bsdf bsdf = Bsdf::diffuse(albedo);
    v.direct = sampleDirect(scene, si, frame, bsdf, wo, uChoice, uLight);
    v.bounce = bsdf.sample(wo, 0, uDirection);
    if (v.bounce) {
        v.bounceDir = frame.toWorld(v.bounce->wi);
        v.bounceOrigin = scene.offsetOrigin(si, v.bounceDir);
    }
    return v;
}

// The Cornell box lit by each kind of light the kernel distinguishes: its
// one-sided parallelogram, one triangle of it, both made two-sided (all
// sampled by the kernel), and — with light samples drawn by LightSet — the
// light sampled by solid angle, and the light with a sky (a light choice, and
// shadow rays to infinity).
std::vector<RenderScene> lightVariants() {
    std::vector<RenderScene> scenes;
    for (bool triangle : {false, true})
        for (bool twoSided : {false, true}) {
            SceneDescription desc = cornellBoxScene();
            for (Mesh& m : desc.meshes) {
                if (isBlack(m.emission)) continue;
                m.twoSided = twoSided;
                if (triangle) m.indices.resize(3);
            }
            scenes.emplace_back(desc);
        }
    scenes.emplace_back(cornellBoxScene(), LightSampling::SolidAngle);
    SceneDescription sky = cornellBoxScene();
    sky.environment = Vec3f(0.3f, 0.4f, 0.5f);
    scenes.emplace_back(sky);
    return scenes;
}

// Random vertices: points anywhere in the box, geometric normals any way,
// shading normals bent off them, some black albedos, and draws that are
// sometimes exactly 0 or ½ (the concentric disk's centre and axes).
class RandomVertices {
  public:
    SurfaceInteraction interaction() {
        SurfaceInteraction si;
        si.p = Vec3f(unit() * 560, unit() * 560, unit() * 560);
        si.ng = direction();
        si.ns = normalize(si.ng + direction() * 0.5f);
        if (dot(si.ns, si.ng) < 0) si.ns = -si.ns;
        return si;
    }
    Vec3f direction() { return normalize(Vec3f(unit() - 0.5f, unit() - 0.5f, unit() - 0.5f)); }
    Vec3f albedo() {
        const float pick = unit();
        if (pick < 0.1f) return Vec3f(0.0f);
        return Vec3f(unit(), pick < 0.2f ? 0.0f : unit(), unit());
    }
    Vec2f draw2D() { return {draw(), draw()}; }
    float unit() { return std::uniform_real_distribution<float>(0.0f, 1.0f)(rng_); }
    float draw() {
        const float u = unit();
        return u < 0.05f ? 0.0f : (u < 0.1f ? 0.5f : unit());
    }

  private:
    std::mt19937 rng_{7};
};

struct Outcomes {
    int lanes = 0, shadows = 0, toInfinity = 0, bounces = 0;
};

// One batch of `lanes` random vertices, each output against the scalar code's.
void compareBatch(const RenderScene& scene, BatchIsa isa, int lanes, RandomVertices& random,
                  Outcomes& outcomes) {
    const AreaLight* onlyLight = scene.lights().onlyAreaLight();
    DiffuseBatchInput in{};
    SurfaceInteraction si[kBatchLanes];
    Vec3f dir[kBatchLanes], albedo[kBatchLanes];
    float uChoice[kBatchLanes];
    Vec2f uLight[kBatchLanes], uDirection[kBatchLanes];
    for (int k = 0; k < lanes; ++k) {
        si[k] = random.interaction();
        dir[k] = random.direction();
        albedo[k] = random.albedo();
        uChoice[k] = random.unit();
        uLight[k] = random.draw2D();
        uDirection[k] = random.draw2D();
        setBatchLane(in, k, si[k], dir[k], albedo[k], uLight[k], uDirection[k]);
        if (!onlyLight)
            setBatchLightSample(in, k,
                                scene.lights().sample(si[k].p, si[k].ns, uChoice[k], uLight[k]));
    }
    DiffuseBatchOutput out;
    shadeDiffuseBatch(onlyLight, scene.epsilon(), in, lanes, out, isa);
    for (int k = 0; k < lanes; ++k) {
        const ScalarVertex v =
            scalarVertex(scene, si[k], dir[k], albedo[k], uChoice[k], uLight[k], uDirection[k]);
        ++outcomes.lanes;
        ASSERT_EQ(v.direct.has_value(), out.shadow[k] != 0) << "lane " << k;
        if (v.direct) {
            ++outcomes.shadows;
            outcomes.toInfinity += std::isinf(v.direct->tMax);
            expectSame(v.direct->origin, out.sox[k], out.soy[k], out.soz[k], "shadow origin", k);
            expectSame(v.direct->toLight, out.sdx[k], out.sdy[k], out.sdz[k], "shadow ray", k);
            EXPECT_TRUE(same(v.direct->tMax, out.shadowTMax[k])) << "shadow ray's end, lane " << k;
            expectSame(v.direct->contribution, out.direct[0][k], out.direct[1][k], out.direct[2][k],
                       "direct", k);
        }
        ASSERT_EQ(v.bounce.has_value(), out.bounce[k] != 0) << "lane " << k;
        if (!v.bounce) continue;
        ++outcomes.bounces;
        expectSame(v.bounceDir, out.wx[k], out.wy[k], out.wz[k], "bounce direction", k);
        expectSame(v.bounceOrigin, out.ox[k], out.oy[k], out.oz[k], "bounce origin", k);
        expectSame(v.bounce->weight(), out.weight[0][k], out.weight[1][k], out.weight[2][k],
                   "bounce weight", k);
        EXPECT_TRUE(same(v.bounce->pdf, out.pdf[k])) << "bounce pdf of lane " << k;
    }
}

TEST(DiffuseBatch, MatchesTheScalarVertexBitForBit) {
    if (!batchUsesAvx2()) std::cout << "(this processor has no AVX2: SSE only)\n";
    RandomVertices random;
    Outcomes outcomes;
    // Both instruction sets (Best is AVX2 where the processor has it), every
    // kind of light, every number of live lanes.
    for (BatchIsa isa : {BatchIsa::Best, BatchIsa::Sse})
        for (const RenderScene& scene : lightVariants()) {
            ASSERT_TRUE(scene.allLambertian());
            for (int round = 0; round < 500; ++round)
                compareBatch(scene, isa, 1 + round % kBatchLanes, random, outcomes);
        }
    // Both outcomes of each test were met, not only one.
    EXPECT_GT(outcomes.shadows, outcomes.lanes / 8);
    EXPECT_LT(outcomes.shadows, outcomes.lanes);
    EXPECT_GT(outcomes.bounces, outcomes.lanes / 2);
    EXPECT_GT(outcomes.toInfinity, 0);
    EXPECT_LT(outcomes.toInfinity, outcomes.shadows / 2);
}

std::vector<float> renderImage(const RenderScene& scene, RenderSettings s, bool batch,
                               RenderStats* stats) {
    s.batchPaths = batch;
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

// More samples than one batch traces together (a full batch, then a partial
// one), and prefixes that end a batch early, with each of `samplers`.
void expectSameRenderAcrossBatches(const RenderScene& scene,
                                   std::initializer_list<const char*> samplers) {
    for (const char* sampler : samplers) {
        RenderSettings s;
        s.sampler = sampler;
        s.resolution = {6, 6};
        s.samplesPerPixel = kBatchSamples + 11;
        s.prefixSpp = {3, kBatchSamples / 2 + 1};
        expectSameRender(scene, s);
    }
}

TEST(DiffuseBatch, RendersTheScalarIntegratorsImageAcrossBatches) {
    // The batches' live paths, packed into groups across camera packets, give
    // the same image.
    expectSameRenderAcrossBatches(RenderScene(cornellBoxScene()),
                                  {"independent", "sobol", "halton-owen", "standard"});
}

TEST(DiffuseBatch, RendersTheScalarIntegratorsImageForEverySetting) {
    // Every kind of light; a partial last packet (13 spp); with and without
    // roulette; a short and a long path.
    for (const RenderScene& scene : lightVariants())
        for (int spp : {1, 13})
            for (bool roulette : {false, true})
                for (int depth : {1, 3, 20}) {
                    RenderSettings s;
                    s.resolution = {12, 12};
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
    ASSERT_TRUE(scene.allLambertian());
    RenderSettings s;
    s.resolution = {24, 24};
    s.samplesPerPixel = 16;
    expectSameRender(scene, s);
}

TEST(DiffuseBatch, RendersTheScalarIntegratorsImageWithSpheres) {
    SceneDescription desc = cornellBoxScene();
    desc.spheres.push_back({{278, 120, 250}, 90, 0});
    desc.spheres.push_back({{150, 300, 300}, 60, 1});
    const RenderScene scene(desc);
    RenderSettings s;
    s.resolution = {16, 16};
    s.samplesPerPixel = 16;
    expectSameRender(scene, s);
}

TEST(DiffuseBatch, RendersTheScalarIntegratorsImageOfGlassAndMetal) {
    // The shipped scene: glass, mirror and rough-metal spheres and a metal
    // pillar in the Cornell box's Lambertian walls.
    const RenderScene scene(
        loadScene(std::string(PATHLAB_SOURCE_DIR) + "/scenes/glass-and-metal.json"));
    RenderSettings s;
    s.resolution = {24, 24};
    s.samplesPerPixel = 16;
    expectSameRender(scene, s);
}

TEST(DiffuseBatch, KnowsWhichMaterialsAreLambertian) {
    EXPECT_TRUE(RenderScene(cornellBoxScene()).allLambertian());
    for (MaterialType type :
         {MaterialType::Mirror, MaterialType::Dielectric, MaterialType::Conductor}) {
        SceneDescription desc = cornellBoxScene();
        desc.materials[0].type = type;
        const RenderScene scene(desc);
        EXPECT_FALSE(scene.allLambertian());
        EXPECT_FALSE(scene.isLambertian(0));
        EXPECT_TRUE(scene.isLambertian(1));
    }
}

// The Cornell box with its first material (white: floor, ceiling, back wall
// and both blocks) and then its second made `type`.
std::vector<RenderScene> specularVariants() {
    std::vector<RenderScene> scenes;
    for (MaterialType type :
         {MaterialType::Mirror, MaterialType::Dielectric, MaterialType::Conductor})
        for (int m : {0, 1}) {
            SceneDescription desc = cornellBoxScene();
            desc.materials[size_t(m)].type = type;  // the default index, η, k and roughness
            scenes.emplace_back(desc);
        }
    return scenes;
}

TEST(DiffuseBatch, RendersTheScalarIntegratorsImageWithSpecularSurfaces) {
    // Mirror, glass and rough metal beside Lambertian surfaces: a group's
    // Lambertian vertices go through the kernel and the others are shaded one
    // at a time, their rays in the same packets; emission after a specular
    // bounce is unweighted. Every setting, and more samples than a batch.
    for (const RenderScene& scene : specularVariants()) {
        ASSERT_FALSE(scene.allLambertian());
        for (bool roulette : {false, true})
            for (int depth : {1, 3, 20}) {
                RenderSettings s;
                s.resolution = {10, 10};
                s.samplesPerPixel = 13;
                s.russianRoulette = roulette;
                s.maxDepth = depth;
                expectSameRender(scene, s);
            }
    }
    const std::vector<RenderScene> variants = specularVariants();
    // Glass floor, ceiling, back wall and blocks: groups of glass vertices
    // alone (no lane draws at all), with every sampler.
    expectSameRenderAcrossBatches(variants[2], {"sobol", "halton-owen", "standard"});
    for (const SamplerInfo& info : samplerInfos()) {
        RenderSettings s;
        s.sampler = info.name;
        s.resolution = {8, 8};
        s.samplesPerPixel = 16;
        expectSameRender(variants[2], s);
    }
}

}  // namespace
}  // namespace pathlab
