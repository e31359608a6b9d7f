// Alpha cut-outs (pbrt-v4's shape "alpha"; its GeometricPrimitive::Intersect):
// a hit where the mesh's alpha texture is a < 1 is ignored unless a hash of
// the ray, u in [0, 1), is at most a — always ignored where a ≤ 0. The choice
// draws nothing from the sampler and is the same for the same ray whatever
// the thread. Done by Embree filter functions, so closest-hit, shadow and
// packet queries all see through the same holes.
#pragma once

#include <embree3/rtcore.h>

#include "scene/scene.h"

namespace pathlab {

struct AlphaCutout {
    const Mesh* mesh;
    const SceneDescription* scene;  // its shading textures and images
};

// Whether the hit on triangle `prim` at barycentrics (b1, b2) of the ray
// o + t·d survives the cut-out. The texture sees the hit's (u, v) and its
// point in the mesh's own space (world space but inside instances).
bool alphaKeepsHit(const AlphaCutout& cutout, Vec3f o, Vec3f d, unsigned prim, float b1, float b2);

// Sets the intersect and occluded filter functions of `geom` to cut it by
// `cutout` (which must outlive the geometry).
void attachAlphaFilter(RTCGeometry geom, const AlphaCutout* cutout);

}  // namespace pathlab
