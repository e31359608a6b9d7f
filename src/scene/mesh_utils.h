// Small geometry helpers shared by the scene loaders: building meshes out of
// triangles and quads, bounds, transforms.
#pragma once

#include <limits>

#include "core/affine.h"
#include "scene/scene.h"

namespace pathlab {

struct Bounds3f {
    Vec3f lo{std::numeric_limits<float>::infinity()};
    Vec3f hi{-std::numeric_limits<float>::infinity()};
    void extend(Vec3f p) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    bool empty() const { return lo.x > hi.x; }
    Vec3f center() const { return (lo + hi) * 0.5f; }
    Vec3f extent() const { return hi - lo; }
};

Bounds3f meshBounds(const Mesh& mesh);
// An object's meshes (their referenced vertices) and spheres, in object space.
Bounds3f objectBounds(const InstancedObject& object);
// The box around `b` carried by `xf`: its eight corners transformed, so it
// holds everything b holds (not tight under rotation).
Bounds3f transformBounds(const Bounds3f& b, const Affine& xf);
// Meshes and spheres together, and every instance of an object (its object
// bounds transformed, see transformBounds).
Bounds3f sceneBounds(const SceneDescription& scene);

// Twice the area's vector: (p1−p0)×(p2−p0); its direction is the triangle's
// front side (the side a one-sided light emits towards).
inline Vec3f triangleNormalArea(Vec3f p0, Vec3f p1, Vec3f p2) {
    return cross(p1 - p0, p2 - p0);
}

// Whether triangle t of `mesh` has area enough to be sampled as part of a
// light: its area vector's length above 10⁻¹² of the mesh's squared extent
// (so a tiny but valid light in millimetres or kilometres is judged alike),
// and finite. `extent2` is dot(e, e) of meshBounds(mesh).extent().
bool lightTriangleHasArea(const Mesh& mesh, size_t t, float extent2);

// Turns every triangle over (swaps its last two vertices): its front side,
// the one (p1−p0)×(p2−p0) points to, becomes its back.
void flipWinding(Mesh& mesh);

// Room for one more element after the positions and the indices (a reallocation
// only when there is none), so that Embree can use them in place rather than
// copy them: it reads a buffer's last element with a 16-byte load.
void reserveForSharing(Mesh& mesh);

// Appends one triangle with its own three vertices.
void appendTriangle(Mesh& mesh, Vec3f p0, Vec3f p1, Vec3f p2);
// Appends a planar quad p0 p1 p2 p3 (in order around its boundary) as the two
// triangles (p0,p1,p2) and (p0,p2,p3): both keep the quad's winding, so a
// quad's front side is that of (p1−p0)×(p2−p0).
void appendQuad(Mesh& mesh, Vec3f p0, Vec3f p1, Vec3f p2, Vec3f p3);

// Applies `xf` to positions and normals. A mirroring transform (negative
// determinant) would turn every triangle's front side inside out, so the
// winding is flipped to keep one-sided lights emitting outwards as authored.
void transformMesh(Mesh& mesh, const Affine& xf);

}  // namespace pathlab
