// Affine transforms of points, vectors and normals (scene loaders, instances).
#pragma once

#include "core/math.h"

namespace pathlab {

// An affine transform p ↦ M p + t (row-major 3×3 M).
struct Affine {
    float m[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    Vec3f t{0.0f};

    static Affine translation(Vec3f t);
    static Affine scaling(Vec3f s);
    // Rotation by `degrees` around `axis` (right-handed, Rodrigues' formula).
    static Affine rotation(Vec3f axis, float degrees);
    // (a * b)(p) = a(b(p)).
    friend Affine operator*(const Affine& a, const Affine& b);

    Vec3f point(Vec3f p) const;
    Vec3f vector(Vec3f v) const;
    // Normals transform with the inverse transpose; the result is normalised.
    Vec3f normal(Vec3f n) const;
    float determinant() const;
};

}  // namespace pathlab
