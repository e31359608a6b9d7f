// PLY meshes for pbrt-v4's "plymesh" shape, read by a small strict reader of
// our own. docs/pbrt-format.md, "PLY loading", says why not assimp, with
// measurements: assimp 5.2 hangs on a truncated header, aborts on a valid
// binary file whose first data byte is '\n', accepts a truncated ASCII file,
// and takes 2–4× the time and 2.7× the memory on a 1M-triangle mesh.
#pragma once

#include <string>

#include "scene/scene.h"

namespace pathlab::pbrt {

// Reads a PLY file (format ascii, binary_little_endian or binary_big_endian
// 1.0) into a triangle mesh named after the file:
//   - element "vertex": x y z (any scalar type, stored as float); normals
//     when nx ny nz are all present; uvs from the first complete pair of
//     u v, s t, texture_u texture_v, texture_s texture_t (pbrt-v4's order).
//     Other properties (colours, …) are skipped.
//   - element "face": list property "vertex_indices" (or "vertex_index") of
//     an integer type; triangles as they are, a quad (v0 v1 v2 v3) as the two
//     triangles (v0 v1 v2) and (v0 v2 v3), which keep its winding — pbrt-v4's
//     TriQuadMesh::ConvertToOnlyTriangles split. (pbrt-v4 renders a quad as a
//     bilinear patch; for a planar quad that is the same surface.)
//   - any other element is read past and ignored.
// A line without a keyword before the first element is read as a comment
// (Blender 2.4 wrote its credit line so; rply, pbrt-v4's reader, refuses it).
// Throws InputError, one line "PLY file '<path>': <problem>", for a missing or
// unreadable file, a malformed or truncated header or body, a missing vertex
// or face element (a file of points only), a face with other than 3 or 4
// vertices (pbrt-v4 reads only those), an index out of range, a non-finite
// position, normal or uv.
Mesh loadPlyMesh(const std::string& path);

}  // namespace pathlab::pbrt
