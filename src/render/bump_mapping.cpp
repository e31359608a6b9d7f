#include "render/bump_mapping.h"

#include <algorithm>
#include <cmath>

namespace pathlab {

namespace {

// a·b − c·d with its rounding error compensated (Kahan's algorithm, pbrt-v4's
// DifferenceOfProducts), per component of the vectors.
float differenceOfProducts(float a, float b, float c, float d) {
    const float cd = c * d;
    return std::fma(a, b, -cd) + std::fma(-c, d, cd);
}
Vec3f differenceOfProducts(float a, Vec3f b, float c, Vec3f d) {
    return {differenceOfProducts(a, b.x, c, d.x), differenceOfProducts(a, b.y, c, d.y),
            differenceOfProducts(a, b.z, c, d.z)};
}

// Partial derivatives of a quantity q given at the corners, with respect to
// (u, v): the solution of q_i − q_2 = Δu_i·∂q/∂u + Δv_i·∂q/∂v, i = 0, 1.
// False where the uvs are degenerate (pbrt-v4's threshold).
bool uvDerivatives(const Vec2f (&uv)[3], const Vec3f (&q)[3], Vec3f* dqdu, Vec3f* dqdv) {
    const Vec2f duv02{uv[0].x - uv[2].x, uv[0].y - uv[2].y};
    const Vec2f duv12{uv[1].x - uv[2].x, uv[1].y - uv[2].y};
    const Vec3f dq02 = q[0] - q[2], dq12 = q[1] - q[2];
    const float determinant = differenceOfProducts(duv02.x, duv12.y, duv02.y, duv12.x);
    if (!(std::abs(determinant) >= 1e-9f)) return false;
    const float invDet = 1 / determinant;
    *dqdu = differenceOfProducts(duv12.y, dq02, duv02.y, dq12) * invDet;
    *dqdv = differenceOfProducts(duv02.x, dq12, duv12.x, dq02) * invDet;
    return true;
}

float lengthSquared(Vec3f v) {
    return dot(v, v);
}

}  // namespace

ShadingGeometry triangleShading(const Vec3f (&p)[3], const Vec2f* uvs, const Vec3f* normals,
                                Vec3f ns) {
    Vec2f uv[3] = {{0, 0}, {1, 0}, {1, 1}};
    if (uvs) std::copy(uvs, uvs + 3, uv);
    ShadingGeometry g;
    g.n = ns;
    if (!uvDerivatives(uv, p, &g.dpdu, &g.dpdv) || lengthSquared(cross(g.dpdu, g.dpdv)) == 0) {
        const Frame frame(normalize(cross(p[2] - p[0], p[1] - p[0])));
        g.dpdu = frame.s, g.dpdv = frame.t;
    }
    if (!normals) return g;
    // The tangent perpendicular to the shading normal, and the bitangent
    // ns × tangent (pbrt-v4's ss and ts).
    Vec3f ts = cross(ns, g.dpdu);
    if (lengthSquared(ts) > 0) {
        g.dpdu = cross(ts, ns);
    } else {
        const Frame frame(ns);
        g.dpdu = frame.s, ts = frame.t;
    }
    g.dpdv = ts;
    const Vec3f n[3] = {normals[0], normals[1], normals[2]};
    if (!uvDerivatives(uv, n, &g.dndu, &g.dndv)) {
        const Vec3f dn = cross(n[2] - n[0], n[1] - n[0]);
        if (lengthSquared(dn) == 0) {
            g.dndu = g.dndv = Vec3f(0.0f);
        } else {
            // pbrt-v4's CoordinateSystem of the unnormalised dn.
            const Frame frame(dn);
            g.dndu = frame.s, g.dndv = frame.t;
        }
    }
    return g;
}

ShadingGeometry sphereShading(Vec3f local, float radius) {
    // pbrt-v4's Sphere with zmin = −r, zmax = r, phimax = 2π: θ runs from
    // θ(zmin) = π to θ(zmax) = 0, so ∂p/∂v carries the factor 0 − π.
    constexpr float kPhiMax = 2 * kPi, kThetaRange = -kPi;
    const float zRadius = std::sqrt(local.x * local.x + local.y * local.y);
    const float cosPhi = zRadius > 0 ? local.x / zRadius : 1;
    const float sinPhi = zRadius > 0 ? local.y / zRadius : 0;
    const float cosTheta = std::clamp(local.z / radius, -1.0f, 1.0f);
    const float sinTheta = std::sqrt(std::max(0.0f, 1 - cosTheta * cosTheta));
    ShadingGeometry g;
    g.n = normalize(local);
    g.dpdu = {-kPhiMax * local.y, kPhiMax * local.x, 0};
    g.dpdv = Vec3f(local.z * cosPhi, local.z * sinPhi, -radius * sinTheta) * kThetaRange;
    g.dndu = g.dpdu / radius;
    g.dndv = g.dpdv / radius;
    return g;
}

Vec3f normalMapNormal(const Texture& map, Vec2f uv, const ShadingGeometry& g) {
    const Vec3f c = lookupImage(map, {uv.x, 1 - uv.y}, TextureWrap::Repeat, false);
    const Vec3f t = c * 2.0f - Vec3f(1.0f);
    // A flat texel read through bilinear weights that sum to 1 only up to
    // rounding gives t.x, t.y of a few ulps: no tilt that float precision
    // could show, so the normal is left as it is.
    constexpr float kFlat = 0x1p-20f;
    if (std::abs(t.x) <= kFlat * t.z && std::abs(t.y) <= kFlat * t.z) return g.n;
    const float tLength = length(t);
    if (!(tLength > 0)) return g.n;
    const Vec3f local = t / tLength;
    // pbrt-v4's Frame::FromXZ(normalize(∂p/∂u), n).
    const Vec3f x = normalize(g.dpdu), y = cross(g.n, x);
    const Vec3f ns = normalize(x * local.x + y * local.y + g.n * local.z);
    // ∂p/∂u made perpendicular to ns (Gram–Schmidt), ∂p/∂v = ns × ∂p/∂u,
    // each keeping its length; their normal is ns up to rounding, which the
    // cross product reproduces as pbrt-v4 does.
    const Vec3f dpdu = normalize(g.dpdu - ns * dot(g.dpdu, ns)) * length(g.dpdu);
    const Vec3f dpdv = normalize(cross(ns, dpdu)) * length(g.dpdv);
    return normalize(cross(dpdu, dpdv));
}

Vec3f bumpMapNormal(const std::vector<ShadingTexture>& nodes, const std::vector<Texture>& images,
                    int displacement, Vec2f uv, Vec3f p, const ShadingGeometry& g) {
    const auto height = [&](Vec2f at, Vec3f point) {
        return evaluateTexture(nodes, images, displacement, {at, point}).x;
    };
    const float du = kBumpStep, dv = kBumpStep;
    const float d = height(uv, p);
    const float uDisplace = height({uv.x + du, uv.y}, p + g.dpdu * du);
    const float vDisplace = height({uv.x, uv.y + dv}, p + g.dpdv * dv);
    const bool curved = !isBlack(g.dndu) || !isBlack(g.dndv);
    if (uDisplace == d && vDisplace == d && (d == 0 || !curved)) return g.n;
    const Vec3f dpdu = g.dpdu + g.n * ((uDisplace - d) / du) + g.dndu * d;
    const Vec3f dpdv = g.dpdv + g.n * ((vDisplace - d) / dv) + g.dndv * d;
    const Vec3f n = cross(dpdu, dpdv);
    if (!(lengthSquared(n) > 0)) return g.n;
    return normalize(n);
}

}  // namespace pathlab
