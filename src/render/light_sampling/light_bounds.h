// What a light BVH knows of a light or of a group of lights: where it is (an
// axis-aligned box), how much it emits (phi), and into which directions — a
// cone of normals around w with spread θo, plus θe, how far past a normal the
// emission reaches (π/2 for a diffuse emitter). This is the light bounds of
// Conty Estevez & Kulla 2018, "Importance Sampling of Many Lights with
// Adaptive Tree Splitting", §4, in the form of pbrt-v4 (Pharr, Jakob &
// Humphreys, PBRT 4th ed., §12.6.3, LightBounds): importance() is an
// upper-bound-like estimate of what the group contributes at a receiver, used
// only as a relative weight between the two children of a node.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/math.h"

namespace pathlab {

struct Box3f {
    Vec3f lo{std::numeric_limits<float>::infinity()}, hi{-std::numeric_limits<float>::infinity()};
    bool empty() const { return lo.x > hi.x; }
    void extend(Vec3f p) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    void extend(const Box3f& b) {
        if (!b.empty()) extend(b.lo), extend(b.hi);
    }
    Vec3f centre() const { return (lo + hi) * 0.5f; }
    Vec3f diagonal() const { return hi - lo; }
    float surfaceArea() const {
        const Vec3f d = diagonal();
        return 2 * (d.x * d.y + d.y * d.z + d.z * d.x);
    }
};

// A cone of directions: every direction within angle acos(cosTheta) of w.
// cosTheta = −1 is the whole sphere.
struct DirectionCone {
    Vec3f w{0, 0, 1};
    float cosTheta = 1;
    static DirectionCone entireSphere() { return {{0, 0, 1}, -1}; }
};

// The smallest cone (of this construction) holding both cones (PBRT 4th ed.,
// §3.9.4, "Bounding directions").
DirectionCone unionCones(const DirectionCone& a, const DirectionCone& b);

struct LightBounds {
    Box3f bounds;
    float phi = 0;  // emitted power (luminance); 0: no light
    DirectionCone normals;
    float cosThetaE = 0;  // cos θe: cos(π/2) for a diffuse emitter
    bool twoSided = false;

    // Importance at receiver p with shading normal n (zero: unknown, no
    // receiver cosine); ≥ 0, and 0 only where the group cannot contribute.
    float importance(Vec3f p, Vec3f n) const;
};

LightBounds unionBounds(const LightBounds& a, const LightBounds& b);

}  // namespace pathlab
