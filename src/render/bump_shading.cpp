// Where RenderScene applies bump and normal maps: at each hit whose material
// has one, before anything reads the shading normal — so next-event
// estimation, the BSDF's frame and the batched Lambertian kernel all see the
// perturbed normal, while the geometric normal keeps offsetting ray origins
// (pbrt-v4's SurfaceInteraction::GetBSDF, which perturbs the shading
// geometry before making the BSDF).
#include "render/render_scene.h"

namespace pathlab {

const Material* RenderScene::mappedMaterial(const SurfaceInteraction& si, Vec3f d) const {
    int index = si.material;
    if (desc_.materials[size_t(index)].type == MaterialType::Mix)
        index = mixComponent(index, si.p, d, si.uv);
    const Material& m = desc_.materials[size_t(index)];
    return m.normalMap >= 0 || m.displacementTexture >= 0 ? &m : nullptr;
}

void RenderScene::applyMap(const Material& m, const ShadingGeometry& g,
                           SurfaceInteraction* si) const {
    const Vec3f n = m.normalMap >= 0
                        ? normalMapNormal(desc_.textures[size_t(m.normalMap)], si->uv, g)
                        : bumpMapNormal(desc_.shadingTextures, desc_.textures,
                                        m.displacementTexture, si->uv, si->p, g);
    si->ns = faceForward(n, si->ng);
}

void RenderScene::bumpTriangle(const Mesh& mesh, unsigned prim, const Affine* instance, Vec3f d,
                               SurfaceInteraction* si) const {
    const Material* m = mappedMaterial(*si, d);
    if (!m) return;
    const unsigned* idx = mesh.indices.data() + 3 * size_t(prim);
    Vec3f p[3], n[3];
    Vec2f uv[3];
    for (int i = 0; i < 3; ++i) {
        p[i] = mesh.positions[idx[i]];
        if (instance) p[i] = instance->point(p[i]);
        if (!mesh.normals.empty())
            n[i] = instance ? instance->normal(mesh.normals[idx[i]]) : mesh.normals[idx[i]];
        if (!mesh.uvs.empty()) uv[i] = mesh.uvs[idx[i]];
    }
    applyMap(*m,
             triangleShading(p, mesh.uvs.empty() ? nullptr : uv, mesh.normals.empty() ? nullptr : n,
                             si->ns),
             si);
}

void RenderScene::bumpSphere(const Sphere& sphere, Vec3f local, const Affine* instance, Vec3f d,
                             SurfaceInteraction* si) const {
    const Material* m = mappedMaterial(*si, d);
    if (!m) return;
    ShadingGeometry g = sphereShading(local, sphere.radius);
    if (instance) {
        g.dpdu = instance->vector(g.dpdu), g.dpdv = instance->vector(g.dpdv);
        g.dndu = instance->vector(g.dndu), g.dndv = instance->vector(g.dndv);
    }
    g.n = si->ns;
    applyMap(*m, g, si);
}

}  // namespace pathlab
