#include "render/render_scene.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "core/hash.h"
#include "render/layered/coated_materials.h"
#include "render/sphere_hit.h"
#include "scene/mesh_utils.h"

namespace pathlab {

namespace {

// Whether material m, or a component of it if a mix, has a bump or normal map
// (loaders reject cyclic mixes, so this ends).
bool hasMap(const std::vector<Material>& materials, int m) {
    const Material& mat = materials[size_t(m)];
    if (mat.type == MaterialType::Mix)
        return hasMap(materials, mat.mix[0]) || hasMap(materials, mat.mix[1]);
    return mat.normalMap >= 0 || mat.displacementTexture >= 0;
}

}  // namespace

RenderScene::RenderScene(SceneDescription desc, LightSampling lightSampling)
    : desc_(std::move(desc)) {
    // Embree shares the meshes' positions and indices (the description outlives
    // the accelerator and is not changed after this).
    for (Mesh& mesh : desc_.meshes) reserveForSharing(mesh);
    for (InstancedObject& object : desc_.objects)
        for (Mesh& mesh : object.meshes) reserveForSharing(mesh);
    accel_ = std::make_unique<EmbreeAccel>(desc_);
    const Vec3f lo = accel_->boundsMin(), hi = accel_->boundsMax();
    const float extent = std::max({std::abs(lo.x), std::abs(lo.y), std::abs(lo.z), std::abs(hi.x),
                                   std::abs(hi.y), std::abs(hi.z), 1.0f});
    // Float spacing near the scene's largest coordinate, with a safety factor
    // (setupInstances may raise it).
    epsilon_ = extent * 2e-5f;
    lights_ = std::make_unique<LightSet>(
        desc_, desc_.camera.target, lightSampling,
        parseLightSelection(desc_.defaults.lightSampler, "the light sampler"));
    triangleNormals_.resize(desc_.meshes.size());
    for (size_t m = 0; m < desc_.meshes.size(); ++m)
        triangleNormals_[m] = faceNormals(desc_.meshes[m]);
    for (size_t m = 0; m < desc_.meshes.size(); ++m) {
        const Mesh& mesh = desc_.meshes[m];
        meshHits_.push_back({mesh.indices.data(), triangleNormals_[m].data(),
                             mesh.normals.empty() ? nullptr : mesh.normals.data(),
                             mesh.uvs.empty() ? nullptr : mesh.uvs.data(),
                             lights_->trianglesLights(unsigned(m)), mesh.material});
    }
    for (const Material& m : desc_.materials) {
        lambertian_.push_back(m.type == MaterialType::Diffuse);
        textured_.push_back(m.type != MaterialType::Mix &&
                            (m.albedoTexture >= 0 || m.transmittanceTexture >= 0 ||
                             m.roughnessTexture >= 0 || m.roughnessVTexture >= 0));
        layered_.push_back(coatedBsdf(m));
    }
    for (size_t m = 0; m < desc_.materials.size(); ++m)
        mapped_.push_back(hasMap(desc_.materials, int(m)));
    anyMapped_ = std::any_of(mapped_.begin(), mapped_.end(), [](char c) { return c; });
    allLambertian_ = std::all_of(lambertian_.begin(), lambertian_.end(), [](char c) { return c; });
    setupInstances();
}

int RenderScene::mixComponent(int material, Vec3f p, Vec3f dir, Vec2f uv) const {
    // Loaders reject cyclic mixes, so this ends.
    while (desc_.materials[size_t(material)].type == MaterialType::Mix) {
        const Material& m = desc_.materials[size_t(material)];
        const float amount =
            m.amountTexture < 0
                ? m.amount
                : evaluateTexture(desc_.shadingTextures, desc_.textures, m.amountTexture, {uv, p})
                      .x;
        if (amount <= 0) {
            material = m.mix[0];
        } else if (amount >= 1) {
            material = m.mix[1];
        } else {
            const uint64_t h = hashValues(
                std::bit_cast<uint32_t>(p.x), std::bit_cast<uint32_t>(p.y),
                std::bit_cast<uint32_t>(p.z), std::bit_cast<uint32_t>(dir.x),
                std::bit_cast<uint32_t>(dir.y), std::bit_cast<uint32_t>(dir.z), uint32_t(material));
            const float u = float(h >> 40) * 0x1p-24f;  // in [0, 1)
            material = amount < u ? m.mix[0] : m.mix[1];
        }
    }
    return material;
}

std::vector<Vec3f> faceNormals(const Mesh& mesh) {
    std::vector<Vec3f> normals(mesh.triangleCount());
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
        const Vec3f a = mesh.positions[mesh.indices[3 * t]];
        const Vec3f b = mesh.positions[mesh.indices[3 * t + 1]];
        const Vec3f c = mesh.positions[mesh.indices[3 * t + 2]];
        const Vec3f n = cross(b - a, c - a);
        const float len = length(n);
        normals[t] = len > 0 ? n / len : Vec3f(0, 0, 1);
    }
    return normals;
}

bool RenderScene::intersect(Vec3f o, Vec3f d, SurfaceInteraction* si) const {
    RayHit hit;
    if (!accel_->intersect(o, d, std::numeric_limits<float>::infinity(), &hit)) return false;
    fillInteraction(o, d, hit, si);
    return true;
}

void RenderScene::intersectPacket(Vec3f o, const Vec3f* d, int count, SurfaceInteraction* si,
                                  bool* found) const {
    RayHit hits[kPacketWidth];
    accel_->intersectPacket(o, d, count, hits, found);
    for (int k = 0; k < count; ++k)
        if (found[k]) fillInteraction(o, d[k], hits[k], &si[k]);
}

void RenderScene::intersectLanes(const RayLanes& rays, const int* to, SurfaceInteraction* si,
                                 bool* found) const {
    RayHit hits[kPacketWidth];
    bool laneFound[kPacketWidth];
    accel_->intersectLanes(rays, hits, laneFound);
    for (int k = 0; k < rays.count; ++k) {
        if (!rays.active[k]) continue;
        found[to[k]] = laneFound[k];
        if (laneFound[k])
            fillInteraction({rays.ox[k], rays.oy[k], rays.oz[k]},
                            {rays.dx[k], rays.dy[k], rays.dz[k]}, hits[k], &si[to[k]]);
    }
}

void RenderScene::fillInteraction(Vec3f o, Vec3f d, const RayHit& hit,
                                  SurfaceInteraction* si) const {
    if (hit.instId != RTC_INVALID_GEOMETRY_ID) [[unlikely]] {
        fillInstanced(o, d, hit, si);
        return;
    }
    si->light = -1;
    if (hit.geomId == accel_->sphereGeometryId()) {
        const Sphere& s = desc_.spheres[hit.primId];
        si->p = o + d * sphereHitDistance(o, d, s, hit.t);
        si->ng = si->ns = normalize(si->p - s.center);
        si->uv = {0, 0};
        si->material = s.material;
        si->light = lights_->lightOfSphere(hit.primId);
        if (anyMapped_ && mapped_[size_t(si->material)]) [[unlikely]]
            bumpSphere(s, si->p - s.center, nullptr, d, si);
        return;
    }
    si->p = o + d * hit.t;
    const MeshHitData& mesh = meshHits_[hit.geomId];
    const unsigned* idx = mesh.indices + 3 * size_t(hit.primId);
    const float b1 = hit.u, b2 = hit.v, b0 = 1 - b1 - b2;
    si->ng = mesh.faceNormals[hit.primId];
    si->ns = si->ng;
    if (mesh.vertexNormals) {
        const Vec3f* normals = mesh.vertexNormals;
        const Vec3f n = normals[idx[0]] * b0 + normals[idx[1]] * b1 + normals[idx[2]] * b2;
        const float len = length(n);
        if (len > 0) si->ns = dot(n, si->ng) < 0 ? -n / len : n / len;
    }
    si->uv = {0, 0};
    if (mesh.uvs) {
        const Vec2f t0 = mesh.uvs[idx[0]], t1 = mesh.uvs[idx[1]], t2 = mesh.uvs[idx[2]];
        si->uv = {t0.x * b0 + t1.x * b1 + t2.x * b2, t0.y * b0 + t1.y * b1 + t2.y * b2};
    }
    si->material = mesh.material;
    si->light = mesh.triangleLights[hit.primId];
    if (anyMapped_ && mapped_[size_t(si->material)]) [[unlikely]]
        bumpTriangle(desc_.meshes[hit.geomId], hit.primId, nullptr, d, si);
}

}  // namespace pathlab
