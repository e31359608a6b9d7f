// Warping functions from the unit square to the domains the renderer samples
// (pbrt-v4, "Sampling Algorithms", ch. A.5; Shirley & Chiu 1997 for the
// concentric disk). Each maps stratified input to stratified output, which is
// what lets a low-discrepancy sampler's structure survive into the image.
#pragma once

#include "core/math.h"

namespace pathlab {

// sin and cos of |x| ≤ π/4 by their Taylor series to x^11 and x^12: the
// remainders, (π/4)^13/13! and (π/4)^14/14!, are below 1e-10 — far under a
// float's rounding — and unlike libm's sincosf there is no range reduction
// and no call (sincosf was 3.7% of a render's profile).
inline Vec2f cosSinQuarterPi(float x) {
    const float x2 = x * x;
    float s = -1.0f / 39916800.0f;
    s = s * x2 + 1.0f / 362880.0f;
    s = s * x2 - 1.0f / 5040.0f;
    s = s * x2 + 1.0f / 120.0f;
    s = s * x2 - 1.0f / 6.0f;
    s = s * x2 + 1.0f;
    float c = 1.0f / 479001600.0f;
    c = c * x2 - 1.0f / 3628800.0f;
    c = c * x2 + 1.0f / 40320.0f;
    c = c * x2 - 1.0f / 720.0f;
    c = c * x2 + 1.0f / 24.0f;
    c = c * x2 - 0.5f;
    c = c * x2 + 1.0f;
    return {c, s * x};
}

// cos and sin of 2πt for t in [0, 1]: t is split into the nearest quarter
// turn q/4 and a remainder r = t − q/4 in [−1/8, 1/8] (exact: the two are
// within a factor of two of each other), cosSinQuarterPi gives the remainder's
// angle 2πr, and the quarter turns swap and negate the pair. No libm call, and
// no rounding of a large angle before the reduction.
inline Vec2f cosSinTurn(float t) {
    const int q = int(t * 4 + 0.5f);  // 0…4
    const Vec2f cs = cosSinQuarterPi(2 * kPi * (t - float(q) * 0.25f));
    switch (q & 3) {
        case 0:
            return cs;
        case 1:
            return {-cs.y, cs.x};
        case 2:
            return {-cs.x, -cs.y};
        default:
            return {cs.y, -cs.x};
    }
}

// Shirley–Chiu concentric mapping: area-preserving and low-distortion. The
// angle within a wedge is (π/4)·(ratio of the coordinates), so its cosine
// and sine come from cosSinQuarterPi; the upper/lower wedges are the
// left/right ones turned by π/2 (cos and sin swap). The wedge is chosen by
// selects, not a branch: with random u it is a coin toss per bounce, and its
// misprediction cost more than the arithmetic.
inline Vec2f sampleConcentricDisk(Vec2f u) {
    const float ox = 2 * u.x - 1, oy = 2 * u.y - 1;
    if (ox == 0 && oy == 0) return {0, 0};
    const bool xMajor = std::abs(ox) > std::abs(oy);
    const float r = xMajor ? ox : oy, other = xMajor ? oy : ox;
    const Vec2f cs = cosSinQuarterPi((kPi / 4) * (other / r));
    const float along = xMajor ? cs.x : cs.y, across = xMajor ? cs.y : cs.x;
    return {r * along, r * across};
}

// Malley's method: project the concentric disk onto the hemisphere; pdf cosθ/π.
inline Vec3f sampleCosineHemisphere(Vec2f u) {
    const Vec2f d = sampleConcentricDisk(u);
    const float z = std::sqrt(std::max(0.0f, 1 - d.x * d.x - d.y * d.y));
    return {d.x, d.y, z};
}
inline float cosineHemispherePdf(float cosTheta) {
    return cosTheta * kInvPi;
}

inline Vec3f sampleUniformSphere(Vec2f u) {
    const float z = 1 - 2 * u.x;
    const float r = std::sqrt(std::max(0.0f, 1 - z * z));
    const Vec2f cs = cosSinTurn(u.y);  // of the azimuth 2π·u.y
    return {r * cs.x, r * cs.y, z};
}
inline constexpr float uniformSpherePdf() {
    return kInv4Pi;
}

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

// The density on [0,1] proportional to the linear function (1−x)·a + x·b
// (a, b ≥ 0, not both 0): 2((1−x)a + xb)/(a + b).
inline float linearPdf(float x, float a, float b) {
    if (x < 0 || x > 1) return 0;
    return 2 * ((1 - x) * a + x * b) / (a + b);
}

// Inverts that density's CDF, (a·x(2−x) + b·x²)/(a + b) = u. The quadratic's
// root is written as u(a+b) / (a + √(a² + u(b² − a²))), which has no
// cancellation for a ≈ b (pbrt-v4, "Sampling Algorithms", §A.4.1). Monotone in
// u, so strata stay strata.
inline float sampleLinear(float u, float a, float b) {
    if (u == 0 && a == 0) return 0;
    const float x = u * (a + b) / (a + std::sqrt((1 - u) * a * a + u * b * b));
    return std::min(x, kOneMinusEpsilon);
}

// The bilinear density over [0,1]² with corner values w = (w(0,0), w(1,0),
// w(0,1), w(1,1)), normalised: 4·bilerp(p; w) / Σw.
inline float bilinearPdf(Vec2f p, const float (&w)[4]) {
    if (p.x < 0 || p.x > 1 || p.y < 0 || p.y > 1) return 0;
    const float sum = w[0] + w[1] + w[2] + w[3];
    if (sum == 0) return 1;
    return 4 *
           ((1 - p.x) * (1 - p.y) * w[0] + p.x * (1 - p.y) * w[1] + (1 - p.x) * p.y * w[2] +
            p.x * p.y * w[3]) /
           sum;
}

// Samples it by the marginal in y — linear between the edge sums w00+w10 and
// w01+w11 — then x given y, linear between the edges interpolated at y.
inline Vec2f sampleBilinear(Vec2f u, const float (&w)[4]) {
    const float y = sampleLinear(u.y, w[0] + w[1], w[2] + w[3]);
    const float x = sampleLinear(u.x, (1 - y) * w[0] + y * w[2], (1 - y) * w[1] + y * w[3]);
    return {x, y};
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
