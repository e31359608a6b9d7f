#include "scene/pbrt/transform.h"

#include <cmath>

namespace pathlab::pbrt {

Matrix4 Matrix4::translate(double x, double y, double z) {
    Matrix4 r;
    r.m[0][3] = x, r.m[1][3] = y, r.m[2][3] = z;
    return r;
}

Matrix4 Matrix4::scale(double x, double y, double z) {
    Matrix4 r;
    r.m[0][0] = x, r.m[1][1] = y, r.m[2][2] = z;
    return r;
}

Matrix4 Matrix4::rotate(double degrees, double ax, double ay, double az) {
    const double len = std::sqrt(ax * ax + ay * ay + az * az);
    Matrix4 r;
    if (len == 0) return r;
    ax /= len, ay /= len, az /= len;
    const double theta = degrees * 3.14159265358979323846 / 180.0;
    const double s = std::sin(theta), c = std::cos(theta), C = 1 - c;
    // Rodrigues' rotation formula, as PBRT 4th ed. eq. (3.19)'s matrix.
    r.m[0][0] = ax * ax * C + c, r.m[0][1] = ax * ay * C - az * s, r.m[0][2] = ax * az * C + ay * s;
    r.m[1][0] = ax * ay * C + az * s, r.m[1][1] = ay * ay * C + c, r.m[1][2] = ay * az * C - ax * s;
    r.m[2][0] = ax * az * C - ay * s, r.m[2][1] = ay * az * C + ax * s, r.m[2][2] = az * az * C + c;
    return r;
}

std::optional<Matrix4> Matrix4::lookAt(Vec3f eye, Vec3f look, Vec3f up) {
    const double e[3] = {eye.x, eye.y, eye.z};
    double dir[3] = {double(look.x) - eye.x, double(look.y) - eye.y, double(look.z) - eye.z};
    double u[3] = {up.x, up.y, up.z};
    const auto norm = [](double* v) {
        const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        if (l == 0) return false;
        for (int i = 0; i < 3; ++i) v[i] /= l;
        return true;
    };
    const auto cross = [](const double* a, const double* b, double* out) {
        out[0] = a[1] * b[2] - a[2] * b[1];
        out[1] = a[2] * b[0] - a[0] * b[2];
        out[2] = a[0] * b[1] - a[1] * b[0];
    };
    if (!norm(dir) || !norm(u)) return std::nullopt;
    double right[3], newUp[3];
    cross(u, dir, right);
    if (!norm(right)) return std::nullopt;
    cross(dir, right, newUp);
    // world-from-camera has the columns right, newUp, dir, eye; its inverse
    // (an orthonormal frame) is the transpose with the translated origin.
    Matrix4 worldFromCamera;
    for (int i = 0; i < 3; ++i) {
        worldFromCamera.m[i][0] = right[i];
        worldFromCamera.m[i][1] = newUp[i];
        worldFromCamera.m[i][2] = dir[i];
        worldFromCamera.m[i][3] = e[i];
    }
    return worldFromCamera.inverse();
}

Matrix4 Matrix4::fromColumnMajor(const double* v) {
    Matrix4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) r.m[i][j] = v[j * 4 + i];
    return r;
}

Matrix4 operator*(const Matrix4& a, const Matrix4& b) {
    Matrix4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            double s = 0;
            for (int k = 0; k < 4; ++k) s += a.m[i][k] * b.m[k][j];
            r.m[i][j] = s;
        }
    return r;
}

std::optional<Matrix4> Matrix4::inverse() const {
    // Gauss-Jordan elimination with partial pivoting.
    double a[4][8];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) a[i][j] = m[i][j], a[i][j + 4] = i == j ? 1 : 0;
    for (int col = 0; col < 4; ++col) {
        int pivot = col;
        for (int r = col + 1; r < 4; ++r)
            if (std::abs(a[r][col]) > std::abs(a[pivot][col])) pivot = r;
        if (std::abs(a[pivot][col]) < 1e-300 || !std::isfinite(a[pivot][col])) return std::nullopt;
        if (pivot != col)
            for (int j = 0; j < 8; ++j) std::swap(a[col][j], a[pivot][j]);
        const double inv = 1 / a[col][col];
        for (int j = 0; j < 8; ++j) a[col][j] *= inv;
        for (int r = 0; r < 4; ++r) {
            if (r == col || a[r][col] == 0) continue;
            const double f = a[r][col];
            for (int j = 0; j < 8; ++j) a[r][j] -= f * a[col][j];
        }
    }
    Matrix4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) r.m[i][j] = a[i][j + 4];
    return r;
}

bool Matrix4::isAffine() const {
    return m[3][0] == 0 && m[3][1] == 0 && m[3][2] == 0 && m[3][3] == 1;
}

bool Matrix4::swapsHandedness() const {
    const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                       m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    return det < 0;
}

Vec3f Matrix4::point(Vec3f p) const {
    double out[4];
    for (int i = 0; i < 4; ++i) out[i] = m[i][0] * p.x + m[i][1] * p.y + m[i][2] * p.z + m[i][3];
    if (out[3] != 1 && out[3] != 0) out[0] /= out[3], out[1] /= out[3], out[2] /= out[3];
    return {float(out[0]), float(out[1]), float(out[2])};
}

Vec3f Matrix4::vector(Vec3f v) const {
    return {float(m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z),
            float(m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z),
            float(m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z)};
}

Affine Matrix4::toAffine() const {
    Affine a;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) a.m[i][j] = float(m[i][j]);
    a.t = {float(m[0][3]), float(m[1][3]), float(m[2][3])};
    return a;
}

}  // namespace pathlab::pbrt
