// Materials whose parameters are textures (pbrt-v4's materials.h: each
// material's GetBxDF evaluates its textures at the hit before building the
// BxDF). The loaders keep every other parameter constant in Material.
#include <algorithm>
#include <cmath>

#include "render/render_scene.h"

namespace pathlab {

namespace {

Vec3f clamp01(Vec3f c) {
    return {std::clamp(c.x, 0.0f, 1.0f), std::clamp(c.y, 0.0f, 1.0f), std::clamp(c.z, 0.0f, 1.0f)};
}

// pbrt-v4's ConductorMaterial given a reflectance r: eta 1 and the k that
// reflects r at normal incidence, k = 2√r / √(1 − r), r clamped to [0, 0.9999].
Vec3f conductorK(Vec3f r) {
    const auto k = [](float rc) {
        rc = std::clamp(rc, 0.0f, 0.9999f);
        return 2 * std::sqrt(rc) / std::sqrt(1 - rc);
    };
    return {k(r.x), k(r.y), k(r.z)};
}

}  // namespace

Vec3f RenderScene::texturedAlbedo(const Material& m, const SurfaceInteraction& si) const {
    const Vec3f c =
        evaluateTexture(desc_.shadingTextures, desc_.textures, m.albedoTexture, {si.uv, si.p});
    return clamp01(c * m.albedoScale);
}

Bsdf RenderScene::texturedBsdf(const Material& m, const SurfaceInteraction& si) const {
    const TextureContext ctx{si.uv, si.p};
    const auto value = [&](int texture) {
        return evaluateTexture(desc_.shadingTextures, desc_.textures, texture, ctx);
    };
    // GGX alpha from a roughness texture, or the material's constant alpha.
    const auto alpha = [&](int texture, float constant) {
        if (texture < 0) return constant;
        const float r = std::max(value(texture).x, 0.0f);
        return m.remapRoughness ? std::sqrt(r) : r;
    };
    const float alphaU = alpha(m.roughnessTexture, m.roughness);
    const float alphaV = alpha(m.roughnessVTexture, roughnessV(m));
    switch (m.type) {
        case MaterialType::Diffuse:
            return Bsdf::diffuse(m.albedoTexture >= 0 ? texturedAlbedo(m, si) : m.albedo);
        case MaterialType::Dielectric:
            return Bsdf::dielectric(m.ior, alphaU, alphaV);
        case MaterialType::Conductor:
            if (m.albedoTexture >= 0)
                return Bsdf::conductor(Vec3f(1.0f), conductorK(value(m.albedoTexture)), alphaU,
                                       alphaV);
            return Bsdf::conductor(m.eta, m.k, alphaU, alphaV);
        case MaterialType::DiffuseTransmission: {
            const Vec3f r = m.albedoTexture >= 0 ? texturedAlbedo(m, si) : m.albedo;
            const Vec3f t = m.transmittanceTexture >= 0
                                ? clamp01(value(m.transmittanceTexture) * m.albedoScale)
                                : m.transmittance;
            return Bsdf::diffuseTransmission(r, t);
        }
        default:
            break;  // no textured parameters (RenderScene's textured_)
    }
    return Bsdf::diffuse(m.albedo);
}

}  // namespace pathlab
