#include "scene/validate.h"

#include <cmath>
#include <sstream>

#include "core/error.h"
#include "scene/mesh_utils.h"

namespace pathlab {
namespace {

std::string str(Vec3f v) {
    std::ostringstream s;
    s << '(' << v.x << ", " << v.y << ", " << v.z << ')';
    return s.str();
}

[[noreturn]] void fail(const std::string& source, const std::string& what) {
    throw InputError(source + ": " + what);
}

bool nonNegativeFinite(Vec3f c) {
    return isFinite(c) && c.x >= 0 && c.y >= 0 && c.z >= 0;
}

void validateCamera(const Camera& c, const std::string& source) {
    if (!isFinite(c.eye) || !isFinite(c.target) || !isFinite(c.up))
        fail(source, "camera has a non-finite eye, target or up");
    const Vec3f forward = c.target - c.eye;
    if (dot(forward, forward) == 0) fail(source, "camera eye equals its target " + str(c.eye));
    const Vec3f side = cross(normalize(forward), c.up);
    if (!(length(side) > 1e-6f * length(c.up)) || dot(c.up, c.up) == 0)
        fail(source, "camera up " + str(c.up) + " is zero or parallel to the view direction");
    if (!(c.fovY > 0 && c.fovY < 180))
        fail(source, "camera fovY must be in (0, 180) degrees, got " + std::to_string(c.fovY));
}

void validateMaterial(const Material& m, size_t textureCount, const std::string& source) {
    const std::string what = "material '" + m.name + "'";
    if (!nonNegativeFinite(m.albedo) || maxComponent(m.albedo) > 1)
        fail(source, what + " has albedo " + str(m.albedo) + " outside [0, 1]");
    if (m.texture < -1 || (m.texture >= 0 && size_t(m.texture) >= textureCount))
        fail(source,
             what + " refers to texture " + std::to_string(m.texture) + " which does not exist");
    if (m.type == MaterialType::Dielectric && !(std::isfinite(m.ior) && m.ior > 0))
        fail(source, what + " has an invalid index of refraction");
    if (m.type == MaterialType::Conductor) {
        if (!nonNegativeFinite(m.eta) || !nonNegativeFinite(m.k))
            fail(source, what + " has a negative or non-finite eta or k");
        if (!(std::isfinite(m.roughness) && m.roughness >= 0))
            fail(source, what + " has an invalid roughness");
    }
}

void validateMesh(const Mesh& mesh, size_t index, size_t materialCount, const std::string& source) {
    const std::string what =
        "mesh '" + (mesh.name.empty() ? std::to_string(index) : mesh.name) + "'";
    const size_t n = mesh.positions.size();
    if (mesh.indices.size() % 3 != 0)
        fail(source, what + " has an index count that is not a multiple of 3");
    if (!mesh.normals.empty() && mesh.normals.size() != n)
        fail(source, what + " has " + std::to_string(mesh.normals.size()) + " normals for " +
                         std::to_string(n) + " vertices");
    if (!mesh.uvs.empty() && mesh.uvs.size() != n)
        fail(source, what + " has " + std::to_string(mesh.uvs.size()) + " UVs for " +
                         std::to_string(n) + " vertices");
    if (mesh.material < 0 || size_t(mesh.material) >= materialCount)
        fail(source, what + " refers to material " + std::to_string(mesh.material) +
                         " which does not exist");
    for (size_t i = 0; i < n; ++i)
        if (!isFinite(mesh.positions[i]))
            fail(source, what + " has a non-finite position at vertex " + std::to_string(i));
    for (size_t i = 0; i < mesh.normals.size(); ++i)
        if (!isFinite(mesh.normals[i]) || dot(mesh.normals[i], mesh.normals[i]) == 0)
            fail(source, what + " has a zero or non-finite normal at vertex " + std::to_string(i));
    for (size_t i = 0; i < mesh.uvs.size(); ++i)
        if (!std::isfinite(mesh.uvs[i].x) || !std::isfinite(mesh.uvs[i].y))
            fail(source, what + " has a non-finite UV at vertex " + std::to_string(i));
    for (size_t i = 0; i < mesh.indices.size(); ++i)
        if (mesh.indices[i] >= n)
            fail(source, what + " has index " + std::to_string(mesh.indices[i]) +
                             " out of range (" + std::to_string(n) + " vertices) in triangle " +
                             std::to_string(i / 3));
    if (!nonNegativeFinite(mesh.emission))
        fail(source, what + " has a negative or non-finite emission " + str(mesh.emission));
    if (!isBlack(mesh.emission)) {
        if (mesh.indices.empty()) fail(source, "light " + what + " has no triangles");
        // Area relative to the squared size of the light, so a tiny but valid
        // light in millimetres or kilometres is judged alike.
        const Vec3f ext = meshBounds(mesh).extent();
        const float scale2 = dot(ext, ext);
        for (size_t t = 0; t < mesh.triangleCount(); ++t) {
            const Vec3f a = triangleNormalArea(mesh.positions[mesh.indices[3 * t]],
                                               mesh.positions[mesh.indices[3 * t + 1]],
                                               mesh.positions[mesh.indices[3 * t + 2]]);
            if (!(length(a) > 1e-12f * scale2) || !std::isfinite(length(a)))
                fail(source, "light " + what + " has a zero-area triangle " + std::to_string(t));
        }
    }
}

}  // namespace

void validateScene(const SceneDescription& scene, const std::string& source) {
    validateCamera(scene.camera, source);
    if (scene.resolution.x <= 0 || scene.resolution.y <= 0)
        fail(source, "resolution must be positive, got " + std::to_string(scene.resolution.x) +
                         "x" + std::to_string(scene.resolution.y));
    if (!nonNegativeFinite(scene.environment))
        fail(source, "environment " + str(scene.environment) + " is negative or non-finite");
    for (const Texture& t : scene.textures)
        if (t.width <= 0 || t.height <= 0 || t.texels.size() != size_t(t.width) * t.height)
            fail(source, "a texture is empty or has the wrong number of texels");
    for (const Material& m : scene.materials) validateMaterial(m, scene.textures.size(), source);
    size_t triangles = 0;
    for (size_t i = 0; i < scene.meshes.size(); ++i) {
        validateMesh(scene.meshes[i], i, scene.materials.size(), source);
        triangles += scene.meshes[i].triangleCount();
    }
    for (size_t i = 0; i < scene.spheres.size(); ++i) {
        const Sphere& s = scene.spheres[i];
        const std::string what = "sphere " + std::to_string(i);
        if (!isFinite(s.center) || !(std::isfinite(s.radius) && s.radius > 0))
            fail(source, what + " has a non-finite centre or a non-positive radius");
        if (s.material < 0 || size_t(s.material) >= scene.materials.size())
            fail(source, what + " refers to material " + std::to_string(s.material) +
                             " which does not exist");
    }
    if (triangles == 0 && scene.spheres.empty()) fail(source, "the scene has no geometry");
}

}  // namespace pathlab
