// pbrt-v4's transformation directives as 4×4 matrices in double precision
// (pbrt-v4 transform.h; PBRT 4th ed., section 3.9): the current transformation
// matrix is post-multiplied by each directive, so the last one written applies
// to points first.
#pragma once

#include <optional>

#include "core/affine.h"
#include "core/math.h"

namespace pathlab::pbrt {

struct Matrix4 {
    double m[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};

    static Matrix4 translate(double x, double y, double z);
    static Matrix4 scale(double x, double y, double z);
    // Rotation by `degrees` about `axis` (pbrt-v4's Rotate: right-handed about
    // the axis in a right-handed space).
    static Matrix4 rotate(double degrees, double ax, double ay, double az);
    // pbrt-v4's LookAt: camera-from-world, with camera +z towards `look`, +y
    // along `up` made orthogonal, and +x = up × dir (a left-handed frame).
    // nullopt when up is parallel to the view direction or eye equals look.
    static std::optional<Matrix4> lookAt(Vec3f eye, Vec3f look, Vec3f up);
    // The 16 numbers of Transform / ConcatTransform, which pbrt-v4 reads in
    // column-major order (the transpose of its row-major matrix).
    static Matrix4 fromColumnMajor(const double* v);

    friend Matrix4 operator*(const Matrix4& a, const Matrix4& b);
    std::optional<Matrix4> inverse() const;  // nullopt when singular
    bool isAffine() const;                   // last row (0, 0, 0, 1)
    bool swapsHandedness() const;            // the upper 3×3 has a negative determinant
    Vec3f point(Vec3f p) const;              // with the homogeneous divide
    Vec3f vector(Vec3f v) const;
    Affine toAffine() const;  // the affine part (only meaningful when isAffine())
};

}  // namespace pathlab::pbrt
