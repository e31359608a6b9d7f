// Where a ray meets a sphere, from the ray alone (RenderScene::fillInteraction
// for top-level and instanced spheres).
#pragma once

#include <cmath>

#include "core/math.h"
#include "scene/scene.h"

namespace pathlab {

// The root of |o + t·d − c|² = r² nearest Embree's t, in double precision.
// Embree's packet and single-ray sphere tests round t differently; taking the
// hit point from the ray alone makes a path's vertices independent of how its
// rays were traced, so the batched integrator's image is the one-at-a-time
// integrator's bit for bit.
inline float sphereHitDistance(Vec3f o, Vec3f d, const Sphere& s, float embreeT) {
    const double ox = double(o.x) - s.center.x, oy = double(o.y) - s.center.y,
                 oz = double(o.z) - s.center.z;
    const double a = double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z;
    const double b = ox * d.x + oy * d.y + oz * d.z;  // half the linear term
    const double c = ox * ox + oy * oy + oz * oz - double(s.radius) * s.radius;
    const double disc = b * b - a * c;
    if (disc < 0) return embreeT;  // a grazing hit Embree found and the quadratic misses
    // The root away from cancellation, and the other as c / (a·t) (Vieta).
    const double q = -(b + std::copysign(std::sqrt(disc), b));
    const double t0 = q / a, t1 = q != 0 ? c / q : t0;
    return float(std::abs(t0 - embreeT) < std::abs(t1 - embreeT) ? t0 : t1);
}

}  // namespace pathlab
