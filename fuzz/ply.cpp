// Fuzzes the PLY reader behind pbrt-v4's "plymesh" (loadPlyMesh): header,
// ASCII and binary bodies of both byte orders. The input is written to
// mesh.ply in a scratch directory. Besides crashes and sanitizer reports, a
// mesh that breaks the reader's promises (an index out of range, attribute
// arrays of the wrong size, a non-finite value) aborts, so the fuzzer reports
// it too.
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/error.h"
#include "fuzz_util.h"
#include "scene/pbrt/ply_mesh.h"

namespace {

bool finite(pathlab::Vec3f v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void require(bool ok, const char* what) {
    if (!ok) {
        std::fprintf(stderr, "loadPlyMesh returned a bad mesh: %s\n", what);
        std::abort();
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace pathlab;
    const std::string path = fuzz::writeScratchFile("mesh.ply", fuzz::asText(data, size));
    Mesh mesh;
    try {
        mesh = pbrt::loadPlyMesh(path);
    } catch (const InputError&) {
        return 0;
    }
    const size_t n = mesh.positions.size();
    require(!mesh.indices.empty() && mesh.indices.size() % 3 == 0, "index count");
    require(mesh.normals.empty() || mesh.normals.size() == n, "normal count");
    require(mesh.uvs.empty() || mesh.uvs.size() == n, "uv count");
    for (uint32_t i : mesh.indices) require(i < n, "index out of range");
    for (const Vec3f& p : mesh.positions) require(finite(p), "non-finite position");
    for (const Vec3f& v : mesh.normals) require(finite(v), "non-finite normal");
    for (const Vec2f& uv : mesh.uvs)
        require(std::isfinite(uv.x) && std::isfinite(uv.y), "non-finite uv");
    return 0;
}
