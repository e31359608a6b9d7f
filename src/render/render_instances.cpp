// RenderScene's instanced objects: the prototypes' hit data, built once per
// object, and hits inside an instance carried to world space.
#include <algorithm>
#include <cmath>

#include "render/render_scene.h"
#include "render/sphere_hit.h"
#include "scene/mesh_utils.h"

namespace pathlab {
namespace {

float maxAbs(Vec3f v) {
    return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

// M⁻¹ in double: validateScene only guarantees det M ≠ 0, and a float
// inverse of an ill-conditioned transform would lose what precision is left.
Affine inverseOf(const Affine& xf) {
    double a[3][3];
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) a[r][c] = xf.m[r][c];
    double cof[3][3];  // cofactors: M⁻¹ = cofᵀ / det
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
            const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
            cof[r][c] = a[r1][c1] * a[r2][c2] - a[r1][c2] * a[r2][c1];
        }
    const double det = a[0][0] * cof[0][0] + a[0][1] * cof[0][1] + a[0][2] * cof[0][2];
    Affine inv;
    double t[3] = {0, 0, 0};
    const double xt[3] = {xf.t.x, xf.t.y, xf.t.z};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
            const double v = cof[c][r] / det;
            inv.m[r][c] = float(v);
            t[r] -= v * xt[c];
        }
    inv.t = {float(t[0]), float(t[1]), float(t[2])};
    return inv;
}

}  // namespace

void RenderScene::setupInstances() {
    const size_t objects = desc_.objects.size();
    objectTriangleNormals_.resize(objects);
    objectMeshHits_.resize(objects);
    std::vector<float> objectExtent(objects, 0.0f);
    for (size_t i = 0; i < objects; ++i) {
        const InstancedObject& object = desc_.objects[i];
        auto& normals = objectTriangleNormals_[i];
        for (const Mesh& mesh : object.meshes) normals.push_back(faceNormals(mesh));
        for (size_t m = 0; m < object.meshes.size(); ++m) {
            const Mesh& mesh = object.meshes[m];
            objectMeshHits_[i].push_back({mesh.indices.data(), normals[m].data(),
                                          mesh.normals.empty() ? nullptr : mesh.normals.data(),
                                          mesh.uvs.empty() ? nullptr : mesh.uvs.data(), nullptr,
                                          mesh.material});
        }
        const Bounds3f b = objectBounds(object);
        if (!b.empty()) objectExtent[i] = std::max(maxAbs(b.lo), maxAbs(b.hi));
    }
    // Embree intersects an instance in object space, where the hit's error is
    // relative to the object's own coordinates; carried to world space it
    // grows with the instance's scale (its longest column: the largest
    // stretch of an axis). The ray's trip into object space adds the error
    // of the translation's magnitude. An object modelled far from its origin
    // and moved back, or modelled small and scaled up, thus needs a larger
    // offset than the world bounds alone suggest (the rule stays that of the
    // top level: 2·10⁻⁵ of the largest coordinate in play).
    float extent = 0;
    instanceFrames_.reserve(desc_.instances.size());
    for (const ObjectInstance& inst : desc_.instances) {
        const Affine inv = inverseOf(inst.objectToWorld);
        InstanceFrame frame{inv, {}, inst.object};
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) frame.normalMatrix[r][c] = inv.m[c][r];
        instanceFrames_.push_back(frame);
        if (objectExtent[size_t(inst.object)] == 0) continue;
        const auto& m = inst.objectToWorld.m;
        float scale = 0;
        for (int c = 0; c < 3; ++c)
            scale = std::max(scale, length(Vec3f(m[0][c], m[1][c], m[2][c])));
        extent = std::max(
            {extent, scale * objectExtent[size_t(inst.object)], maxAbs(inst.objectToWorld.t)});
    }
    epsilon_ = std::max(epsilon_, extent * 2e-5f);
}

namespace {

// A normal through M⁻ᵀ, normalised.
Vec3f toWorldNormal(const float (&n)[3][3], Vec3f v) {
    return normalize(Vec3f(n[0][0] * v.x + n[0][1] * v.y + n[0][2] * v.z,
                           n[1][0] * v.x + n[1][1] * v.y + n[1][2] * v.z,
                           n[2][0] * v.x + n[2][1] * v.y + n[2][2] * v.z));
}

}  // namespace

void RenderScene::fillInstanced(Vec3f o, Vec3f d, const RayHit& hit, SurfaceInteraction* si) const {
    const InstanceFrame& frame = instanceFrames_[accel_->instanceIndex(hit.instId)];
    const auto object = size_t(frame.object);
    si->light = -1;  // instanced shapes never emit (validateScene)
    si->uv = {0, 0};
    if (hit.geomId == accel_->objectSphereGeometryId(object)) {
        // The sphere's quadratic in object space, where it is a sphere (in
        // world space it may be an ellipsoid). Embree transforms the ray the
        // same way without normalising it, so t is the world ray's parameter.
        const Sphere& s = desc_.objects[object].spheres[hit.primId];
        const Vec3f oo = frame.toObject.point(o), od = frame.toObject.vector(d);
        const float t = sphereHitDistance(oo, od, s, hit.t);
        si->p = o + d * t;
        si->ng = si->ns = toWorldNormal(frame.normalMatrix, oo + od * t - s.center);
        si->material = s.material;
        if (anyMapped_ && mapped_[size_t(si->material)]) [[unlikely]]
            bumpSphere(s, oo + od * t - s.center,
                       &desc_.instances[accel_->instanceIndex(hit.instId)].objectToWorld, d, si);
        return;
    }
    si->p = o + d * hit.t;
    const MeshHitData& mesh = objectMeshHits_[object][hit.geomId];
    const unsigned* idx = mesh.indices + 3 * size_t(hit.primId);
    // Barycentrics are invariant under affine maps: Embree's object-space
    // (u, v) are the world triangle's.
    const float b1 = hit.u, b2 = hit.v, b0 = 1 - b1 - b2;
    si->ng = toWorldNormal(frame.normalMatrix, mesh.faceNormals[hit.primId]);
    si->ns = si->ng;
    if (mesh.vertexNormals) {
        // Each vertex normal to world space before interpolating, as a
        // flattened copy (transformMesh) holds them: under a non-uniform
        // scale, normalising then interpolating is not interpolating then
        // normalising.
        const Vec3f* normals = mesh.vertexNormals;
        const Vec3f n = toWorldNormal(frame.normalMatrix, normals[idx[0]]) * b0 +
                        toWorldNormal(frame.normalMatrix, normals[idx[1]]) * b1 +
                        toWorldNormal(frame.normalMatrix, normals[idx[2]]) * b2;
        const float len = length(n);
        if (len > 0) si->ns = dot(n, si->ng) < 0 ? -n / len : n / len;
    }
    if (mesh.uvs) {
        const Vec2f t0 = mesh.uvs[idx[0]], t1 = mesh.uvs[idx[1]], t2 = mesh.uvs[idx[2]];
        si->uv = {t0.x * b0 + t1.x * b1 + t2.x * b2, t0.y * b0 + t1.y * b1 + t2.y * b2};
    }
    si->material = mesh.material;
    if (anyMapped_ && mapped_[size_t(si->material)]) [[unlikely]]
        bumpTriangle(desc_.objects[object].meshes[hit.geomId], hit.primId,
                     &desc_.instances[accel_->instanceIndex(hit.instId)].objectToWorld, d, si);
}

}  // namespace pathlab
