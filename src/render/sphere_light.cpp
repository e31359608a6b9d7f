#include "render/sphere_light.h"

#include <algorithm>
#include <cmath>

#include "render/sampling_routines.h"

namespace pathlab {
namespace {

// The cone's half-angle θmax seen from a receiver at squared distance dc2
// from the centre: sin²θmax = r²/dc², and 1 − cos θmax computed as
// sin²θmax / (1 + cos θmax), which has no cancellation however small the
// cone. (pbrt-v4 switches to the first Taylor term sin²θmax / 2 below 1.5°
// for the same reason; the identity is exact at every size.)
struct Cone {
    float sin2Max, cosMax, oneMinusCosMax;
    Cone(float radius, float dc2) {
        sin2Max = std::min(1.0f, radius * radius / dc2);
        cosMax = std::sqrt(1 - sin2Max);
        oneMinusCosMax = sin2Max / (1 + cosMax);
    }
    float pdf() const { return 1 / (2 * kPi * oneMinusCosMax); }
};

}  // namespace

bool sphereConeExists(Vec3f center, float radius, Vec3f ref) {
    const Vec3f d = center - ref;
    return dot(d, d) > radius * radius * (1 + 1e-4f);
}

SpherePoint sampleSphereCone(Vec3f center, float radius, Vec3f ref, Vec2f u) {
    const Vec3f axis = center - ref;
    const float dc2 = dot(axis, axis), dc = std::sqrt(dc2);
    const Cone cone(radius, dc2);
    // cos θ uniform in [cos θmax, 1] (PBRT 4th ed., eq. A.14): 1 − cos θ =
    // u (1 − cos θmax), and sin²θ = (1 − cos θ)(1 + cos θ), free of the
    // cancellation in 1 − cos²θ.
    const float oneMinusCos = u.x * cone.oneMinusCosMax;
    const float cosTheta = 1 - oneMinusCos;
    const float sin2Theta = oneMinusCos * (2 - oneMinusCos);
    const float sinTheta = std::sqrt(std::max(0.0f, sin2Theta));
    const Vec2f cs = cosSinTurn(u.y);  // the azimuth 2π·u.y around the axis
    const Vec3f dir = Frame(axis / dc).toWorld({sinTheta * cs.x, sinTheta * cs.y, cosTheta});
    // The ray ref + t·dir meets the sphere first at t = dc cos θ − √(r² − dc² sin²θ)
    // (the near root of |ref + t·dir − c|² = r²). With x = sin²θ / sin²θmax ∈
    // [0, 1], dc² sin²θ = r² x, and x = u (1 + cos θ) / (1 + cos θmax): no
    // division of two small numbers.
    const float x = std::min(1.0f, u.x * (2 - oneMinusCos) / (1 + cone.cosMax));
    const float t = dc * cosTheta - radius * std::sqrt(1 - x);
    return {ref + dir * t, cone.pdf()};
}

float sphereConePdf(Vec3f center, float radius, Vec3f ref) {
    const Vec3f axis = center - ref;
    return Cone(radius, dot(axis, axis)).pdf();
}

std::optional<SpherePoint> sampleSphereArea(Vec3f center, float radius, Vec3f ref, Vec2f u) {
    const Vec3f p = center + sampleUniformSphere(u) * radius;
    const float pdf = sphereAreaPdf(center, radius, ref, p);
    if (!(pdf > 0) || std::isinf(pdf)) return std::nullopt;
    return SpherePoint{p, pdf};
}

float sphereAreaPdf(Vec3f center, float radius, Vec3f ref, Vec3f p) {
    const Vec3f d = ref - p;
    const float dist2 = dot(d, d);
    // |cos θ'| = |n·d| / |d| with n = (p − c)/r.
    const float cosLight = std::abs(dot(p - center, d)) / (radius * std::sqrt(dist2));
    if (!(cosLight > 0)) return 0;
    return dist2 / (4 * kPi * radius * radius * cosLight);
}

}  // namespace pathlab
