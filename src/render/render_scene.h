// A scene ready to render: the description, its Embree acceleration structure,
// per-triangle normals and the light set. Immutable and shared by all threads.
// Instanced objects keep their prototype's data once (object space); a hit
// inside an instance is carried to world space by that instance's transform
// (render_instances.cpp).
#pragma once

#include <memory>
#include <vector>

#include "render/bsdf.h"
#include "render/bump_mapping.h"
#include "render/layered/layered_bsdf.h"
#include "render/lights.h"
#include "scene/embree_accel.h"
#include "scene/scene.h"

namespace pathlab {

struct SurfaceInteraction {
    Vec3f p;
    Vec3f ng;  // unit geometric normal (mesh winding / sphere outward)
    Vec3f ns;  // unit shading normal, on the same side as ng
    Vec2f uv;
    int material = 0;
    int light = -1;  // area light index when the surface emits
};

// Each triangle's unit geometric normal, (p1−p0)×(p2−p0) normalised; (0, 0, 1)
// for a degenerate one.
std::vector<Vec3f> faceNormals(const Mesh& mesh);

class RenderScene {
  public:
    explicit RenderScene(SceneDescription desc, LightSampling lightSampling = LightSampling::Area);

    const SceneDescription& description() const { return desc_; }
    const LightSet& lights() const { return *lights_; }
    // Closest surface along o + t·d; false when the ray leaves the scene.
    bool intersect(Vec3f o, Vec3f d, SurfaceInteraction* si) const;
    bool occluded(Vec3f o, Vec3f d, float tMax) const { return accel_->occluded(o, d, tMax); }
    // Closest surfaces of up to kPacketWidth coherent rays from one origin
    // (the camera's), traced together; found[k] is false where ray k escapes.
    void intersectPacket(Vec3f o, const Vec3f* d, int count, SurfaceInteraction* si,
                         bool* found) const;
    // Rays of any origins, traced as one packet (EmbreeAccel::intersectLanes,
    // occludedLanes). Active lane k's answer goes to found[to[k]] and, on a
    // hit, si[to[k]] (the batched integrator's path of that lane); blocked[k]
    // is per lane, false where inactive.
    void intersectLanes(const RayLanes& rays, const int* to, SurfaceInteraction* si,
                        bool* found) const;
    void occludedLanes(const RayLanes& rays, bool* blocked) const {
        accel_->occludedLanes(rays, blocked);
    }
    // Every ray traced from now on is also recorded (null stops recording).
    void setRayRecorder(RayRecorder* recorder) { accel_->setRecorder(recorder); }
    const EmbreeAccel& accel() const { return *accel_; }
    // A ray origin nudged off the surface along the geometric normal, on the
    // side of direction w — avoids self-intersection at this scene's scale.
    // (Inline: twice per path vertex.)
    Vec3f offsetOrigin(const SurfaceInteraction& si, Vec3f w) const {
        const Vec3f offset = si.ng * epsilon_;
        return dot(w, si.ng) > 0 ? si.p + offset : si.p - offset;
    }
    // The BSDF at si for a ray arriving along dir (a mix material chooses
    // its component from both; see mixComponent).
    Bsdf bsdfAt(const SurfaceInteraction& si, Vec3f dir) const;
    // Which material a mix material stands for at point p seen along dir:
    // pbrt-v4's MixMaterial::ChooseMaterial, a hash of the point, the
    // direction and the material, so the choice is deterministic per shading
    // point and draws nothing from the sampler. Follows nested mixes.
    // A mix with an `amount` texture evaluates it at (uv, p).
    int mixComponent(int material, Vec3f p, Vec3f dir, Vec2f uv = {0, 0}) const;
    // bsdfAt's albedo where isLambertian(si.material).
    Vec3f lambertianAlbedoAt(const SurfaceInteraction& si) const;
    // The ray-origin offset of offsetOrigin.
    float epsilon() const { return epsilon_; }
    // Whether surfaces of material m are Lambertian, which the batched
    // integrator shades eight at a time (shadeDiffuseBatch), and whether every
    // material is, so that no vertex needs the one-at-a-time shading.
    bool isLambertian(int material) const { return lambertian_[size_t(material)] != 0; }
    bool allLambertian() const { return allLambertian_; }

  private:
    // bsdfAt for a material with textured parameters (textured_): evaluates
    // them at si (textured_materials.cpp). Out of line, so that untextured
    // scenes keep the shading path they had.
    [[gnu::noinline]] Bsdf texturedBsdf(const Material& m, const SurfaceInteraction& si) const;
    [[gnu::noinline]] Vec3f texturedAlbedo(const Material& m, const SurfaceInteraction& si) const;
    void fillInteraction(Vec3f o, Vec3f d, const RayHit& hit, SurfaceInteraction* si) const;
    // si's shading normal perturbed by the bump or normal map of the material
    // bsdfAt will shade it with (bump_shading.cpp), from the geometry of the
    // triangle (placed by `instance` when not null) or sphere hit (`local`:
    // the hit minus the centre, in the sphere's own space). Out of line and
    // cold: scenes without maps keep their hit path.
    [[gnu::noinline]] void bumpTriangle(const Mesh& mesh, unsigned prim, const Affine* instance,
                                        Vec3f d, SurfaceInteraction* si) const;
    [[gnu::noinline]] void bumpSphere(const Sphere& sphere, Vec3f local, const Affine* instance,
                                      Vec3f d, SurfaceInteraction* si) const;
    // The material whose map applies at si seen along d (a mix resolved as
    // bsdfAt resolves it); null where it has none.
    const Material* mappedMaterial(const SurfaceInteraction& si, Vec3f d) const;
    void applyMap(const Material& m, const ShadingGeometry& g, SurfaceInteraction* si) const;
    // fillInteraction for a hit inside an instance. Out of line and cold, so
    // that scenes without instances keep the hit path they had.
    [[gnu::noinline]] void fillInstanced(Vec3f o, Vec3f d, const RayHit& hit,
                                         SurfaceInteraction* si) const;
    // The instances' transforms and their objects' hit data; the ray offset
    // grown to cover the instances' own float error.
    void setupInstances();

    // What a hit on mesh geomId reads, gathered in one place: one lookup per
    // hit instead of a chain through the description, the normals and the lights.
    struct MeshHitData {
        const unsigned* indices;
        const Vec3f* faceNormals;    // per triangle
        const Vec3f* vertexNormals;  // null: flat shading
        const Vec2f* uvs;            // null: none
        const int* triangleLights;   // LightSet::lightOfTriangle, per triangle
        int material;
    };

    // What a hit inside instance i needs of its transform M: world to object
    // for rays (a sphere's quadratic is solved in object space; the hit point
    // itself comes from the world ray), and the normal matrix M⁻ᵀ, which keeps
    // normals perpendicular and outward under any non-singular M (mirrors
    // included: it is what transformMesh and Affine::normal give a flattened
    // copy).
    struct InstanceFrame {
        Affine toObject;
        float normalMatrix[3][3];
        int object;
    };

    SceneDescription desc_;
    std::unique_ptr<EmbreeAccel> accel_;
    std::unique_ptr<LightSet> lights_;
    std::vector<std::vector<Vec3f>> triangleNormals_;  // per mesh, per triangle
    std::vector<MeshHitData> meshHits_;                // per mesh
    std::vector<InstanceFrame> instanceFrames_;        // per ObjectInstance
    // Per object, per mesh: object-space face normals, and the hit data
    // (triangleLights null: instanced shapes never emit).
    std::vector<std::vector<std::vector<Vec3f>>> objectTriangleNormals_;
    std::vector<std::vector<MeshHitData>> objectMeshHits_;
    float epsilon_ = 1e-4f;
    std::vector<char> lambertian_;  // per material
    std::vector<char> textured_;    // per material: some parameter is a texture
    // Per material: it, or a mix's component, has a bump or normal map.
    std::vector<char> mapped_;
    bool anyMapped_ = false;
    // Per material: the layered BSDF of a coated material (else empty),
    // built once, which bsdfAt's Bsdf points to.
    std::vector<std::optional<LayeredBsdf>> layered_;
    bool allLambertian_ = false;
};

// Inline: at every vertex; the texture coordinates are read only for a
// textured material (an out-of-line call took them by value, reloading them
// from the stored interaction).
inline float roughnessV(const Material& m) {
    return m.roughnessV >= 0 ? m.roughnessV : m.roughness;
}

inline Vec3f RenderScene::lambertianAlbedoAt(const SurfaceInteraction& si) const {
    const Material& m = desc_.materials[size_t(si.material)];
    if (m.texture >= 0) return desc_.textures[size_t(m.texture)].lookup(si.uv);
    if (m.albedoTexture >= 0) [[unlikely]]
        return texturedAlbedo(m, si);
    return m.albedo;
}

inline Bsdf RenderScene::bsdfAt(const SurfaceInteraction& si, Vec3f dir) const {
    int index = si.material;
    if (desc_.materials[size_t(index)].type == MaterialType::Mix)
        index = mixComponent(index, si.p, dir, si.uv);
    const Material* m = &desc_.materials[size_t(index)];
    if (textured_[size_t(index)]) [[unlikely]]
        return texturedBsdf(*m, si);
    switch (m->type) {
        case MaterialType::Diffuse:
            return Bsdf::diffuse(m->texture >= 0 ? desc_.textures[size_t(m->texture)].lookup(si.uv)
                                                 : m->albedo);
        case MaterialType::Mirror:
            return Bsdf::mirror(m->albedo);
        case MaterialType::Dielectric:
            return Bsdf::dielectric(m->ior, m->roughness, roughnessV(*m));
        case MaterialType::Conductor:
            return Bsdf::conductor(m->eta, m->k, m->roughness, roughnessV(*m));
        case MaterialType::ThinDielectric:
            return Bsdf::thinDielectric(m->ior);
        case MaterialType::DiffuseTransmission:
            return Bsdf::diffuseTransmission(m->albedo, m->transmittance);
        case MaterialType::Interface:
            return Bsdf::passThrough();
        case MaterialType::CoatedDiffuse:
        case MaterialType::CoatedConductor:
            return Bsdf::layered(&*layered_[size_t(m - desc_.materials.data())]);
        case MaterialType::Mix:
            break;  // resolved above
    }
    return Bsdf::diffuse(m->albedo);
}

}  // namespace pathlab
