// The new materials in the renderer: in a furnace (constant sky of radiance
// 1, nothing else) every object whose BSDF conserves energy is invisible —
// the image is 1 everywhere, which fails if the integrator mishandles
// transmission, the 1/η² radiance scaling on the way in and out, a pass-
// through surface, or a mix's choice. Rough glass loses a few per cent to
// single scattering and must stay within that.
#include <gtest/gtest.h>

#include <cmath>

#include "render/renderer.h"

namespace pathlab {
namespace {

struct ImageMean {
    double mean, standardError;
};

ImageMean meanOf(const RenderOutput& out) {
    double sum = 0, var = 0;
    const size_t n = out.image.rgb.size();
    for (size_t i = 0; i < n; ++i) sum += out.image.rgb[i], var += out.varianceOfMean.rgb[i];
    return {sum / double(n), std::sqrt(var) / double(n)};
}

// Two spheres of `material` filling most of the view, in a sky of radiance 1;
// `extra` materials are appended (for a mix's parts).
SceneDescription furnaceSpheres(const Material& material, std::vector<Material> extra = {}) {
    SceneDescription s;
    s.materials.push_back(material);
    for (Material& m : extra) s.materials.push_back(m);
    s.spheres.push_back({Vec3f(-0.6f, 0, 0), 0.7f, 0});
    s.spheres.push_back({Vec3f(0.6f, 0.1f, -0.8f), 0.7f, 0});
    s.environment = Vec3f(1.0f);
    s.camera = Camera{{0, 0, 4}, {0, 0, 0}, {0, 1, 0}, 40};
    s.resolution = {16, 16};
    return s;
}

ImageMean renderMean(const SceneDescription& desc) {
    const RenderScene scene(desc);
    RenderSettings s;
    s.samplesPerPixel = 64;
    s.maxDepth = 100;
    return meanOf(render(scene, s));
}

Material makeMaterial(MaterialType type, float ior = 1.5f, float alpha = 0) {
    Material m;
    m.type = type;
    m.ior = ior;
    m.roughness = alpha;
    return m;
}

TEST(MaterialFurnace, LosslessMaterialsAreInvisible) {
    Material difftrans = makeMaterial(MaterialType::DiffuseTransmission);
    difftrans.albedo = Vec3f(0.4f);
    difftrans.transmittance = Vec3f(0.6f);
    Material mix = makeMaterial(MaterialType::Mix);
    mix.mix[0] = 1, mix.mix[1] = 2, mix.amount = 0.3f;
    const struct {
        const char* name;
        SceneDescription scene;
    } cases[] = {
        {"smooth glass", furnaceSpheres(makeMaterial(MaterialType::Dielectric, 1.5f))},
        {"smooth glass eta<1", furnaceSpheres(makeMaterial(MaterialType::Dielectric, 0.75f))},
        {"thin dielectric", furnaceSpheres(makeMaterial(MaterialType::ThinDielectric, 1.5f))},
        {"diffuse transmission", furnaceSpheres(difftrans)},
        {"interface", furnaceSpheres(makeMaterial(MaterialType::Interface))},
        {"mix", furnaceSpheres(mix, {makeMaterial(MaterialType::ThinDielectric), difftrans})},
    };
    for (const auto& c : cases) {
        const ImageMean m = renderMean(c.scene);
        EXPECT_NEAR(m.mean, 1.0, 5 * m.standardError * std::sqrt(3.0) + 1e-3) << c.name;
    }
}

TEST(MaterialFurnace, RoughGlassLosesOnlyWhatSingleScatteringLoses) {
    for (float alpha : {0.1f, 0.3f}) {
        Material glass = makeMaterial(MaterialType::Dielectric, 1.5f, alpha);
        glass.roughnessV = alpha * 0.5f;  // anisotropic too
        const ImageMean m = renderMean(furnaceSpheres(glass));
        EXPECT_LE(m.mean, 1.0 + 5 * m.standardError * std::sqrt(3.0) + 1e-3) << alpha;
        EXPECT_GE(m.mean, 0.9) << alpha;
    }
}

}  // namespace
}  // namespace pathlab
