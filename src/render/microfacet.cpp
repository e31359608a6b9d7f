#include "render/microfacet.h"

#include "render/sampling_routines.h"

namespace pathlab {

float GgxDistribution::D(Vec3f wm) const {
    // pbrt-v4 eq. 9.16: 1 / (π αx αy cos⁴θ (1 + tan²θ (cos²φ/αx² + sin²φ/αy²))²),
    // with tan²θ cos²φ = x²/z² and tan²θ sin²φ = y²/z².
    const float cos2 = wm.z * wm.z;
    if (cos2 <= 0) return 0;
    const float e = 1 + (wm.x * wm.x / (alphaX * alphaX) + wm.y * wm.y / (alphaY * alphaY)) / cos2;
    return 1 / (kPi * alphaX * alphaY * cos2 * cos2 * e * e);
}

float GgxDistribution::lambda(Vec3f w) const {
    // pbrt-v4 eq. 9.22 with the direction's own alpha² = αx² cos²φ + αy² sin²φ
    // (eq. 9.23): α² tan²θ = (αx² x² + αy² y²) / z².
    const float cos2 = w.z * w.z;
    if (cos2 <= 0) return 0;
    const float a2tan2 = (alphaX * alphaX * w.x * w.x + alphaY * alphaY * w.y * w.y) / cos2;
    return (std::sqrt(1 + a2tan2) - 1) / 2;
}

float GgxDistribution::visibleD(Vec3f w, Vec3f wm) const {
    return G1(w) / absCosTheta(w) * D(wm) * std::abs(dot(w, wm));
}

Vec3f GgxDistribution::sampleVisibleNormal(Vec3f w, Vec2f u) const {
    // Stretch to the unit-roughness configuration (Heitz 2018, sec. 4).
    Vec3f wh = normalize(Vec3f(alphaX * w.x, alphaY * w.y, w.z));
    if (wh.z < 0) wh = -wh;
    const Vec3f t1 = wh.z < 0.99999f ? normalize(cross(Vec3f(0, 0, 1), wh)) : Vec3f(1, 0, 0);
    const Vec3f t2 = cross(wh, t1);
    // A point on the projected hemisphere: a disk whose lower half is squashed.
    const float r = std::sqrt(u.x), phi = 2 * kPi * u.y;
    float px = r * std::cos(phi), py = r * std::sin(phi);
    const float h = std::sqrt(1 - px * px);
    py = (1 - (1 + wh.z) / 2) * h + ((1 + wh.z) / 2) * py;
    const float pz = std::sqrt(std::max(0.0f, 1 - px * px - py * py));
    const Vec3f nh = t1 * px + t2 * py + wh * pz;
    // Unstretch (the normal transforms with the inverse transpose).
    return normalize(Vec3f(alphaX * nh.x, alphaY * nh.y, std::max(1e-6f, nh.z)));
}

}  // namespace pathlab
