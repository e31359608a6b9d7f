#include "scene/validate.h"

#include <algorithm>
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

// A pbrt-v4 camera: its frame must span space, its lens and screen make sense.
void validatePbrtCamera(const Camera& c, const std::string& source) {
    if (!isFinite(c.eye) || !isFinite(c.axisX) || !isFinite(c.axisY) || !isFinite(c.axisZ))
        fail(source, "camera has a non-finite position or axis");
    const float volume = std::abs(dot(cross(c.axisX, c.axisY), c.axisZ));
    if (!(volume > 1e-12f * length(c.axisX) * length(c.axisY) * length(c.axisZ)) ||
        !std::isfinite(volume))
        fail(source, "camera transform is singular: its axes do not span space");
    if (c.projection == Projection::Perspective && !(c.fov > 0 && c.fov < 180))
        fail(source, "camera fov must be in (0, 180) degrees, got " + std::to_string(c.fov));
    if (!(c.lensRadius >= 0 && std::isfinite(c.lensRadius)) ||
        !(c.focalDistance > 0 && std::isfinite(c.focalDistance)))
        fail(source, "camera lens radius must be >= 0 and focal distance > 0");
}

void validateCamera(const Camera& c, const std::string& source) {
    if (c.pbrtFrame) return validatePbrtCamera(c, source);
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

void validateCoating(const Material& m, const std::string& what, const std::string& source) {
    const Coating& c = m.coating;
    if (m.type == MaterialType::CoatedConductor &&
        (!nonNegativeFinite(m.eta) || !nonNegativeFinite(m.k)))
        fail(source, what + " has a negative or non-finite eta or k");
    if (!(std::isfinite(c.eta) && c.eta > 0))
        fail(source, what + " has an invalid coating index of refraction");
    if (!(std::isfinite(c.thickness) && c.thickness > 0))
        fail(source, what + " has a coating thickness that is not positive");
    if (!nonNegativeFinite(c.albedo) || maxComponent(c.albedo) > 1)
        fail(source, what + " has coating albedo " + str(c.albedo) + " outside [0, 1]");
    if (!(c.g > -1 && c.g < 1)) fail(source, what + " has a coating g outside (-1, 1)");
    if (c.maxDepth < 1 || c.nSamples < 1)
        fail(source, what + " has a coating maxDepth or samples below 1");
    if (!(std::isfinite(c.roughness) && c.roughness >= 0) || !std::isfinite(c.roughnessV) ||
        !(std::isfinite(m.roughness) && m.roughness >= 0) || !std::isfinite(m.roughnessV))
        fail(source, what + " has an invalid roughness");
}

void validateMaterial(const Material& m, size_t textureCount, size_t materialCount,
                      const std::string& source) {
    const std::string what = "material '" + m.name + "'";
    if (!nonNegativeFinite(m.albedo) || maxComponent(m.albedo) > 1)
        fail(source, what + " has albedo " + str(m.albedo) + " outside [0, 1]");
    if (m.texture < -1 || (m.texture >= 0 && size_t(m.texture) >= textureCount))
        fail(source,
             what + " refers to texture " + std::to_string(m.texture) + " which does not exist");
    if (m.normalMap < -1 || (m.normalMap >= 0 && size_t(m.normalMap) >= textureCount))
        fail(source, what + " refers to normal map " + std::to_string(m.normalMap) +
                         " which does not exist");
    if ((m.normalMap >= 0 || m.displacementTexture >= 0) &&
        (m.type == MaterialType::Mix || m.type == MaterialType::Interface))
        fail(source, what + ": a mix or an interface has no bump or normal map");
    if (m.type == MaterialType::Dielectric && !(std::isfinite(m.ior) && m.ior > 0))
        fail(source, what + " has an invalid index of refraction");
    if (m.type == MaterialType::ThinDielectric && !(std::isfinite(m.ior) && m.ior > 0))
        fail(source, what + " has an invalid index of refraction");
    if (m.type == MaterialType::Conductor) {
        if (!nonNegativeFinite(m.eta) || !nonNegativeFinite(m.k))
            fail(source, what + " has a negative or non-finite eta or k");
    }
    if (m.type == MaterialType::Conductor || m.type == MaterialType::Dielectric) {
        if (!(std::isfinite(m.roughness) && m.roughness >= 0) || !std::isfinite(m.roughnessV))
            fail(source, what + " has an invalid roughness");
    }
    if (m.type == MaterialType::DiffuseTransmission &&
        (!nonNegativeFinite(m.transmittance) || maxComponent(m.transmittance) > 1))
        fail(source, what + " has transmittance " + str(m.transmittance) + " outside [0, 1]");
    if (m.type == MaterialType::CoatedDiffuse || m.type == MaterialType::CoatedConductor)
        validateCoating(m, what, source);
    if (m.type == MaterialType::Mix) {
        for (int c : m.mix)
            if (c < 0 || size_t(c) >= materialCount)
                fail(source,
                     what + " mixes material " + std::to_string(c) + " which does not exist");
        if (!std::isfinite(m.amount)) fail(source, what + " has an invalid amount");
    }
}

// The shading textures form a graph whose inputs come before them (so that
// evaluation ends) and whose images exist; materials refer to existing nodes.
void validateShadingTextures(const SceneDescription& scene, const std::string& source) {
    const auto& nodes = scene.shadingTextures;
    for (size_t i = 0; i < nodes.size(); ++i) {
        const ShadingTexture& n = nodes[i];
        const std::string what = "shading texture " + std::to_string(i);
        const int inputs = n.kind == TextureKind::Mix ? 3
                           : n.kind == TextureKind::Checkerboard || n.kind == TextureKind::Scale
                               ? 2
                               : 0;
        for (int k = 0; k < inputs; ++k)
            if (n.inputs[k] < 0 || size_t(n.inputs[k]) >= i)
                fail(source, what + " has an input that is not an earlier texture");
        if (n.kind == TextureKind::Image &&
            (n.image < 0 || size_t(n.image) >= scene.textures.size()))
            fail(source, what + " refers to an image which does not exist");
    }
    for (const Material& m : scene.materials)
        for (int t : {m.albedoTexture, m.transmittanceTexture, m.roughnessTexture,
                      m.roughnessVTexture, m.amountTexture, m.displacementTexture})
            if (t < -1 || (t >= 0 && size_t(t) >= nodes.size()))
                fail(source, "material '" + m.name + "' refers to shading texture " +
                                 std::to_string(t) + " which does not exist");
    const auto checkAlpha = [&](const Mesh& mesh) {
        if (mesh.alphaTexture < -1 ||
            (mesh.alphaTexture >= 0 && size_t(mesh.alphaTexture) >= nodes.size()))
            fail(source, "mesh '" + mesh.name + "' has an alpha texture which does not exist");
    };
    for (const Mesh& mesh : scene.meshes) checkAlpha(mesh);
    for (const InstancedObject& object : scene.objects)
        for (const Mesh& mesh : object.meshes) checkAlpha(mesh);
}

// `owner` prefixes the mesh's description: "" at the top level, "object 'o' "
// inside an instanced object.
void validateMesh(const Mesh& mesh, size_t index, size_t materialCount, const std::string& source,
                  const std::string& owner = "") {
    const std::string what =
        owner + "mesh '" + (mesh.name.empty() ? std::to_string(index) : mesh.name) + "'";
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
        const Vec3f ext = meshBounds(mesh).extent();
        for (size_t t = 0; t < mesh.triangleCount(); ++t)
            if (!lightTriangleHasArea(mesh, t, dot(ext, ext)))
                fail(source, "light " + what + " has a zero-area triangle " + std::to_string(t));
    }
}

void validateSphere(const Sphere& s, const std::string& what, size_t materialCount,
                    const std::string& source) {
    if (!isFinite(s.center) || !(std::isfinite(s.radius) && s.radius > 0))
        fail(source, what + " has a non-finite centre or a non-positive radius");
    if (s.material < 0 || size_t(s.material) >= materialCount)
        fail(source,
             what + " refers to material " + std::to_string(s.material) + " which does not exist");
    if (!nonNegativeFinite(s.emission))
        fail(source, what + " has a negative or non-finite emission " + str(s.emission));
}

std::string objectName(const SceneDescription& scene, size_t i) {
    const std::string& name = scene.objects[i].name;
    return "object '" + (name.empty() ? std::to_string(i) : name) + "'";
}

// Objects as top-level shapes, minus emission (pbrt-v4 does not support area
// lights in an object either: it warns and the shapes do not emit; here the
// scene is rejected so that no light silently disappears. One emitter per
// instance would make the light set grow with the instance count, the very
// cost instancing avoids); instances refer to an
// object that exists with a finite, invertible transform (the renderer
// inverts it to carry normals and sphere hits to world space). True when some
// instance places some geometry.
bool validateInstancing(const SceneDescription& scene, const std::string& source) {
    for (size_t o = 0; o < scene.objects.size(); ++o) {
        const InstancedObject& object = scene.objects[o];
        const std::string owner = objectName(scene, o);
        for (size_t i = 0; i < object.meshes.size(); ++i) {
            const Mesh& mesh = object.meshes[i];
            if (!isBlack(mesh.emission))
                fail(source,
                     owner + " has an emitting mesh '" +
                         (mesh.name.empty() ? std::to_string(i) : mesh.name) +
                         "': instanced shapes cannot be area lights (pbrt-v4 does not support them "
                         "either)");
            validateMesh(mesh, i, scene.materials.size(), source, owner + " ");
        }
        for (size_t i = 0; i < object.spheres.size(); ++i) {
            if (!isBlack(object.spheres[i].emission))
                fail(source, owner + " has an emitting sphere " + std::to_string(i) +
                                 ": instanced shapes cannot be area lights");
            validateSphere(object.spheres[i], owner + " sphere " + std::to_string(i),
                           scene.materials.size(), source);
        }
    }
    bool geometry = false;
    for (size_t i = 0; i < scene.instances.size(); ++i) {
        const ObjectInstance& inst = scene.instances[i];
        const std::string what = "instance " + std::to_string(i);
        if (inst.object < 0 || size_t(inst.object) >= scene.objects.size())
            fail(source, what + " refers to object " + std::to_string(inst.object) +
                             " which does not exist (" + std::to_string(scene.objects.size()) +
                             " objects)");
        const std::string of = what + " of " + objectName(scene, size_t(inst.object));
        const Affine& xf = inst.objectToWorld;
        double scale = 0;
        for (const auto& row : xf.m)
            for (float v : row) {
                if (!std::isfinite(v)) fail(source, of + " has a non-finite transform");
                scale = std::max(scale, double(std::abs(v)));
            }
        if (!isFinite(xf.t)) fail(source, of + " has a non-finite translation");
        // Relative to the matrix's size, so that an object scaled to
        // millimetres is not taken for a flattened one.
        const auto& m = xf.m;
        const double det =
            double(m[0][0]) * (double(m[1][1]) * m[2][2] - double(m[1][2]) * m[2][1]) -
            double(m[0][1]) * (double(m[1][0]) * m[2][2] - double(m[1][2]) * m[2][0]) +
            double(m[0][2]) * (double(m[1][0]) * m[2][1] - double(m[1][1]) * m[2][0]);
        if (!(std::abs(det) > 1e-12 * scale * scale * scale))
            fail(source,
                 of + " has a singular transform (determinant " + std::to_string(det) + ")");
        const InstancedObject& object = scene.objects[size_t(inst.object)];
        for (const Mesh& mesh : object.meshes) geometry |= mesh.triangleCount() > 0;
        geometry |= !object.spheres.empty();
    }
    return geometry;
}

}  // namespace

void validateScene(const SceneDescription& scene, const std::string& source) {
    validateCamera(scene.camera, source);
    if (scene.resolution.x <= 0 || scene.resolution.y <= 0)
        fail(source, "resolution must be positive, got " + std::to_string(scene.resolution.x) +
                         "x" + std::to_string(scene.resolution.y));
    if (!nonNegativeFinite(scene.environment))
        fail(source, "environment " + str(scene.environment) + " is negative or non-finite");
    for (size_t i = 0; i < scene.punctualLights.size(); ++i) {
        const PunctualLight& l = scene.punctualLights[i];
        const std::string what = "light " + std::to_string(i);
        if (!nonNegativeFinite(l.intensity) || !nonNegativeFinite(l.radiance))
            fail(source, what + " has a negative or non-finite intensity or radiance");
        if (!std::isfinite(l.position.x) || !std::isfinite(l.position.y) ||
            !std::isfinite(l.position.z) || !(std::abs(length(l.direction) - 1) < 1e-3f))
            fail(source,
                 what + " has a non-finite position or a direction that is not a unit vector");
    }
    for (const Texture& t : scene.textures)
        if (t.width <= 0 || t.height <= 0 || t.texels.size() != size_t(t.width) * t.height)
            fail(source, "a texture is empty or has the wrong number of texels");
    for (const Material& m : scene.materials)
        validateMaterial(m, scene.textures.size(), scene.materials.size(), source);
    validateShadingTextures(scene, source);
    size_t triangles = 0;
    for (size_t i = 0; i < scene.meshes.size(); ++i) {
        validateMesh(scene.meshes[i], i, scene.materials.size(), source);
        triangles += scene.meshes[i].triangleCount();
    }
    for (size_t i = 0; i < scene.spheres.size(); ++i)
        validateSphere(scene.spheres[i], "sphere " + std::to_string(i), scene.materials.size(),
                       source);
    const bool instancedGeometry = validateInstancing(scene, source);
    if (triangles == 0 && scene.spheres.empty() && !instancedGeometry)
        fail(source, "the scene has no geometry");
}

}  // namespace pathlab
