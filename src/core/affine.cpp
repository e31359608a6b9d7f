#include "core/affine.h"

#include <cmath>

namespace pathlab {

Affine Affine::translation(Vec3f t) {
    Affine a;
    a.t = t;
    return a;
}

Affine Affine::scaling(Vec3f s) {
    Affine a;
    a.m[0][0] = s.x, a.m[1][1] = s.y, a.m[2][2] = s.z;
    return a;
}

Affine Affine::rotation(Vec3f axis, float degrees) {
    const Vec3f k = normalize(axis);
    const double th = double(degrees) * 3.14159265358979323846 / 180.0;
    const float c = float(std::cos(th)), s = float(std::sin(th)), C = 1 - c;
    Affine a;
    a.m[0][0] = c + k.x * k.x * C, a.m[0][1] = k.x * k.y * C - k.z * s,
    a.m[0][2] = k.x * k.z * C + k.y * s;
    a.m[1][0] = k.y * k.x * C + k.z * s, a.m[1][1] = c + k.y * k.y * C,
    a.m[1][2] = k.y * k.z * C - k.x * s;
    a.m[2][0] = k.z * k.x * C - k.y * s, a.m[2][1] = k.z * k.y * C + k.x * s,
    a.m[2][2] = c + k.z * k.z * C;
    return a;
}

Affine operator*(const Affine& a, const Affine& b) {
    Affine r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            r.m[i][j] = a.m[i][0] * b.m[0][j] + a.m[i][1] * b.m[1][j] + a.m[i][2] * b.m[2][j];
    r.t = a.point(b.t);
    return r;
}

Vec3f Affine::vector(Vec3f v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
            m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}

Vec3f Affine::point(Vec3f p) const {
    return vector(p) + t;
}

float Affine::determinant() const {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

Vec3f Affine::normal(Vec3f n) const {
    // M⁻ᵀ has the rows r1×r2, r2×r0, r0×r1 divided by det M. The division only
    // scales, but its sign matters: it keeps the normal on the same side as
    // the geometric normal of the (winding-flipped, see transformMesh) result.
    const Vec3f r0{m[0][0], m[0][1], m[0][2]}, r1{m[1][0], m[1][1], m[1][2]},
        r2{m[2][0], m[2][1], m[2][2]};
    const Vec3f c0 = cross(r1, r2), c1 = cross(r2, r0), c2 = cross(r0, r1);
    Vec3f out{dot(c0, n), dot(c1, n), dot(c2, n)};
    if (determinant() < 0) out = -out;
    return normalize(out);
}

}  // namespace pathlab
