// The scene description: what the loaders (built-in scenes, JSON scene files,
// OBJ/MTL, the PMD wolf) produce and the renderer consumes. Plain data, units
// as the source gives them, linear RGB everywhere.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"

namespace pathlab {

// An RGB texture, linear, top row first; looked up with (u,v) where v = 0 is the
// top row (the convention of the wolf's UVs), wrapping.
struct Texture {
    int width = 0, height = 0;
    std::vector<Vec3f> texels;
    Vec3f lookup(Vec2f uv) const;  // bilinear
};

enum class MaterialType {
    Diffuse,     // Lambertian; `albedo`, or `texture` when >= 0
    Mirror,      // ideal specular reflection with reflectance `albedo`
    Dielectric,  // smooth glass: Fresnel-weighted reflection/refraction, index `ior`
    Conductor,   // GGX microfacet metal: complex index `eta` + i `k`, GGX `roughness` (alpha)
};

struct Material {
    std::string name;
    MaterialType type = MaterialType::Diffuse;
    Vec3f albedo{0.8f};
    int texture = -1;  // index into SceneDescription::textures
    float ior = 1.5f;
    Vec3f eta{0.2f, 0.92f, 1.1f};  // gold-ish defaults
    Vec3f k{3.9f, 2.45f, 2.14f};
    float roughness = 0.2f;
};

// A triangle mesh. Normals and UVs are per vertex and optional (empty = flat
// shading / no texture coordinates). A mesh with non-zero `emission` is an area
// light: every triangle emits that radiance from its front side (the side its
// geometric normal, (p1−p0)×(p2−p0), points to), or from both when `twoSided`.
struct Mesh {
    std::string name;
    std::vector<Vec3f> positions;
    std::vector<Vec3f> normals;
    std::vector<Vec2f> uvs;
    std::vector<uint32_t> indices;  // 3 per triangle
    int material = 0;
    Vec3f emission{0.0f};
    bool twoSided = false;
    size_t triangleCount() const { return indices.size() / 3; }
};

struct Sphere {
    Vec3f center;
    float radius = 1;
    int material = 0;
};

// A pinhole camera looking from `eye` towards `target`; `fovY` is the vertical
// field of view in degrees. Image axes: forward = normalize(target − eye),
// image right = normalize(cross(forward, up)), image up = cross(right, forward).
// (So the Cornell box, seen from −z with up +y, has +x on the image's left.)
struct Camera {
    Vec3f eye{0, 0, 0}, target{0, 0, -1}, up{0, 1, 0};
    float fovY = 45;
};

struct SceneDescription {
    std::string name;
    Camera camera;
    Vec2i resolution{512, 512};  // the scene's preferred image size
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<Mesh> meshes;
    std::vector<Sphere> spheres;
    Vec3f environment{0.0f};  // constant radiance arriving from every direction
    std::string credit;       // attribution to show wherever the scene's images appear
};

}  // namespace pathlab
