// Small vector math for the renderer: float 3-vectors, 2-vectors and an
// orthonormal frame. Kept header-only so hot loops inline.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace pathlab {

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 0.31830988618379067154f;
inline constexpr float kInv2Pi = 0.15915494309189533577f;
inline constexpr float kInv4Pi = 0.07957747154594766788f;
// The largest float below one: every sample value is clamped to [0, kOneMinusEpsilon].
inline constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

struct Vec2f {
    float x = 0, y = 0;
};
struct Vec2i {
    int x = 0, y = 0;
};

struct Vec3f {
    float x = 0, y = 0, z = 0;
    constexpr Vec3f() = default;
    constexpr Vec3f(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
    constexpr explicit Vec3f(float v) : x(v), y(v), z(v) {}
    constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr Vec3f operator-() const { return {-x, -y, -z}; }
    constexpr Vec3f& operator+=(const Vec3f& o) {
        x += o.x, y += o.y, z += o.z;
        return *this;
    }
    constexpr Vec3f& operator*=(const Vec3f& o) {
        x *= o.x, y *= o.y, z *= o.z;
        return *this;
    }
    constexpr Vec3f& operator*=(float s) {
        x *= s, y *= s, z *= s;
        return *this;
    }
};

constexpr Vec3f operator+(Vec3f a, Vec3f b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
constexpr Vec3f operator-(Vec3f a, Vec3f b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
constexpr Vec3f operator*(Vec3f a, Vec3f b) {
    return {a.x * b.x, a.y * b.y, a.z * b.z};
}
constexpr Vec3f operator*(Vec3f a, float s) {
    return {a.x * s, a.y * s, a.z * s};
}
constexpr Vec3f operator*(float s, Vec3f a) {
    return a * s;
}
constexpr Vec3f operator/(Vec3f a, float s) {
    return a * (1.0f / s);
}
constexpr float dot(Vec3f a, Vec3f b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
constexpr Vec3f cross(Vec3f a, Vec3f b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(Vec3f a) {
    return std::sqrt(dot(a, a));
}
inline Vec3f normalize(Vec3f a) {
    return a / length(a);
}
constexpr float maxComponent(Vec3f a) {
    return std::max(a.x, std::max(a.y, a.z));
}
constexpr float luminance(Vec3f c) {
    return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}
// Without short-circuits: one branch on the result instead of one per component.
constexpr bool isBlack(Vec3f c) {
    return (c.x == 0) & (c.y == 0) & (c.z == 0);
}
inline bool isFinite(Vec3f c) {
    return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z);
}
constexpr Vec3f lerp(float t, Vec3f a, Vec3f b) {
    return a * (1 - t) + b * t;
}

// An orthonormal basis around a unit normal (Duff et al. 2017, "Building an
// Orthonormal Basis, Revisited"): branchless and free of the singularity of
// cross-product constructions.
struct Frame {
    Vec3f s, t, n;
    Frame() = default;
    explicit Frame(Vec3f normal) : n(normal) {
        const float sign = std::copysign(1.0f, n.z);
        const float a = -1.0f / (sign + n.z);
        const float b = n.x * n.y * a;
        s = {1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x};
        t = {b, sign + n.y * n.y * a, -n.y};
    }
    Vec3f toLocal(Vec3f v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
    Vec3f toWorld(Vec3f v) const { return s * v.x + t * v.y + n * v.z; }
};

// Local shading-space helpers: the normal is +z.
inline float cosTheta(Vec3f w) {
    return w.z;
}
inline float absCosTheta(Vec3f w) {
    return std::abs(w.z);
}
inline bool sameHemisphere(Vec3f a, Vec3f b) {
    return a.z * b.z > 0;
}

inline Vec3f reflect(Vec3f wo, Vec3f n) {
    return -wo + n * (2 * dot(wo, n));
}

}  // namespace pathlab
