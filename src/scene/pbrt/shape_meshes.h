// Triangle meshes for pbrt-v4's analytic shapes that pathlab renders as
// triangles: the disk and the bilinear patch. Both are built in the shape's
// object space; the caller applies the transform and the orientation flags.
#pragma once

#include <cstdint>
#include <vector>

#include "scene/scene.h"

namespace pathlab::pbrt {

// pbrt-v4's "disk": the annulus innerRadius ≤ r ≤ radius, 0 ≤ φ ≤ phiMax in
// the plane z = height. Its front is +z, as pbrt-v4's Disk, whose normal
// cross(∂p/∂u, ∂p/∂v) is +z and which samples with normal (0, 0, 1): every
// triangle's (p1−p0)×(p2−p0) points along +z. UVs are pbrt-v4's: u = φ/phiMax,
// v = (radius − r)/(radius − innerRadius). No normals (the disk is flat, and
// an absent normal leaves the front to the winding, so ReverseOrientation
// keeps working as for pbrt-v4's Disk). `segments` is the number of edges of
// the whole circle; a partial disk gets ceil(segments·phiMax/360) of them. The
// area is then π(r² − ri²)·phiMax/360 times sin(δ)/δ for an edge angle δ.
// phiMax is clamped to [0, 360] as pbrt-v4 does. Throws InputError for
// non-finite values, radius ≤ 0, innerRadius outside [0, radius), phiMax ≤ 0
// or segments < 3.
Mesh tessellateDisk(float height, float radius, float innerRadius, float phiMaxDegrees,
                    int segments);

// pbrt-v4's "bilinearmesh": patches of four vertices given in pbrt-v4's order
// p00 p10 p01 p11, the surface p(u,v) = lerp(v, lerp(u, p00, p10),
// lerp(u, p01, p11)). A planar patch (its four corners coplanar, within 1e-6
// of its size) is two triangles, exactly its surface when it is a
// parallelogram or any planar convex quad: split along p00–p11, as pbrt-v4
// splits a PLY quad, or along p10–p01 where that diagonal lies outside a
// non-convex quad. Any other patch is a tessellation × tessellation grid of
// points on the surface. Either way each triangle faces the side of
// cross(∂p/∂u, ∂p/∂v), pbrt-v4's patch normal (at p00: (p10−p00)×(p01−p00)).
// UVs: `uvs` (one per vertex) interpolated bilinearly, or (u, v) when empty,
// as pbrt-v4. Normals only when `normals` are given (one per vertex), also
// interpolated bilinearly and normalised; otherwise none, so the front stays
// the winding's — pbrt-v4 takes the orientation from N only when N is given.
// Zero-area triangles (a patch with two coincident corners is a triangle)
// are left out. Throws InputError for an index count not a multiple of 4, an
// index out of range, normals or uvs not one per vertex, a non-finite
// position, or tessellation < 1.
Mesh bilinearPatchMesh(const std::vector<Vec3f>& positions, const std::vector<uint32_t>& indices,
                       const std::vector<Vec3f>& normals, const std::vector<Vec2f>& uvs,
                       int tessellation);

}  // namespace pathlab::pbrt
