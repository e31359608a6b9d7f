// Clarberg's equal-area mapping between the unit square and the sphere
// (P. Clarberg, "Fast Equal-Area Mapping of the (Hemi)Sphere using SIMD",
// JGT 13(3), 2008), the parameterisation of pbrt-v4's image environment maps
// (EqualAreaSquareToSphere): the square [0,1]² folded as an octahedron, the
// upper hemisphere (z > 0) inside the diamond |u|+|v| < 1 of [−1,1]², the lower
// one in the four corners. Equal areas of the square map to equal solid
// angles, so the map's Jacobian is 4π everywhere.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/math.h"

namespace pathlab {

inline Vec3f equalAreaSquareToSphere(Vec2f p) {
    const float u = 2 * p.x - 1, v = 2 * p.y - 1;
    const float au = std::abs(u), av = std::abs(v);
    // Signed distance from the diamond's edge: positive inside (upper
    // hemisphere). r is the radius of the concentric ring the point lies on.
    const float signedDistance = 1 - (au + av);
    const float r = 1 - std::abs(signedDistance);
    // The angle along the ring, within the quadrant: 0 on the u axis, π/2 on v.
    const float phi = (r == 0 ? 1 : (av - au) / r + 1) * float(kPi / 4);
    // z = 1 − r² keeps the area: the ring of radius r holds the cap of area 2π·r².
    const float z = std::copysign(1 - r * r, signedDistance);
    const float s = r * std::sqrt(std::max(0.0f, 2 - r * r));
    return {std::copysign(std::cos(phi), u) * s, std::copysign(std::sin(phi), v) * s, z};
}

// The inverse, for a unit vector.
inline Vec2f equalAreaSphereToSquare(Vec3f d) {
    const float x = std::abs(d.x), y = std::abs(d.y), z = std::abs(d.z);
    const float r = std::sqrt(std::max(0.0f, 1 - z));
    // The angle within the quadrant as a fraction of π/2.
    const float phi = (x == 0 && y == 0) ? 0.0f : std::atan2(y, x) * float(2 / kPi);
    float v = phi * r, u = r - v;
    if (d.z < 0) {  // lower hemisphere: fold into the corner
        std::swap(u, v);
        u = 1 - u;
        v = 1 - v;
    }
    u = std::copysign(u, d.x);
    v = std::copysign(v, d.y);
    return {0.5f * (u + 1), 0.5f * (v + 1)};
}

}  // namespace pathlab
