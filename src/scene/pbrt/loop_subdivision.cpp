#include "scene/pbrt/loop_subdivision.h"

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <climits>
#include <cmath>
#include <memory>
#include <mutex>
#include <string>

#include "core/error.h"

namespace pathlab::pbrt {
namespace {
namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

constexpr int kMaxLevels = 10;
constexpr uint64_t kMaxTriangles = uint64_t(1) << 28;

// A point as OpenSubdiv's primvar refiner wants it: cleared, then summed
// with the weights of its stencil.
struct Point {
    float x, y, z;
    void Clear() { x = y = z = 0; }
    void AddWithWeight(const Point& p, float w) {
        x += w * p.x;
        y += w * p.y;
        z += w * p.z;
    }
    Vec3f vec() const { return {x, y, z}; }
};

// OpenSubdiv reports problems through process-wide callbacks, printing them
// by default: keep the last error of this thread for the exception instead,
// and drop warnings (the input is validated before OpenSubdiv sees it).
thread_local std::string lastOsdError;
void onOsdError(Far::ErrorType, const char* message) {
    lastOsdError = message;
}
void onOsdWarning(const char*) {}

void validate(const std::vector<Vec3f>& positions, const std::vector<uint32_t>& indices,
              int levels) {
    if (indices.empty() || indices.size() % 3 != 0)
        throw InputError(std::to_string(indices.size()) +
                         " vertex indices, not a positive multiple of 3");
    if (positions.size() > size_t(INT_MAX)) throw InputError("too many vertices");
    for (size_t i = 0; i < positions.size(); ++i) {
        const Vec3f p = positions[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw InputError("vertex " + std::to_string(i) + " has a non-finite position");
    }
    for (size_t t = 0; t < indices.size(); t += 3) {
        const uint32_t a = indices[t], b = indices[t + 1], c = indices[t + 2];
        for (uint32_t v : {a, b, c})
            if (v >= positions.size())
                throw InputError("index " + std::to_string(v) + " is out of range (" +
                                 std::to_string(positions.size()) + " vertices)");
        // Loop's rules need three distinct corners: a triangle that repeats
        // one has an edge from a vertex to itself, which no rule covers.
        if (a == b || b == c || a == c)
            throw InputError("triangle " + std::to_string(t / 3) +
                             " is degenerate (it repeats a vertex)");
    }
    if (levels < 0 || levels > kMaxLevels)
        throw InputError("levels " + std::to_string(levels) + " is outside [0, " +
                         std::to_string(kMaxLevels) + "]");
    if ((uint64_t(indices.size() / 3) << (2 * levels)) > kMaxTriangles)
        throw InputError(std::to_string(levels) + " levels would make more than 2^28 triangles");
}

}  // namespace

Mesh loopSubdivide(const std::vector<Vec3f>& positions, const std::vector<uint32_t>& indices,
                   int levels) {
    validate(positions, indices, levels);
    static std::once_flag callbacks;
    std::call_once(callbacks, [] {
        Far::SetErrorCallback(onOsdError);
        Far::SetWarningCallback(onOsdWarning);
    });

    const int faces = int(indices.size() / 3);
    const std::vector<int> vertsPerFace(size_t(faces), 3);
    Far::TopologyDescriptor desc;
    desc.numVertices = int(positions.size());
    desc.numFaces = faces;
    desc.numVertsPerFace = vertsPerFace.data();
    // uint32_t and int may alias; every index is below INT_MAX (checked above).
    desc.vertIndicesPerFace = reinterpret_cast<const Far::Index*>(indices.data());

    // Boundary edges as infinitely sharp creases, corners smooth: pbrt-v4's
    // boundary rules (edge points at the midpoint, boundary vertices from
    // their two boundary neighbours alone).
    Sdc::Options sdc;
    sdc.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
    using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
    lastOsdError.clear();
    std::unique_ptr<Far::TopologyRefiner> refiner(
        Factory::Create(desc, Factory::Options(Sdc::SCHEME_LOOP, sdc)));
    if (!refiner) throw InputError("OpenSubdiv rejected the control mesh: " + lastOsdError);

    // The limit masks need the finest level's full topology (edges, rings).
    Far::TopologyRefiner::UniformOptions uniform(levels);
    uniform.fullTopologyInLastLevel = true;
    refiner->RefineUniform(uniform);

    // Refine the positions level by level, then evaluate the limit surface
    // (position and two tangents) at every finest vertex.
    const Far::PrimvarRefiner primvar(*refiner);
    std::vector<Point> coarse(positions.size()), fine;
    for (size_t i = 0; i < positions.size(); ++i)
        coarse[i] = {positions[i].x, positions[i].y, positions[i].z};
    for (int level = 1; level <= levels; ++level) {
        fine.resize(size_t(refiner->GetLevel(level).GetNumVertices()));
        Point* dst = fine.data();
        primvar.Interpolate(level, coarse.data(), dst);
        coarse.swap(fine);
    }
    const Far::TopologyLevel& finest = refiner->GetLevel(levels);
    const size_t nv = size_t(finest.GetNumVertices());
    std::vector<Point> limit(nv), du(nv), dv(nv);
    {
        Point *p = limit.data(), *t1 = du.data(), *t2 = dv.data();
        primvar.Limit(coarse.data(), p, t1, t2);
    }
    if (!lastOsdError.empty()) throw InputError("OpenSubdiv failed: " + lastOsdError);

    // Each vertex's area-weighted face normal: the side the triangles' winding
    // faces, which the limit normal is made to agree with (OpenSubdiv's tangent
    // order is its own convention), and the normal itself where the tangents
    // are degenerate.
    const int nf = finest.GetNumFaces();
    std::vector<Vec3f> faceSum(nv, Vec3f(0.0f));
    std::vector<uint32_t> remap(nv, UINT32_MAX);
    Mesh mesh;
    mesh.name = "loopsubdiv";
    mesh.indices.reserve(3 * size_t(nf));
    for (int f = 0; f < nf; ++f) {
        const Far::ConstIndexArray fv = finest.GetFaceVertices(f);
        const Vec3f n = cross(limit[size_t(fv[1])].vec() - limit[size_t(fv[0])].vec(),
                              limit[size_t(fv[2])].vec() - limit[size_t(fv[0])].vec());
        for (int k = 0; k < 3; ++k) {
            const size_t v = size_t(fv[k]);
            faceSum[v] += n;
            // Only vertices of some triangle make it into the mesh.
            if (remap[v] == UINT32_MAX) {
                remap[v] = uint32_t(mesh.positions.size());
                mesh.positions.push_back(limit[v].vec());
            }
            mesh.indices.push_back(remap[v]);
        }
    }
    mesh.normals.resize(mesh.positions.size());
    for (size_t v = 0; v < nv; ++v) {
        if (remap[v] == UINT32_MAX) continue;
        Vec3f n = cross(du[v].vec(), dv[v].vec());
        const float len = length(n);
        if (!(len > 0) || !std::isfinite(len))
            n = faceSum[v];
        else if (dot(n, faceSum[v]) < 0)
            n = -n;
        const float nl = length(n);
        mesh.normals[remap[v]] = nl > 0 && std::isfinite(nl) ? n / nl : Vec3f(0, 0, 1);
    }
    return mesh;
}

}  // namespace pathlab::pbrt
