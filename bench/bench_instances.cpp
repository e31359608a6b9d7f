// Memory and ray cost of Embree instancing: N instances of one 200,978-
// triangle grid against N flattened copies of it (transformMesh), each as a
// ready-to-render RenderScene.
//
// Counters: embree_MiB, the bytes Embree's device holds (its memory monitor:
// BVHs and geometry buffers; exact and repeatable); rss_MiB, the growth of the
// process's resident set while the scene (description included) exists — the
// whole cost, but subject to the allocator (freed memory of an earlier
// iteration may be reused), so read it next to embree_MiB; Mrays/s, closest-
// hit rays one at a time on the N-copy scene, one thread (copies not turned).
#include <benchmark/benchmark.h>
#include <malloc.h>
#include <unistd.h>

#include <fstream>
#include <limits>
#include <random>

#include "render/render_scene.h"
#include "scene/mesh_utils.h"

namespace pathlab {
namespace {

constexpr int kGridSide = 318;  // 2·317² = 200,978 triangles

Mesh grid() {
    Mesh m;
    for (int y = 0; y < kGridSide; ++y)
        for (int x = 0; x < kGridSide; ++x)
            m.positions.push_back({float(x) / kGridSide, 0.02f * float((x * 7 + y * 3) % 5) / 5,
                                   float(y) / kGridSide});
    for (int y = 0; y + 1 < kGridSide; ++y)
        for (int x = 0; x + 1 < kGridSide; ++x) {
            const auto a = uint32_t(y * kGridSide + x), b = a + 1, c = a + uint32_t(kGridSide),
                       d = c + 1;
            m.indices.insert(m.indices.end(), {a, b, d, a, d, c});
        }
    return m;
}

// Copy i: on a 32-wide lattice of unit cells, turned about y or not.
Affine placement(int i, bool turned) {
    return Affine::translation({1.1f * float(i % 32), 0, 1.1f * float(i / 32)}) *
           Affine::rotation({0, 1, 0}, turned ? float(11 * i) : 0.0f);
}

SceneDescription scene(int copies, bool instanced, bool turned = true) {
    SceneDescription s;
    s.materials.push_back(Material{});
    s.environment = Vec3f(1.0f);
    const Mesh mesh = grid();
    if (instanced) {
        s.objects.push_back(InstancedObject{"grid", {mesh}, {}});
        for (int i = 0; i < copies; ++i) s.instances.push_back({0, placement(i, turned)});
    } else {
        for (int i = 0; i < copies; ++i) {
            s.meshes.push_back(mesh);
            transformMesh(s.meshes.back(), placement(i, turned));
        }
    }
    s.camera.eye = {16, 20, -10};
    s.camera.target = {16, 0, 4};
    return s;
}

double residentMiB() {
    std::ifstream statm("/proc/self/statm");
    double pages = 0, resident = 0;
    statm >> pages >> resident;
    return resident * double(sysconf(_SC_PAGESIZE)) / 1048576.0;
}

void build(benchmark::State& state, bool instanced) {
    const int copies = int(state.range(0));
    double embree = 0, rss = 0;
    for (auto _ : state) {
        // Freed memory of the previous iteration back to the system first,
        // or the allocator would serve this one from it, unseen.
        malloc_trim(0);
        const double before = residentMiB();
        const RenderScene built(scene(copies, instanced));
        rss = residentMiB() - before;
        embree = double(built.accel().embreeBytes()) / 1048576.0;
    }
    state.counters["embree_MiB"] = embree;
    state.counters["rss_MiB"] = rss;
    state.counters["triangles_placed"] = double(copies) * 2 * (kGridSide - 1) * (kGridSide - 1);
}

void BM_BuildInstanced(benchmark::State& state) {
    build(state, true);
}
void BM_BuildFlattened(benchmark::State& state) {
    build(state, false);
}

// The price of instancing per ray: each ray that enters an instance is
// transformed into it, on top of the traversal a flattened copy costs. The
// copies are not turned here: a turned flattened grid has a worse BVH (boxes
// around oblique triangles) than the axis-aligned one an instance keeps in
// object space, which would hide that price.
void trace(benchmark::State& state, bool instanced) {
    const int copies = int(state.range(0));
    const RenderScene built(scene(copies, instanced, false));
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<std::pair<Vec3f, Vec3f>> rays(1 << 16);
    const Vec3f lo = built.accel().boundsMin(), hi = built.accel().boundsMax();
    for (auto& [o, d] : rays) {
        const Vec3f p{lo.x + (hi.x - lo.x) * unit(rng), 0, lo.z + (hi.z - lo.z) * unit(rng)};
        o = p + Vec3f(unit(rng) - 0.5f, 1, unit(rng) - 0.5f) * 3.0f;
        d = p - o;
    }
    size_t hits = 0;
    for (auto _ : state)
        for (const auto& [o, d] : rays) {
            RayHit hit;
            hits += built.accel().intersect(o, d, std::numeric_limits<float>::infinity(), &hit);
        }
    // The same rays hit the same grids in both scenes.
    state.counters["hit_fraction"] = double(hits) / double(rays.size() * state.iterations());
    state.counters["Mrays/s"] = benchmark::Counter(
        double(rays.size()) * 1e-6 * double(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_TraceInstanced(benchmark::State& state) {
    trace(state, true);
}
void BM_TraceFlattened(benchmark::State& state) {
    trace(state, false);
}

BENCHMARK(BM_BuildInstanced)
    ->Arg(1)
    ->Arg(10)
    ->Arg(100)
    ->Arg(1000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2)
    ->UseRealTime();
BENCHMARK(BM_BuildFlattened)
    ->Arg(1)
    ->Arg(10)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2)
    ->UseRealTime();
BENCHMARK(BM_TraceInstanced)->Arg(10)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_TraceFlattened)->Arg(10)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace pathlab
