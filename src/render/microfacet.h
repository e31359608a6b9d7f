// Trowbridge–Reitz (GGX) microfacet distribution, anisotropic with roughness
// alphaX along the shading frame's x axis and alphaY along y (Walter et al.
// 2007, "Microfacet Models for Refraction through Rough Surfaces"; pbrt-v4
// sec. 9.6). Visible normals are sampled by Heitz 2018, "Sampling the GGX
// Distribution of Visible Normals".
#pragma once

#include "core/math.h"

namespace pathlab {

struct GgxDistribution {
    float alphaX, alphaY;
    explicit GgxDistribution(float alpha) : alphaX(alpha), alphaY(alpha) {}
    GgxDistribution(float ax, float ay) : alphaX(ax), alphaY(ay) {}

    // Below this roughness the lobe is numerically a delta (pbrt-v4's
    // EffectivelySmooth): it is treated as a perfect specular interface.
    static constexpr float kSmoothAlpha = 1e-3f;
    bool effectivelySmooth() const { return std::max(alphaX, alphaY) < kSmoothAlpha; }

    // pbrt-v4's RoughnessToAlpha: the user's roughness r is alpha = √r.
    static float roughnessToAlpha(float roughness) { return std::sqrt(roughness); }

    float D(Vec3f wm) const;
    float lambda(Vec3f w) const;
    float G1(Vec3f w) const { return 1 / (1 + lambda(w)); }
    float G(Vec3f wo, Vec3f wi) const { return 1 / (1 + lambda(wo) + lambda(wi)); }
    // Density of normals visible from w (Heitz 2018 eq. 3), with |cos| so that
    // w may lie below the surface.
    float visibleD(Vec3f w, Vec3f wm) const;
    // A normal in the upper hemisphere distributed as visibleD(w, ·) for w
    // flipped to the upper hemisphere.
    Vec3f sampleVisibleNormal(Vec3f w, Vec2f u) const;
};

}  // namespace pathlab
