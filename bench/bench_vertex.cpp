// Nanoseconds per Lambertian path vertex on the Cornell box for the arithmetic
// around its rays: next-event sample and bounce, computed by the scalar
// integrator's functions (sampleDirect, Bsdf::sample, Frame, offsetOrigin) and
// by the batched kernel (shadeDiffuseBatch) with AVX2 and with SSE. Random
// vertices, as a path's successive vertices are: a random wall, side and
// direction each time.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "render/batched_paths.h"
#include "render/diffuse_batch.h"
#include "render/path_integrator.h"
#include "scene/builtin_scenes.h"

namespace pathlab {
namespace {

constexpr int kVertices = 4096;

struct Vertex {
    SurfaceInteraction si;
    Vec3f dir, albedo;
    Vec2f uLight, uDirection;
};

const RenderScene& cornellBox() {
    static const RenderScene scene(cornellBoxScene());
    return scene;
}

// Points on the box's five walls, facing into it, hit from inside.
std::vector<Vertex> randomVertices() {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const Vec3f normals[5] = {{0, 1, 0}, {0, -1, 0}, {1, 0, 0}, {-1, 0, 0}, {0, 0, -1}};
    std::vector<Vertex> vertices(kVertices);
    for (Vertex& v : vertices) {
        const int wall = int(unit(rng) * 5) % 5;
        const Vec3f n = normals[wall];
        v.si.p = Vec3f(unit(rng) * 550, unit(rng) * 548, unit(rng) * 559);
        v.si.ng = v.si.ns = n;
        v.dir = normalize(Vec3f(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f));
        if (dot(v.dir, n) > 0) v.dir = -v.dir;
        v.albedo = Vec3f(0.7f, 0.6f, 0.5f);
        v.uLight = {unit(rng), unit(rng)};
        v.uDirection = {unit(rng), unit(rng)};
    }
    return vertices;
}

void BM_VertexScalar(benchmark::State& state) {
    const RenderScene& scene = cornellBox();
    const std::vector<Vertex> vertices = randomVertices();
    for (auto _ : state) {
        for (const Vertex& v : vertices) {
            const Frame frame(v.si.ns);
            const Vec3f wo = frame.toLocal(-v.dir);
            const Bsdf bsdf = Bsdf::diffuse(v.albedo);
            benchmark::DoNotOptimize(sampleDirect(scene, v.si, frame, bsdf, wo, 0, v.uLight));
            const auto bs = bsdf.sample(wo, 0, v.uDirection);
            if (!bs) continue;
            const Vec3f wi = frame.toWorld(bs->wi);
            benchmark::DoNotOptimize(scene.offsetOrigin(v.si, wi));
            benchmark::DoNotOptimize(bs->weight());
        }
    }
    state.counters["ns/vertex"] =
        benchmark::Counter(double(state.iterations()) * kVertices,
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_VertexBatch(benchmark::State& state, BatchIsa isa) {
    const RenderScene& scene = cornellBox();
    const AreaLight* light = scene.lights().onlyAreaLight();
    const std::vector<Vertex> vertices = randomVertices();
    std::vector<DiffuseBatchInput> batches(kVertices / kBatchLanes);
    for (int i = 0; i < kVertices; ++i) {
        const Vertex& v = vertices[size_t(i)];
        setBatchLane(batches[size_t(i / kBatchLanes)], i % kBatchLanes, v.si, v.dir, v.albedo,
                     v.uLight, v.uDirection);
    }
    DiffuseBatchOutput out;
    for (auto _ : state) {
        for (const DiffuseBatchInput& in : batches) {
            shadeDiffuseBatch(light, scene.epsilon(), in, kBatchLanes, out, isa);
            benchmark::DoNotOptimize(out);
        }
    }
    state.counters["ns/vertex"] =
        benchmark::Counter(double(state.iterations()) * kVertices,
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

BENCHMARK(BM_VertexScalar);
BENCHMARK_CAPTURE(BM_VertexBatch, best, BatchIsa::Best);
BENCHMARK_CAPTURE(BM_VertexBatch, sse, BatchIsa::Sse);

}  // namespace
}  // namespace pathlab
