// Scenes for the instancing tests: objects placed by instances, and the same
// scene with every instance flattened into world-space copies (transformMesh),
// which is what the instanced renderer must reproduce.
#pragma once

#include <cmath>
#include <utility>

#include "scene/mesh_utils.h"
#include "scene/scene.h"

namespace pathlab::test {

// A closed, lumpy, deliberately asymmetric blob (a mirror image of it is a
// different shape), wound outwards, with smooth per-vertex normals (area-
// weighted face normals) and UVs: an (n+1)×(n+1) latitude-longitude grid whose
// radius varies with direction.
inline Mesh blobMesh(int n, int material) {
    Mesh m;
    m.name = "blob";
    m.material = material;
    const float pi = 3.14159265f;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
            const float theta = pi * float(i) / float(n), phi = 2 * pi * float(j) / float(n);
            const Vec3f dir{std::sin(theta) * std::cos(phi), std::cos(theta),
                            std::sin(theta) * std::sin(phi)};
            const float r = 0.8f + 0.25f * std::max(dir.x, 0.0f) + 0.1f * std::sin(3 * phi) * dir.y;
            m.positions.push_back(dir * r);
            m.uvs.push_back({float(j) / float(n), float(i) / float(n)});
        }
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const auto a = uint32_t(i * (n + 1) + j), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
            m.indices.insert(m.indices.end(), {a, b, c, b, d, c});
        }
    m.normals.assign(m.positions.size(), Vec3f(0.0f));
    for (size_t t = 0; t < m.triangleCount(); ++t) {
        const uint32_t* v = &m.indices[3 * t];
        const Vec3f n2 =
            triangleNormalArea(m.positions[v[0]], m.positions[v[1]], m.positions[v[2]]);
        for (int k = 0; k < 3; ++k) m.normals[v[k]] = m.normals[v[k]] + n2;
    }
    for (Vec3f& nv : m.normals) nv = normalize(nv);
    return m;
}

// An axis-aligned box [lo, hi] with outward-wound faces, flat shaded.
inline Mesh boxMesh(Vec3f lo, Vec3f hi, int material) {
    Mesh m;
    m.name = "box";
    m.material = material;
    const auto p = [&](int i) {
        return Vec3f(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
    };
    const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& f : faces) appendQuad(m, p(f[0]), p(f[1]), p(f[2]), p(f[3]));
    return m;
}

// A flat n×n vertex grid in the xz plane, 2(n−1)² triangles (the memory test's
// large mesh).
inline Mesh gridMesh(int n) {
    Mesh m;
    m.name = "grid";
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            m.positions.push_back(
                {float(x) / float(n), 0.02f * float((x * 7 + y * 3) % 5) / 5, float(y) / float(n)});
    for (int y = 0; y + 1 < n; ++y)
        for (int x = 0; x + 1 < n; ++x) {
            const auto a = uint32_t(y * n + x), b = a + 1, c = a + uint32_t(n), d = c + 1;
            m.indices.insert(m.indices.end(), {a, b, d, a, d, c});
        }
    return m;
}

// The transforms the instances use: a plain translation, a mirror
// (pbrt-v4's Scale -1 1 1), rotation + translation + non-uniform scale.
inline Affine plainMove() {
    return Affine::translation({-2.2f, 1, 0.3f});
}
inline Affine mirrorMove() {
    return Affine::translation({2.1f, 1, 0}) * Affine::scaling({-1, 1, 1});
}
inline Affine skewMove() {
    return Affine::translation({0.2f, 1.3f, -2.0f}) * Affine::rotation({1, 1, 0.3f}, 35) *
           Affine::scaling({1.5f, 0.6f, 1.1f});
}
// Similarity transforms (uniform scale, possibly mirroring), under which a
// sphere stays a sphere and can be flattened.
inline Affine sphereMove() {
    return Affine::translation({0.5f, 0.6f, 2.0f}) * Affine::rotation({0, 1, 1}, 50) *
           Affine::scaling({0.7f, 0.7f, 0.7f});
}
inline Affine sphereMirrorMove() {
    return Affine::translation({-1.3f, 0.5f, 2.2f}) * Affine::scaling({-0.5f, 0.5f, 0.5f});
}

// A floor and a light at the top level; object 0 (blob + metal box) placed by
// plainMove, mirrorMove and skewMove; object 1 (two spheres) by sphereMove
// and sphereMirrorMove; object 2 defined and never placed.
inline SceneDescription instancedScene() {
    SceneDescription s;
    s.name = "instances";
    s.materials = {Material{"floor", MaterialType::Diffuse, {0.6f, 0.6f, 0.6f}},
                   Material{"red", MaterialType::Diffuse, {0.7f, 0.2f, 0.15f}},
                   Material{"metal", MaterialType::Conductor},
                   Material{"green", MaterialType::Diffuse, {0.2f, 0.6f, 0.25f}}};
    s.materials[2].roughness = 0.3f;
    Mesh floor;
    floor.name = "floor";
    appendQuad(floor, {-6, 0, -6}, {-6, 0, 6}, {6, 0, 6}, {6, 0, -6});
    s.meshes.push_back(floor);
    Mesh light;
    light.name = "light";
    appendQuad(light, {-1, 5, -1}, {1, 5, -1}, {1, 5, 1}, {-1, 5, 1});  // faces −y
    light.emission = Vec3f(12.0f);
    s.meshes.push_back(light);
    s.environment = Vec3f(0.05f);

    InstancedObject thing{
        "thing", {blobMesh(24, 1), boxMesh({0.3f, -0.9f, -0.4f}, {0.9f, -0.5f, 0.1f}, 2)}, {}};
    InstancedObject balls{
        "balls", {}, {Sphere{{0, 0, 0}, 0.6f, 3}, Sphere{{1.0f, 0.2f, 0}, 0.3f, 2}}};
    InstancedObject unused{"unused", {boxMesh({0, 0, 0}, {1, 1, 1}, 1)}, {}};
    s.objects = {thing, balls, unused};
    s.instances = {{0, plainMove()},
                   {0, mirrorMove()},
                   {0, skewMove()},
                   {1, sphereMove()},
                   {1, sphereMirrorMove()}};
    s.camera = Camera{{0, 4, 9}, {0, 1, 0}, {0, 1, 0}, 45};
    s.resolution = {48, 48};
    return s;
}

// The same scene with every instance replaced by world-space copies: meshes
// through transformMesh, spheres moved and scaled (the transforms of sphere
// instances must be similarities).
inline SceneDescription flattened(const SceneDescription& instanced) {
    SceneDescription s = instanced;
    s.objects.clear();
    s.instances.clear();
    for (const ObjectInstance& inst : instanced.instances) {
        const InstancedObject& object = instanced.objects[size_t(inst.object)];
        for (Mesh mesh : object.meshes) {
            transformMesh(mesh, inst.objectToWorld);
            s.meshes.push_back(std::move(mesh));
        }
        const float scale = std::cbrt(std::abs(inst.objectToWorld.determinant()));
        for (Sphere sphere : object.spheres) {
            sphere.center = inst.objectToWorld.point(sphere.center);
            sphere.radius *= scale;
            s.spheres.push_back(sphere);
        }
    }
    return s;
}

}  // namespace pathlab::test
