#include "scene/pbrt/shape_meshes.h"

#include <cmath>
#include <string>

#include "core/error.h"

namespace pathlab::pbrt {
namespace {

bool finite(Vec3f p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

// Double precision for the planarity test: the differences of float corners
// are exact in double, so a planar patch far from the origin still tests planar.
struct Vec3d {
    double x, y, z;
};
Vec3d diff(Vec3f a, Vec3f b) {
    return {double(a.x) - b.x, double(a.y) - b.y, double(a.z) - b.z};
}
Vec3d cross(Vec3d a, Vec3d b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double dot(Vec3d a, Vec3d b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
double len(Vec3d a) {
    return std::sqrt(dot(a, a));
}

// Vec3f has pathlab's lerp (core/math.h); Vec2f gets its own here.
Vec2f lerp(float t, Vec2f a, Vec2f b) {
    return {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)};
}

// One patch's corners and their attributes, in pbrt-v4's order 00 10 01 11.
struct Patch {
    Vec3f p[4];
    Vec3f n[4];
    Vec2f uv[4];
    template <typename T>
    static T at(const T (&c)[4], float u, float v) {
        return lerp(v, lerp(u, c[0], c[1]), lerp(u, c[2], c[3]));
    }
};

class PatchMeshBuilder {
  public:
    PatchMeshBuilder(Mesh& mesh, bool normals) : mesh_(mesh), normals_(normals) {}

    uint32_t vertex(const Patch& patch, float u, float v) {
        mesh_.positions.push_back(Patch::at(patch.p, u, v));
        mesh_.uvs.push_back(Patch::at(patch.uv, u, v));
        if (normals_) {
            Vec3f n = Patch::at(patch.n, u, v);
            // Opposite corner normals can cancel; the surface's own normal then.
            if (!(dot(n, n) > 0)) n = surfaceNormal(patch, u, v);
            mesh_.normals.push_back(normalize(n));
        }
        return uint32_t(mesh_.positions.size() - 1);
    }

    // Appends the triangle unless it has (next to) no area relative to the
    // patch: a light's zero-area triangle has no valid sampling density.
    void triangle(uint32_t a, uint32_t b, uint32_t c, double size2) {
        const Vec3d n = cross(diff(mesh_.positions[b], mesh_.positions[a]),
                              diff(mesh_.positions[c], mesh_.positions[a]));
        if (len(n) > 1e-10 * size2) mesh_.indices.insert(mesh_.indices.end(), {a, b, c});
    }

    static Vec3f surfaceNormal(const Patch& q, float u, float v) {
        const Vec3f dpdu = lerp(v, q.p[1] - q.p[0], q.p[3] - q.p[2]);
        const Vec3f dpdv = lerp(u, q.p[2] - q.p[0], q.p[3] - q.p[1]);
        const Vec3f n = cross(dpdu, dpdv);
        return dot(n, n) > 0 ? n : Vec3f(0, 0, 1);
    }

  private:
    Mesh& mesh_;
    bool normals_;
};

}  // namespace

Mesh tessellateDisk(float height, float radius, float innerRadius, float phiMaxDegrees,
                    int segments) {
    if (!std::isfinite(height) || !std::isfinite(radius) || !std::isfinite(innerRadius) ||
        !std::isfinite(phiMaxDegrees))
        throw InputError("disk: a non-finite height, radius, innerradius or phimax");
    if (!(radius > 0) || innerRadius < 0 || innerRadius >= radius)
        throw InputError("disk: needs 0 <= innerradius < radius");
    // pbrt-v4's Disk clamps phimax to [0, 360].
    const float degrees = std::min(phiMaxDegrees, 360.0f);
    if (!(degrees > 0)) throw InputError("disk: phimax must be positive");
    if (segments < 3) throw InputError("disk: needs at least 3 segments");
    const float phiMax = degrees * (kPi / 180);
    // From degrees, so that 90° of 256 is 64 edges, not 65 by a rounding of π.
    const int n = std::max(1, int(std::ceil(double(segments) * degrees / 360 - 1e-6)));

    Mesh mesh;
    mesh.name = "disk";
    const bool annulus = innerRadius > 0;
    // Outer ring j at 2j, inner ring (or, for a full disk, one centre vertex per
    // segment, each with the u of its segment's middle) at 2j + 1. The seam of a
    // full circle has two vertices, u = 0 and u = 1, as pbrt-v4's u jumps there.
    for (int j = 0; j <= n; ++j) {
        const float t = float(j) / float(n);
        const float phi = phiMax * t;
        const float c = std::cos(phi), s = std::sin(phi);
        mesh.positions.push_back({radius * c, radius * s, height});
        mesh.uvs.push_back({t, 0});
        if (annulus) {
            mesh.positions.push_back({innerRadius * c, innerRadius * s, height});
            mesh.uvs.push_back({t, 1});
        } else {
            mesh.positions.push_back({0, 0, height});
            mesh.uvs.push_back({(float(j) + 0.5f) / float(n), 1});
        }
    }
    // Counter-clockwise seen from +z, so each (p1−p0)×(p2−p0) is +z.
    for (uint32_t j = 0; j < uint32_t(n); ++j) {
        const uint32_t o0 = 2 * j, i0 = 2 * j + 1, o1 = 2 * j + 2, i1 = 2 * j + 3;
        if (annulus)
            mesh.indices.insert(mesh.indices.end(), {o0, o1, i1, o0, i1, i0});
        else
            mesh.indices.insert(mesh.indices.end(), {o0, o1, i0});
    }
    return mesh;
}

Mesh bilinearPatchMesh(const std::vector<Vec3f>& positions, const std::vector<uint32_t>& indices,
                       const std::vector<Vec3f>& normals, const std::vector<Vec2f>& uvs,
                       int tessellation) {
    const size_t nv = positions.size();
    if (indices.size() % 4 != 0)
        throw InputError("bilinear patches: " + std::to_string(indices.size()) +
                         " indices, not a multiple of 4");
    for (size_t i = 0; i < indices.size(); ++i)
        if (indices[i] >= nv)
            throw InputError("bilinear patches: index " + std::to_string(indices[i]) +
                             " is out of range (" + std::to_string(nv) + " vertices)");
    if (!normals.empty() && normals.size() != nv)
        throw InputError("bilinear patches: " + std::to_string(normals.size()) + " normals for " +
                         std::to_string(nv) + " vertices");
    if (!uvs.empty() && uvs.size() != nv)
        throw InputError("bilinear patches: " + std::to_string(uvs.size()) + " uvs for " +
                         std::to_string(nv) + " vertices");
    for (size_t i = 0; i < nv; ++i)
        if (!finite(positions[i]))
            throw InputError("bilinear patches: vertex " + std::to_string(i) +
                             " has a non-finite position");
    if (tessellation < 1) throw InputError("bilinear patches: tessellation must be at least 1");

    Mesh mesh;
    mesh.name = "bilinear patches";
    PatchMeshBuilder out(mesh, !normals.empty());
    const int t = tessellation;
    for (size_t k = 0; k < indices.size(); k += 4) {
        Patch q;
        static constexpr Vec2f kCornerUv[4] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
        for (int c = 0; c < 4; ++c) {
            const uint32_t v = indices[k + size_t(c)];
            q.p[c] = positions[v];
            q.n[c] = normals.empty() ? Vec3f() : normals[v];
            q.uv[c] = uvs.empty() ? kCornerUv[c] : uvs[v];
        }
        const Vec3d e10 = diff(q.p[1], q.p[0]), e01 = diff(q.p[2], q.p[0]),
                    e11 = diff(q.p[3], q.p[0]), e1001 = diff(q.p[2], q.p[1]);
        const double size = std::max({len(e10), len(e01), len(e11), len(e1001)});
        const double size2 = size * size;
        // The corners are coplanar when p11 lies in the plane of the other
        // three: the triple product, relative to size³, is (close to) zero.
        const bool planar = std::abs(dot(e11, cross(e10, e01))) <= 1e-6 * size2 * size;
        if (planar) {
            const uint32_t v00 = out.vertex(q, 0, 0), v10 = out.vertex(q, 1, 0),
                           v01 = out.vertex(q, 0, 1), v11 = out.vertex(q, 1, 1);
            // The quad's area vector (its diagonals' cross product): a
            // triangle facing against it lies outside a non-convex quad, and
            // the other diagonal is the one inside.
            const Vec3d area = cross(e11, e1001);
            const bool mainDiagonal =
                dot(cross(e10, e11), area) >= 0 && dot(cross(e11, e01), area) >= 0;
            if (mainDiagonal) {
                out.triangle(v00, v10, v11, size2);
                out.triangle(v00, v11, v01, size2);
            } else {
                out.triangle(v00, v10, v01, size2);
                out.triangle(v10, v11, v01, size2);
            }
            continue;
        }
        // Row-major grid of (t+1)² points; cell (i, j) spans u in [i/t, (i+1)/t].
        const uint32_t first = uint32_t(mesh.positions.size());
        for (int j = 0; j <= t; ++j)
            for (int i = 0; i <= t; ++i) out.vertex(q, float(i) / float(t), float(j) / float(t));
        const uint32_t row = uint32_t(t) + 1;
        for (uint32_t j = 0; j < uint32_t(t); ++j)
            for (uint32_t i = 0; i < uint32_t(t); ++i) {
                const uint32_t a = first + j * row + i;
                out.triangle(a, a + 1, a + row + 1, size2);
                out.triangle(a, a + row + 1, a + row, size2);
            }
    }
    return mesh;
}

}  // namespace pathlab::pbrt
