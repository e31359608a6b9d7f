// Wavefront OBJ/MTL meshes through tinyobjloader.
#pragma once

#include <string>

#include "scene/scene.h"

namespace pathlab {

// Appends the OBJ's geometry to `scene`: polygons are triangulated and faces
// grouped into one mesh per MTL material (faces without one share a grey
// diffuse material). The MTL's materials are appended to scene.materials,
// their map_Kd textures to scene.textures. MTL mapping (docs/scene-format.md):
//   Ke > 0                       → the mesh is a one-sided area light (front =
//                                  the face winding's side), radiance Ke
//   Pm ≥ 0.5 (PBR metallic)      → Conductor, normal-incidence reflectance Kd,
//                                  GGX alpha = Pr²
//   illum 4, 6, 7 or 9           → Dielectric, ior Ni (1.5 when Ni ≤ 1)
//   illum 3, 5 or 8 and Ns ≥ 1000 → Mirror, reflectance Ks (1 when Ks = 0)
//   illum 3, 5 or 8, Ns < 1000   → Conductor, reflectance Ks, GGX alpha
//                                  sqrt(2/(Ns+2)) (the Phong–Beckmann match)
//   anything else                → Diffuse with Kd, or map_Kd's texture instead
// A conductor's reflectance R becomes eta = 1, k = 2·sqrt(R/(1−R)), which
// reproduces R at normal incidence. OBJ texture coordinates have v = 0 at the
// bottom; they are flipped to our top-row-first convention. When
// `materialOverride` ≥ 0, every face uses that material instead of the MTL's.
// Throws InputError for a missing file or MTL, a malformed line, a
// non-finite coordinate, an index out of range.
// Returns the number of meshes appended.
size_t appendObj(SceneDescription& scene, const std::string& path, int materialOverride = -1);

}  // namespace pathlab
