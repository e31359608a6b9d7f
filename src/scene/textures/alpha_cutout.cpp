#include "scene/textures/alpha_cutout.h"

#include <bit>

#include "core/hash.h"

namespace pathlab {

namespace {

// pbrt-v4's HashFloat(ray.o, ray.d): a value in [0, 1) from the ray alone.
float rayHash(Vec3f o, Vec3f d) {
    const uint64_t h = hashValues(std::bit_cast<uint32_t>(o.x), std::bit_cast<uint32_t>(o.y),
                                  std::bit_cast<uint32_t>(o.z), std::bit_cast<uint32_t>(d.x),
                                  std::bit_cast<uint32_t>(d.y), std::bit_cast<uint32_t>(d.z));
    return float(h >> 40) * 0x1p-24f;
}

void alphaFilter(const RTCFilterFunctionNArguments* args) {
    const auto* cutout = static_cast<const AlphaCutout*>(args->geometryUserPtr);
    const unsigned n = args->N;
    for (unsigned i = 0; i < n; ++i) {
        if (args->valid[i] != -1) continue;
        RTCRayN* ray = args->ray;
        RTCHitN* hit = args->hit;
        const Vec3f o{RTCRayN_org_x(ray, n, i), RTCRayN_org_y(ray, n, i), RTCRayN_org_z(ray, n, i)};
        const Vec3f d{RTCRayN_dir_x(ray, n, i), RTCRayN_dir_y(ray, n, i), RTCRayN_dir_z(ray, n, i)};
        if (!alphaKeepsHit(*cutout, o, d, RTCHitN_primID(hit, n, i), RTCHitN_u(hit, n, i),
                           RTCHitN_v(hit, n, i)))
            args->valid[i] = 0;
    }
}

}  // namespace

bool alphaKeepsHit(const AlphaCutout& cutout, Vec3f o, Vec3f d, unsigned prim, float b1, float b2) {
    const Mesh& mesh = *cutout.mesh;
    const uint32_t* idx = &mesh.indices[3 * size_t(prim)];
    const float b0 = 1 - b1 - b2;
    const Vec3f p =
        mesh.positions[idx[0]] * b0 + mesh.positions[idx[1]] * b1 + mesh.positions[idx[2]] * b2;
    Vec2f uv{0, 0};  // no uvs: as RenderScene
    if (!mesh.uvs.empty()) {
        const Vec2f t0 = mesh.uvs[idx[0]], t1 = mesh.uvs[idx[1]], t2 = mesh.uvs[idx[2]];
        uv = {t0.x * b0 + t1.x * b1 + t2.x * b2, t0.y * b0 + t1.y * b1 + t2.y * b2};
    }
    const float a = evaluateTexture(cutout.scene->shadingTextures, cutout.scene->textures,
                                    mesh.alphaTexture, {uv, p})
                        .x;
    if (a >= 1) return true;
    if (a <= 0) return false;
    return rayHash(o, d) <= a;
}

void attachAlphaFilter(RTCGeometry geom, const AlphaCutout* cutout) {
    rtcSetGeometryUserData(geom, const_cast<AlphaCutout*>(cutout));
    rtcSetGeometryIntersectFilterFunction(geom, alphaFilter);
    rtcSetGeometryOccludedFilterFunction(geom, alphaFilter);
}

}  // namespace pathlab
