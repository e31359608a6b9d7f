#include "render/light_sampling/light_bounds.h"

namespace pathlab {
namespace {

float safeSqrt(float x) {
    return std::sqrt(std::max(0.0f, x));
}
float safeAcos(float x) {
    return std::acos(std::clamp(x, -1.0f, 1.0f));
}

// The angle between unit vectors, accurate for nearly (anti)parallel ones.
float angleBetween(Vec3f a, Vec3f b) {
    if (dot(a, b) < 0) return kPi - 2 * std::asin(std::min(1.0f, length(a + b) / 2));
    return 2 * std::asin(std::min(1.0f, length(b - a) / 2));
}

// v rotated by `angle` about the unit axis k (Rodrigues' formula).
Vec3f rotate(Vec3f v, Vec3f k, float angle) {
    const float c = std::cos(angle), s = std::sin(angle);
    return v * c + cross(k, v) * s + k * (dot(k, v) * (1 - c));
}

// cos(max(0, a − b)) and sin(max(0, a − b)) from the sines and cosines of a
// and b (PBRT 4th ed., eq. 12.26): the angle is clamped at 0 when a < b.
float cosSubClamped(float sinA, float cosA, float sinB, float cosB) {
    if (cosA > cosB) return 1;
    return cosA * cosB + sinA * sinB;
}
float sinSubClamped(float sinA, float cosA, float sinB, float cosB) {
    if (cosA > cosB) return 0;
    return sinA * cosB - cosA * sinB;
}

// cos of the half-angle of the cone from p that holds the box's bounding
// sphere; −1 when p is inside that sphere.
float cosBoundingSphereAngle(const Box3f& b, Vec3f p) {
    const Vec3f c = b.centre();
    const Vec3f d = p - c;
    const float radius2 = dot(b.hi - c, b.hi - c);
    const float dist2 = dot(d, d);
    if (dist2 < radius2) return -1;
    return safeSqrt(1 - radius2 / dist2);
}

}  // namespace

DirectionCone unionCones(const DirectionCone& a, const DirectionCone& b) {
    const float thetaA = safeAcos(a.cosTheta), thetaB = safeAcos(b.cosTheta);
    const float thetaD = angleBetween(a.w, b.w);
    if (std::min(thetaD + thetaB, kPi) <= thetaA) return a;
    if (std::min(thetaD + thetaA, kPi) <= thetaB) return b;
    const float thetaO = (thetaA + thetaD + thetaB) / 2;
    if (thetaO >= kPi) return DirectionCone::entireSphere();
    const Vec3f axis = cross(a.w, b.w);
    if (dot(axis, axis) == 0) return DirectionCone::entireSphere();
    return {normalize(rotate(a.w, normalize(axis), thetaO - thetaA)), std::cos(thetaO)};
}

LightBounds unionBounds(const LightBounds& a, const LightBounds& b) {
    if (a.phi == 0) return b;
    if (b.phi == 0) return a;
    LightBounds u;
    u.bounds = a.bounds;
    u.bounds.extend(b.bounds);
    u.phi = a.phi + b.phi;
    u.normals = unionCones(a.normals, b.normals);
    u.cosThetaE = std::min(a.cosThetaE, b.cosThetaE);
    u.twoSided = a.twoSided || b.twoSided;
    return u;
}

// PBRT 4th ed., §12.6.3, LightBounds::Importance (after Conty Estevez & Kulla
// 2018, eq. 3): phi·cos θ'/d², θ' the smallest angle between the emission cone
// and the direction towards p once the box's angular extent θb is taken off,
// times the receiver's cosine bound cos θ'i.
float LightBounds::importance(Vec3f p, Vec3f n) const {
    const Vec3f c = bounds.centre();
    // Clamped below at half the diagonal so that receivers inside or next to
    // a big box do not get an unbounded weight (as pbrt-v4).
    const float d2 = std::max(dot(p - c, p - c), length(bounds.diagonal()) / 2);
    const Vec3f d = p - c;
    const float dl = length(d);
    const Vec3f wi = dl > 0 ? d / dl : Vec3f(0, 0, 1);
    float cosW = dot(normals.w, wi);
    if (twoSided) cosW = std::abs(cosW);
    const float sinW = safeSqrt(1 - cosW * cosW);
    const float cosB = cosBoundingSphereAngle(bounds, p);
    const float sinB = safeSqrt(1 - cosB * cosB);
    const float cosO = normals.cosTheta, sinO = safeSqrt(1 - cosO * cosO);
    const float cosX = cosSubClamped(sinW, cosW, sinO, cosO);
    const float sinX = sinSubClamped(sinW, cosW, sinO, cosO);
    const float cosThetaP = cosSubClamped(sinX, cosX, sinB, cosB);
    if (cosThetaP <= cosThetaE) return 0;
    float importance = phi * cosThetaP / d2;
    if (n.x != 0 || n.y != 0 || n.z != 0) {
        const float cosI = std::abs(dot(wi, n)), sinI = safeSqrt(1 - cosI * cosI);
        importance *= cosSubClamped(sinI, cosI, sinB, cosB);
    }
    return std::max(importance, 0.0f);
}

}  // namespace pathlab
