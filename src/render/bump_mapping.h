// Bump and normal mapping (PBRT 4th ed., section 10.5.2; pbrt-v4's
// materials.h BumpMap and NormalMap): a material's `displacement` (a float
// texture, a height along the shading normal) or `normalmap` (an image of
// tangent-space normals) perturbs the shading normal at each hit. The
// geometric normal is kept: ray origins are still offset along it
// (RenderScene::offsetOrigin), and the perturbed normal is turned to its side.
#pragma once

#include <vector>

#include "core/math.h"
#include "scene/scene.h"

namespace pathlab {

// What a map perturbs: pbrt-v4's SurfaceInteraction::shading — the shading
// normal and the surface's partial derivatives ∂p/∂u, ∂p/∂v, ∂n/∂u, ∂n/∂v.
struct ShadingGeometry {
    Vec3f n, dpdu, dpdv;
    Vec3f dndu{0.0f}, dndv{0.0f};
};

// A triangle's, as pbrt-v4's Triangle::InteractionFromIntersection computes
// it from its corners p, their (u, v) (null: pbrt-v4's (0, 0), (1, 0),
// (1, 1)) and normals (null: none), at the hit whose shading normal is ns:
// ∂p/∂u and ∂p/∂v solve p_i − p_2 = (u_i − u_2)·∂p/∂u + (v_i − v_2)·∂p/∂v
// (an arbitrary frame about the face where the uvs are degenerate); with
// vertex normals the tangent is made perpendicular to ns, ∂p/∂v becomes
// ns × ∂p/∂u, and ∂n/∂u, ∂n/∂v solve the same system for the normals.
ShadingGeometry triangleShading(const Vec3f (&p)[3], const Vec2f* uv, const Vec3f* normals,
                                Vec3f ns);

// A whole sphere's at `local` (the hit minus the centre), as pbrt-v4's Sphere
// in its own unrotated frame: u = φ/2π, v from the south pole (θ = π) to the
// north, and the outward normal's derivatives ∂n/∂u = ∂p/∂u / r (Weingarten).
ShadingGeometry sphereShading(Vec3f local, float radius);

// The step of the finite differences along u and v: pbrt-v4's fallback
// where a hit has no (u, v) differentials, which pathlab does not estimate.
inline constexpr float kBumpStep = 0.0005f;

// The shading normal under a normal map (pbrt-v4's NormalMap): the texel at
// (u, 1 − v), bilinear and repeating, as t = 2c − 1 in the frame (∂p/∂u, n × ∂p/∂u, n),
// and the normal of the ∂p/∂u, ∂p/∂v re-orthogonalised about it. Where the
// map reads (0, 0, 1) — up to a tilt of 2⁻²⁰, the rounding of the bilinear
// weights —, g.n itself (bit for bit: no rounding of a rebuilt frame).
Vec3f normalMapNormal(const Texture& map, Vec2f uv, const ShadingGeometry& g);

// The shading normal under a displacement texture d (pbrt-v4's BumpMap,
// PBRT 4th ed. eq. 10.12): with forward differences of step kBumpStep,
// ∂p'/∂u ≈ ∂p/∂u + (d(u + Δu) − d(u))/Δu · n + d·∂n/∂u, likewise in v, and
// n' = ∂p'/∂u × ∂p'/∂v normalised. The shifted lookups move the point along
// ∂p/∂u (∂p/∂v) too, for spatially mapped textures. Where nothing changes
// (equal displacements, and d = 0 or a flat surface), g.n itself.
Vec3f bumpMapNormal(const std::vector<ShadingTexture>& nodes, const std::vector<Texture>& images,
                    int displacement, Vec2f uv, Vec3f p, const ShadingGeometry& g);

// `n` turned to the side of the geometric normal ng (pbrt-v4's FaceForward
// in SetShadingGeometry when the orientation is not authoritative).
inline Vec3f faceForward(Vec3f n, Vec3f ng) {
    return dot(n, ng) < 0 ? -n : n;
}

}  // namespace pathlab
