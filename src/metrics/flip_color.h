// Colour spaces used by FLIP (Andersson et al., "FLIP: A Difference Evaluator
// for Alternating Images", HPG 2020, colour pipeline): linear sRGB → CIE XYZ
// (D65) → the linear opponent space YyCxCz, in which the contrast sensitivity
// filters are applied, and back to CIE L*a*b*, where the Hunt adjustment and
// the HyAB distance are computed.
//
// Everything is single precision and evaluated in a fixed order, so results
// are reproducible and agree closely with NVIDIA's reference implementation,
// which also works in 32-bit floats.
#pragma once

#include <algorithm>
#include <cmath>

namespace pathlab::flip {

struct Color {
    float x = 0, y = 0, z = 0;
};

// Linear sRGB (D65) → XYZ. The matrix of the sRGB primaries (IEC 61966-2-1)
// written as ratios of integers, evaluated in float.
inline Color linearRgbToXyz(Color c) {
    constexpr float m00 = 10135552.0f / 24577794.0f, m01 = 8788810.0f / 24577794.0f,
                    m02 = 4435075.0f / 24577794.0f;
    constexpr float m10 = 2613072.0f / 12288897.0f, m11 = 8788810.0f / 12288897.0f,
                    m12 = 887015.0f / 12288897.0f;
    constexpr float m20 = 1425312.0f / 73733382.0f, m21 = 8788810.0f / 73733382.0f,
                    m22 = 70074185.0f / 73733382.0f;
    return {m00 * c.x + m01 * c.y + m02 * c.z, m10 * c.x + m11 * c.y + m12 * c.z,
            m20 * c.x + m21 * c.y + m22 * c.z};
}

// XYZ → linear sRGB: the inverse of the matrix above to ten significant
// digits, as NVIDIA's reference implementation writes it. The exactly rounded
// inverse differs by ~1e-7 relative, which moves single error-map pixels by up
// to 6e-5; with these digits our FLIP maps match the reference bit for bit.
inline Color xyzToLinearRgb(Color c) {
    constexpr float m00 = 3.241003275f, m01 = -1.537398934f, m02 = -0.498615861f;
    constexpr float m10 = -0.969224334f, m11 = 1.875930071f, m12 = 0.041554224f;
    constexpr float m20 = 0.055639423f, m21 = -0.204011202f, m22 = 1.057148933f;
    return {m00 * c.x + m01 * c.y + m02 * c.z, m10 * c.x + m11 * c.y + m12 * c.z,
            m20 * c.x + m21 * c.y + m22 * c.z};
}

// The D65 white point as XYZ of linear RGB (1,1,1) — the row sums of the
// matrix above, 23359437/24577794 and 80288307/73733382 — and its reciprocal,
// each correctly rounded to float. Both normalise XYZ before YCxCz / L*a*b*.
inline constexpr Color kD65White = {0.9504285454750061f, 1.0f, 1.0889003276824951f};
inline constexpr Color kInvD65White = {1.052156925201416f, 1.0f, 0.9183576703071594f};

// XYZ → YyCxCz (Johnson & Fairchild's linearised CIELAB, used by FLIP so the
// spatial filters act on a linear opponent space).
inline Color xyzToYcxcz(Color c) {
    const float x = c.x * kInvD65White.x, y = c.y * kInvD65White.y, z = c.z * kInvD65White.z;
    return {116.0f * y - 16.0f, 500.0f * (x - y), 200.0f * (y - z)};
}

inline Color ycxczToXyz(Color c) {
    const float y = (c.x + 16.0f) / 116.0f;
    const float cx = c.y / 500.0f, cz = c.z / 200.0f;
    return {(y + cx) * kD65White.x, y * kD65White.y, (y - cz) * kD65White.z};
}

// XYZ → CIE 1976 L*a*b* relative to D65.
inline Color xyzToLab(Color c) {
    constexpr float delta = 6.0f / 29.0f;
    constexpr float deltaCube = delta * delta * delta;
    constexpr float linearSlope = 1.0f / (3.0f * delta * delta);
    constexpr float linearOffset = 4.0f / 29.0f;
    auto f = [&](float t) {
        return t > deltaCube ? std::pow(t, 1.0f / 3.0f) : linearSlope * t + linearOffset;
    };
    const float fx = f(c.x * kInvD65White.x), fy = f(c.y * kInvD65White.y),
                fz = f(c.z * kInvD65White.z);
    return {116.0f * fy - 16.0f, 500.0f * (fx - fy), 200.0f * (fy - fz)};
}

inline Color linearRgbToYcxcz(Color c) {
    return xyzToYcxcz(linearRgbToXyz(c));
}
inline Color linearRgbToLab(Color c) {
    return xyzToLab(linearRgbToXyz(c));
}

// Hunt effect (HPG 2020, colour pipeline): chroma appears weaker at low
// luminance, so a* and b* are scaled by 0.01·L*.
inline Color huntAdjust(Color lab) {
    const float scale = 0.01f * lab.x;
    return {lab.x, scale * lab.y, scale * lab.z};
}

// HyAB distance (Abasi et al. 2020, used by FLIP): city-block distance in
// lightness plus Euclidean distance in the chromatic plane; better than ΔE*ab
// for large colour differences.
inline float hyab(Color a, Color b) {
    const float da = a.y - b.y, db = a.z - b.z;
    return std::fabs(a.x - b.x) + std::sqrt(da * da + db * db);
}

}  // namespace pathlab::flip
