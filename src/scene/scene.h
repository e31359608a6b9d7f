// The scene description: what the loaders (built-in scenes, JSON scene files,
// OBJ/MTL, the PMD wolf) produce and the renderer consumes. Plain data, units
// as the source gives them, linear RGB everywhere.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/affine.h"
#include "core/math.h"
#include "scene/environment_image.h"
#include "scene/punctual_light.h"
#include "scene/textures/shading_texture.h"

namespace pathlab {

// An RGB texture, linear, top row first; looked up with (u,v) where v = 0 is the
// top row (the convention of the wolf's UVs), wrapping.
struct Texture {
    int width = 0, height = 0;
    std::vector<Vec3f> texels;
    Vec3f lookup(Vec2f uv) const;  // bilinear
};

enum class MaterialType {
    Diffuse,         // Lambertian; `albedo`, or `texture` when >= 0
    Mirror,          // ideal specular reflection with reflectance `albedo`
    Dielectric,      // glass of index `ior`: smooth, or GGX rough (`roughness`, `roughnessV`)
    Conductor,       // GGX microfacet metal: complex index `eta` + i `k`, GGX `roughness` (alpha)
    ThinDielectric,  // a thin slab of index `ior` (pbrt-v4's thindielectric)
    DiffuseTransmission,  // Lambertian reflection `albedo` and transmission `transmittance`
    Mix,                  // `mix[0]` or `mix[1]`, the latter with probability `amount`
    Interface,            // no surface: rays pass through (pbrt-v4's interface)
    CoatedDiffuse,        // `coating` over a Lambertian base of reflectance `albedo`
    CoatedConductor,      // `coating` over the conductor `eta`, `k`, `roughness`, `roughnessV`
};

// The dielectric coating and the medium under it of pbrt-v4's coateddiffuse
// and coatedconductor (render/layered/layered_bsdf.h).
struct Coating {
    float eta = 1.5f;
    float roughness = 0, roughnessV = -1;  // GGX alphas as Material's
    float thickness = 0.01f;
    Vec3f albedo{0.0f};  // of the medium; black: no scattering, only absorption
    float g = 0;
    int maxDepth = 10;
    int nSamples = 1;
};

struct Material {
    std::string name;
    MaterialType type = MaterialType::Diffuse;
    Vec3f albedo{0.8f};
    int texture = -1;  // index into SceneDescription::textures
    float ior = 1.5f;
    Vec3f eta{0.2f, 0.92f, 1.1f};  // gold-ish defaults
    Vec3f k{3.9f, 2.45f, 2.14f};
    // GGX alpha along the surface's u direction (the shading frame's x), and
    // along v when roughnessV >= 0 (anisotropic); else isotropic. Loaders give
    // a dielectric 0 (smooth) unless the scene says otherwise.
    float roughness = 0.2f;
    float roughnessV = -1;
    Vec3f transmittance{0.25f};
    int mix[2] = {-1, -1};  // material indices
    float amount = 0.5f;
    // Textured parameters: indices into SceneDescription::shadingTextures
    // evaluated at each hit in place of the constants above (-1: the constant).
    // albedoTexture: diffuse and diffusetransmission reflectance (clamped to
    // [0, 1]), a conductor's reflectance (eta 1 and the k that reflects it).
    int albedoTexture = -1;
    int transmittanceTexture = -1;  // diffusetransmission
    float albedoScale = 1;          // diffusetransmission's `scale` on both
    // Roughness along u and v; with remapRoughness the value r becomes the
    // GGX alpha √r (pbrt-v4's RoughnessToAlpha), else it is alpha.
    int roughnessTexture = -1, roughnessVTexture = -1;
    bool remapRoughness = true;
    int amountTexture = -1;  // mix
    Coating coating{};       // CoatedDiffuse, CoatedConductor
    // Bump and normal maps (render/bump_mapping.h), on every type but Mix and
    // Interface: a float shading texture of heights along the shading normal,
    // or an index into SceneDescription::textures holding tangent-space
    // normals as linear RGB (2c − 1); -1: none. A normal map wins over a
    // displacement, as in pbrt-v4.
    int displacementTexture = -1;
    int normalMap = -1;
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
    // A float shading texture (SceneDescription::shadingTextures) cutting the
    // surface out: hits where it is 0 are ignored, where it is a in (0, 1)
    // kept with probability a (pbrt-v4's alpha; scene/textures/alpha_cutout.h).
    // -1: opaque.
    int alphaTexture = -1;
    size_t triangleCount() const { return indices.size() / 3; }
};

// A whole sphere, rendered exactly. With non-zero `emission` it is an area
// light emitting that radiance outwards (both ways when `twoSided`), sampled
// by the cone it subtends (render/sphere_light.h).
struct Sphere {
    Vec3f center;
    float radius = 1;
    int material = 0;
    Vec3f emission{0.0f};
    bool twoSided = false;
};

// How film positions become rays.
enum class Projection { Perspective, Orthographic };

// The camera. pathlab's own scenes give a pinhole looking from `eye` towards
// `target`; `fovY` is the vertical field of view in degrees. Image axes:
// forward = normalize(target − eye), image right = normalize(cross(forward,
// up)), image up = cross(right, forward). (So the Cornell box, seen from −z
// with up +y, has +x on the image's left.)
//
// A pbrt-v4 camera (`pbrtFrame`) gives camera space directly instead: the
// camera-space point (x, y, z) is world eye + x·axisX + y·axisY + z·axisZ, with
// pbrt-v4's convention x = image right, y = image up, z = forward (its
// transforms may mirror or scale the axes; target, up and fovY are then
// unused). The film maps to pbrt-v4's screen window: a perspective camera's
// ray through screen point (sx, sy) has the camera-space direction
// (sx·tan(fov/2), sy·tan(fov/2), 1); an orthographic camera's starts at
// (sx, sy, 0) going +z. A thin lens (lensRadius > 0) focuses at
// focalDistance along z, as pbrt-v4's PerspectiveCamera / OrthographicCamera.
struct Camera {
    Vec3f eye{0, 0, 0}, target{0, 0, -1}, up{0, 1, 0};
    float fovY = 45;

    bool pbrtFrame = false;
    Vec3f axisX{1, 0, 0}, axisY{0, 1, 0}, axisZ{0, 0, 1};
    Projection projection = Projection::Perspective;
    float fov = 90;  // degrees, across the screen window's shorter side [-1, 1]
    // xmin, xmax, ymin, ymax; all zero: pbrt-v4's default from the frame
    // aspect ratio a (a > 1: [-a, a] × [-1, 1], else [-1, 1] × [-1/a, 1/a]).
    float screenWindow[4] = {0, 0, 0, 0};
    float frameAspectRatio = 0;  // 0: the image's width / height
    float lensRadius = 0;        // 0: pinhole
    float focalDistance = 1e6f;
};

// The pixel reconstruction filter, sampled by filter importance sampling as
// pbrt-v4 does (the sample's position is drawn from the filter, weighted by
// f/pdf). Box of radius 0.5 is a uniform position inside the pixel.
enum class FilterType { Box, Gaussian, Triangle, Mitchell, Lanczos };
struct PixelFilter {
    FilterType type = FilterType::Box;
    Vec2f radius{0.5f, 0.5f};
    float sigma = 0.5f;                // gaussian
    float b = 1 / 3.0f, c = 1 / 3.0f;  // mitchell
    float tau = 3;                     // lanczos
};

struct Film {
    PixelFilter filter;
    // Multiplies the image: pbrt-v4's imaging ratio, exposuretime · iso / 100
    // (times the film's `scale`).
    float scale = 1;
    // pbrt-v4's Film "whitebalance" (spectral/white_balance.h): the colour
    // temperature in kelvin of the white the "cie1931" sensor is balanced
    // for, each sample adapted from it to the colour space's white; 0: none.
    float whiteBalance = 0;
    // The part of the image rendered, as fractions xmin, xmax, ymin, ymax of
    // the full resolution (pbrt-v4's cropwindow): the image holds pixels
    // ceil(W·xmin) … ceil(W·xmax) − 1 and likewise in y.
    float cropWindow[4] = {0, 1, 0, 1};
};

// What a scene file asks the renderer for (pbrt-v4's Sampler and Integrator
// directives); the command line overrides each. Unset: the renderer's own.
struct RenderDefaults {
    std::string sampler;      // "" = unset
    int samplesPerPixel = 0;  // 0 = unset
    bool hasSeed = false;
    uint64_t seed = 0;
    int maxDepth = -1;  // -1 = unset
    // How next-event estimation chooses a light: "uniform", "power" or "bvh"
    // (render/light_sampling/light_chooser.h); "" = unset, power. pbrt-v4
    // files have no directive for it (pbrt's --lightsampler is a command-line
    // option); pathlab's JSON key "lightSampler" and --light-sampler set it.
    std::string lightSampler;
};

// A group of shapes defined once (pbrt-v4's ObjectBegin … ObjectEnd) and
// placed any number of times by instances, each with its own transform.
// The renderer builds its geometry once (Embree instances), so memory grows
// with the unique geometry, not the instance count. Instanced shapes do not
// emit (as in pbrt-v4).
struct InstancedObject {
    std::string name;
    std::vector<Mesh> meshes;
    std::vector<Sphere> spheres;
};
struct ObjectInstance {
    int object = 0;  // index into SceneDescription::objects
    Affine objectToWorld;
};

struct SceneDescription {
    std::string name;
    Camera camera;
    Vec2i resolution{512, 512};  // the scene's preferred image size
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<ShadingTexture> shadingTextures;  // what Material's *Texture fields refer to
    std::vector<Mesh> meshes;
    std::vector<Sphere> spheres;
    Vec3f environment{0.0f};                    // constant radiance arriving from every direction
    std::vector<PunctualLight> punctualLights;  // point, spot and distant lights
    EnvironmentImage environmentMap;            // radiance by direction; empty: none
    std::string credit;  // attribution to show wherever the scene's images appear
    Film film;
    RenderDefaults defaults;
    std::vector<InstancedObject> objects;
    std::vector<ObjectInstance> instances;
};

}  // namespace pathlab
