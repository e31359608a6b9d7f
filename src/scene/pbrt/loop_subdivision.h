// pbrt-v4's "loopsubdiv" shape: Loop subdivision (Loop 1987) of a triangle
// control mesh, computed with OpenSubdiv's Far API.
#pragma once

#include <cstdint>
#include <vector>

#include "scene/scene.h"

namespace pathlab::pbrt {

// Refines the control mesh (`indices`, 3 per triangle, into `positions`)
// uniformly `levels` times — each level splits every triangle into four, so
// a closed mesh goes from V vertices, E edges, F faces to V + E vertices and
// 4F faces — and moves the finest vertices to their limit positions, with
// the limit surface's normals, as pbrt-v4's LoopSubdivide does. Boundary
// edges are infinitely sharp creases (the boundary is a cubic B-spline curve
// of the boundary vertices alone), as pbrt-v4's boundary rules; corners are
// not pinned. Differences from pbrt-v4: OpenSubdiv uses Loop's own weight
// β(n) = (5/8 − (3/8 + cos(2π/n)/4)²)/n for an interior vertex of valence n
// (pbrt-v4 uses Warren's 3/(8n), the same for n = 6), and the exact limit
// masks. Normals: these point to the side of the triangles' winding, so the
// normals and (p1−p0)×(p2−p0) of the result agree, as everywhere in pathlab.
// (By our reading of pbrt-v4's LoopSubdivide, its one-ring runs clockwise
// about that side, so its Cross(S, T) normals point the other way.)
// Control vertices no triangle uses are left out of the result. Throws
// InputError (without a "loopsubdiv:" prefix, which the caller adds) when the
// index count is not a multiple of 3 or is zero, an index is out of range, a
// triangle repeats a vertex, a position is not finite, levels is outside
// [0, 10] or the result would exceed 2^28 triangles.
Mesh loopSubdivide(const std::vector<Vec3f>& positions, const std::vector<uint32_t>& indices,
                   int levels);

}  // namespace pathlab::pbrt
