#include "scene/mesh_utils.h"

#include <cmath>
#include <utility>

namespace pathlab {

Bounds3f meshBounds(const Mesh& mesh) {
    Bounds3f b;
    for (const Vec3f& p : mesh.positions) b.extend(p);
    return b;
}

namespace {

void extendByShapes(Bounds3f& b, const std::vector<Mesh>& meshes,
                    const std::vector<Sphere>& spheres) {
    for (const Mesh& m : meshes)
        for (uint32_t i : m.indices)
            if (i < m.positions.size()) b.extend(m.positions[i]);
    for (const Sphere& s : spheres) {
        b.extend(s.center - Vec3f(s.radius));
        b.extend(s.center + Vec3f(s.radius));
    }
}

}  // namespace

Bounds3f objectBounds(const InstancedObject& object) {
    Bounds3f b;
    extendByShapes(b, object.meshes, object.spheres);
    return b;
}

Bounds3f transformBounds(const Bounds3f& b, const Affine& xf) {
    Bounds3f out;
    if (b.empty()) return out;
    for (int c = 0; c < 8; ++c)
        out.extend(
            xf.point({c & 1 ? b.hi.x : b.lo.x, c & 2 ? b.hi.y : b.lo.y, c & 4 ? b.hi.z : b.lo.z}));
    return out;
}

Bounds3f sceneBounds(const SceneDescription& scene) {
    Bounds3f b;
    extendByShapes(b, scene.meshes, scene.spheres);
    // Each object's bounds once, not once per instance: a forest of a million
    // instances of one tree costs a million corner transforms, not a million
    // walks over the tree's vertices.
    std::vector<Bounds3f> objects;
    objects.reserve(scene.objects.size());
    for (const InstancedObject& o : scene.objects) objects.push_back(objectBounds(o));
    for (const ObjectInstance& inst : scene.instances) {
        if (inst.object < 0 || size_t(inst.object) >= objects.size()) continue;
        const Bounds3f ib = transformBounds(objects[size_t(inst.object)], inst.objectToWorld);
        if (!ib.empty()) b.extend(ib.lo), b.extend(ib.hi);
    }
    return b;
}

void appendTriangle(Mesh& mesh, Vec3f p0, Vec3f p1, Vec3f p2) {
    const auto base = static_cast<uint32_t>(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), {p0, p1, p2});
    mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2});
}

void appendQuad(Mesh& mesh, Vec3f p0, Vec3f p1, Vec3f p2, Vec3f p3) {
    const auto base = static_cast<uint32_t>(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), {p0, p1, p2, p3});
    mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

void transformMesh(Mesh& mesh, const Affine& xf) {
    for (Vec3f& p : mesh.positions) p = xf.point(p);
    for (Vec3f& n : mesh.normals) n = xf.normal(n);
    if (xf.determinant() < 0) flipWinding(mesh);
}

void reserveForSharing(Mesh& mesh) {
    mesh.positions.reserve(mesh.positions.size() + 1);
    mesh.indices.reserve(mesh.indices.size() + 1);
}

void flipWinding(Mesh& mesh) {
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
        std::swap(mesh.indices[i + 1], mesh.indices[i + 2]);
}

bool lightTriangleHasArea(const Mesh& mesh, size_t t, float extent2) {
    const float a = length(triangleNormalArea(mesh.positions[mesh.indices[3 * t]],
                                              mesh.positions[mesh.indices[3 * t + 1]],
                                              mesh.positions[mesh.indices[3 * t + 2]]));
    return a > 1e-12f * extent2 && std::isfinite(a);
}

}  // namespace pathlab
