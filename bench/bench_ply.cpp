// pbrt-v4 "plymesh" loading at scale: a 1M-triangle binary PLY (positions,
// normals, uvs; a 500 × 1000 grid of quads stored as triangles, as exporters
// write them) loaded by loadPlyMesh, alone and followed by the Embree build
// the renderer does (EmbreeAccel over a scene holding the mesh). Goal: load +
// BVH under 1.5 s on 2 cores. With assimp available (libassimp-dev), the same
// through assimp's PLY importer (aiProcess_Triangulate, converted to a Mesh)
// for comparison (docs/pbrt-format.md, "PLY loading").
//
// Peak memory: run one benchmark per process, e.g.
//   /usr/bin/time -v pathlab_bench --benchmark_filter='BM_PlyLoadAndBvh$'
// or read its peak_rss_MiB counter (getrusage's maximum resident set size of
// the whole process, so also only meaningful alone).
#include <benchmark/benchmark.h>
#include <sys/resource.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "scene/embree_accel.h"
#include "scene/pbrt/ply_mesh.h"

#ifdef PATHLAB_BENCH_ASSIMP
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#endif

namespace pathlab {
namespace {

constexpr int kQuadsX = 500, kQuadsY = 1000;  // 1,000,000 triangles
// The file is written in the host's byte order and says little endian.
static_assert(std::endian::native == std::endian::little);

// The file, written once per process (row by row, so writing it costs no
// memory to speak of) and removed at exit.
class BigPly {
  public:
    BigPly() {
        dir_ = std::filesystem::temp_directory_path() /
               ("pathlab-bench-ply-" + std::to_string(getpid()));
        std::filesystem::create_directories(dir_);
        path_ = (dir_ / "grid.ply").string();
        std::FILE* f = std::fopen(path_.c_str(), "wb");
        if (!f) {
            std::perror(path_.c_str());
            std::abort();
        }
        const int nx = kQuadsX + 1, ny = kQuadsY + 1;
        std::fprintf(f,
                     "ply\nformat binary_little_endian 1.0\nelement vertex %d\n"
                     "property float x\nproperty float y\nproperty float z\n"
                     "property float nx\nproperty float ny\nproperty float nz\n"
                     "property float u\nproperty float v\n"
                     "element face %d\nproperty list uchar int vertex_indices\nend_header\n",
                     nx * ny, 2 * kQuadsX * kQuadsY);
        std::vector<float> row;
        for (int j = 0; j < ny; ++j) {
            row.clear();
            for (int i = 0; i < nx; ++i) {
                // A gently rolling height field: a realistic BVH, not a flat one.
                const float u = float(i) / kQuadsX, v = float(j) / kQuadsY;
                const float z = 0.05f * std::sin(20 * u) * std::cos(13 * v);
                const float dzdu = std::cos(20 * u) * std::cos(13 * v),
                            dzdv = -0.65f * std::sin(20 * u) * std::sin(13 * v);
                const float len = std::sqrt(1 + dzdu * dzdu + dzdv * dzdv);
                row.insert(row.end(), {u, 2 * v, z, -dzdu / len, -dzdv / len, 1 / len, u, v});
            }
            std::fwrite(row.data(), sizeof(float), row.size(), f);
        }
        for (int j = 0; j < kQuadsY; ++j)
            for (int i = 0; i < kQuadsX; ++i) {
                const int32_t a = j * nx + i, b = a + 1, c = a + nx + 1, d = a + nx;
                // Two faces of 13 bytes: count 3, then three little-endian int32.
                unsigned char face[2 * 13];
                const int32_t idx[6] = {a, b, c, a, c, d};
                for (int t = 0; t < 2; ++t) {
                    face[13 * t] = 3;
                    std::memcpy(face + 13 * t + 1, idx + 3 * t, 12);
                }
                std::fwrite(face, 1, sizeof face, f);
            }
        if (std::fclose(f) != 0) {
            std::perror(path_.c_str());
            std::abort();
        }
    }
    ~BigPly() {
        std::error_code ec;
        std::filesystem::remove_all(dir_, ec);
    }
    const std::string& path() const { return path_; }

  private:
    std::filesystem::path dir_;
    std::string path_;
};

const std::string& bigPly() {
    static const BigPly ply;
    return ply.path();
}

void reportPeak(benchmark::State& state, size_t triangles) {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    state.counters["peak_rss_MiB"] = double(usage.ru_maxrss) / 1024;  // ru_maxrss is in KiB
    state.counters["triangles"] = double(triangles);
}

void BM_PlyLoad(benchmark::State& state) {
    const std::string& path = bigPly();
    size_t triangles = 0;
    for (auto _ : state) {
        // Scoped: one mesh alive at a time, as in a scene load.
        const Mesh mesh = pbrt::loadPlyMesh(path);
        triangles = mesh.triangleCount();
        benchmark::DoNotOptimize(mesh.indices.data());
    }
    reportPeak(state, triangles);
}
BENCHMARK(BM_PlyLoad)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_PlyLoadAndBvh(benchmark::State& state) {
    const std::string& path = bigPly();
    size_t triangles = 0;
    for (auto _ : state) {
        SceneDescription scene;
        scene.meshes.push_back(pbrt::loadPlyMesh(path));
        triangles = scene.meshes[0].triangleCount();
        const EmbreeAccel accel(scene);
        benchmark::DoNotOptimize(accel.boundsMax());
    }
    reportPeak(state, triangles);
}
BENCHMARK(BM_PlyLoadAndBvh)->Unit(benchmark::kMillisecond)->UseRealTime();

#ifdef PATHLAB_BENCH_ASSIMP
// assimp's importer, with only the post-processing a mesh needs
// (Triangulate; JoinIdenticalVertices would cost more time, and the PLY
// importer keeps the file's vertex sharing without it), then copied into a Mesh.
Mesh loadWithAssimp(const std::string& path) {
    Assimp::Importer importer;
    const aiScene* s = importer.ReadFile(path, aiProcess_Triangulate);
    if (!s || s->mNumMeshes != 1) {
        std::fprintf(stderr, "assimp: %s\n", importer.GetErrorString());
        std::abort();
    }
    const aiMesh* m = s->mMeshes[0];
    Mesh mesh;
    auto vec = [](const aiVector3D& v) { return Vec3f(v.x, v.y, v.z); };
    mesh.positions.resize(m->mNumVertices);
    for (unsigned i = 0; i < m->mNumVertices; ++i) mesh.positions[i] = vec(m->mVertices[i]);
    if (m->HasNormals()) {
        mesh.normals.resize(m->mNumVertices);
        for (unsigned i = 0; i < m->mNumVertices; ++i) mesh.normals[i] = vec(m->mNormals[i]);
    }
    if (m->HasTextureCoords(0)) {
        mesh.uvs.resize(m->mNumVertices);
        for (unsigned i = 0; i < m->mNumVertices; ++i)
            mesh.uvs[i] = {m->mTextureCoords[0][i].x, m->mTextureCoords[0][i].y};
    }
    mesh.indices.reserve(3 * size_t(m->mNumFaces));
    for (unsigned f = 0; f < m->mNumFaces; ++f)
        for (unsigned k = 0; k < 3; ++k) mesh.indices.push_back(m->mFaces[f].mIndices[k]);
    return mesh;
}

void BM_PlyAssimpLoad(benchmark::State& state) {
    const std::string& path = bigPly();
    size_t triangles = 0;
    for (auto _ : state) {
        const Mesh mesh = loadWithAssimp(path);
        triangles = mesh.triangleCount();
        benchmark::DoNotOptimize(mesh.indices.data());
    }
    reportPeak(state, triangles);
}
BENCHMARK(BM_PlyAssimpLoad)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_PlyAssimpLoadAndBvh(benchmark::State& state) {
    const std::string& path = bigPly();
    size_t triangles = 0;
    for (auto _ : state) {
        SceneDescription scene;
        scene.meshes.push_back(loadWithAssimp(path));
        triangles = scene.meshes[0].triangleCount();
        const EmbreeAccel accel(scene);
        benchmark::DoNotOptimize(accel.boundsMax());
    }
    reportPeak(state, triangles);
}
BENCHMARK(BM_PlyAssimpLoadAndBvh)->Unit(benchmark::kMillisecond)->UseRealTime();
#endif

}  // namespace
}  // namespace pathlab
