// Warping functions from the unit square to the domains the renderer samples
// (pbrt-v4, "Sampling Algorithms", ch. A.5; Shirley & Chiu 1997 for the
// concentric disk). Each maps stratified input to stratified output, which is
// what lets a low-discrepancy sampler's structure survive into the image.
#pragma once

#include "core/math.h"

namespace pathlab {

// Shirley–Chiu concentric mapping: area-preserving and low-distortion.
inline Vec2f sampleConcentricDisk(Vec2f u) {
    const float ox = 2 * u.x - 1, oy = 2 * u.y - 1;
    if (ox == 0 && oy == 0) return {0, 0};
    float r, theta;
    if (std::abs(ox) > std::abs(oy)) {
        r = ox;
        theta = (kPi / 4) * (oy / ox);
    } else {
        r = oy;
        theta = kPi / 2 - (kPi / 4) * (ox / oy);
    }
    return {r * std::cos(theta), r * std::sin(theta)};
}

// Malley's method: project the concentric disk onto the hemisphere; pdf cosθ/π.
inline Vec3f sampleCosineHemisphere(Vec2f u) {
    const Vec2f d = sampleConcentricDisk(u);
    const float z = std::sqrt(std::max(0.0f, 1 - d.x * d.x - d.y * d.y));
    return {d.x, d.y, z};
}
inline float cosineHemispherePdf(float cosTheta) { return cosTheta * kInvPi; }

inline Vec3f sampleUniformSphere(Vec2f u) {
    const float z = 1 - 2 * u.x;
    const float r = std::sqrt(std::max(0.0f, 1 - z * z));
    const float phi = 2 * kPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}
inline constexpr float uniformSpherePdf() { return kInv4Pi; }

// Uniform barycentrics on a triangle (Heitz 2019, "A Low-Distortion Map Between
// Triangle and Square"): unlike the square-root map it keeps strata compact.
// Returns (b0, b1); b2 = 1 − b0 − b1.
inline Vec2f sampleUniformTriangle(Vec2f u) {
    float b0, b1;
    if (u.x < u.y) {
        b0 = u.x / 2;
        b1 = u.y - b0;
    } else {
        b1 = u.y / 2;
        b0 = u.x - b1;
    }
    return {b0, b1};
}

// The power heuristic with β = 2 (Veach 1997, eq. 9.13), for one sample from
// each of two strategies with densities fPdf and gPdf.
inline float powerHeuristic(float fPdf, float gPdf) {
    const float f = fPdf * fPdf, g = gPdf * gPdf;
    if (f == 0) return 0;
    if (std::isinf(f)) return 1;
    return f / (f + g);
}

}  // namespace pathlab
