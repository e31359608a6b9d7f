// Coated materials in the renderer. In a furnace (sky of radiance 1) a
// coated sphere that loses no energy (white base, clear coating, a
// non-absorbing medium) is invisible, which fails if the walks' numbers,
// the sample's rescaling to the pdf estimate, or the MIS weights (both
// strategies ask the same estimate, so they still sum to 1 in expectation)
// are wrong. The batched and the scalar integrator give the same image, and
// the walks draw from the dimensions the layout gives them.
#include <gtest/gtest.h>

#include <cmath>

#include "render/layered/walk_dimensions.h"
#include "render/renderer.h"
#include "spectral_test_util.h"

namespace pathlab {
namespace {

SceneDescription coatedSphereInFurnace(float roughness, float albedo) {
    Material m;
    m.type = MaterialType::CoatedDiffuse;
    m.albedo = Vec3f(1.0f);
    m.coating.roughness = roughness;
    m.coating.thickness = 0.1f;
    m.coating.albedo = Vec3f(albedo);
    m.coating.maxDepth = 500;
    return test::sphereInFurnace(m);
}

double meanOf(const Image& image) {
    double sum = 0;
    for (float v : image.rgb) sum += v;
    return sum / double(image.rgb.size());
}

TEST(LayeredRender, LosslessCoatedSphereIsInvisibleInAFurnace) {
    // A smooth coating: a rough one loses energy to GGX single scattering
    // (test_layered_bsdf.cpp).
    for (float roughness : {0.0f}) {
        const RenderScene scene(coatedSphereInFurnace(roughness, 1.0f));
        RenderSettings s;
        s.samplesPerPixel = 64;
        s.threads = 2;
        const RenderOutput out = render(scene, s);
        double var = 0;
        for (float v : out.varianceOfMean.rgb) var += v;
        const double error = std::sqrt(var) / double(out.image.rgb.size());
        EXPECT_NEAR(meanOf(out.image), 1.0, 4 * error + 5e-3) << "roughness " << roughness;
    }
}

TEST(LayeredRender, BatchedAndScalarIntegratorsAgreeBitForBit) {
    const RenderScene scene(coatedSphereInFurnace(0.2f, 0.5f));
    for (const char* sampler : {"independent", "sobol-owen", "halton-owen"}) {
        RenderSettings s;
        s.sampler = sampler;
        s.samplesPerPixel = 8;
        s.threads = 2;
        const RenderOutput batched = render(scene, s);
        s.batchPaths = false;
        s.threads = 1;
        const RenderOutput scalar = render(scene, s);
        EXPECT_EQ(batched.image.rgb, scalar.image.rgb) << sampler;
    }
}

TEST(LayeredRender, WalkBlocksFollowEveryVertexFixedBlock) {
    // A vertex's walks start after the fixed blocks of all maxDepth vertices
    // and never overlap each other or the next vertex's walks.
    for (int first : {dims::kFirstBounce, dims::firstBounce(true)})
        for (int maxDepth : {1, 8}) {
            EXPECT_EQ(dims::walkBase(0, dims::Walk::LightF, maxDepth, first),
                      dims::bounceBase(maxDepth, first));
            for (int d = 0; d + 1 < maxDepth; ++d)
                EXPECT_EQ(dims::walkBase(d, dims::Walk::SampledPdf, maxDepth, first) +
                              kWalkSamplerDimensions,
                          dims::walkBase(d + 1, dims::Walk::LightF, maxDepth, first));
        }
}

TEST(LayeredRender, WalksDrawFromTheSampler) {
    // The same image whatever the thread count (the walks' numbers are
    // functions of pixel, index, dimension and seed, not of the schedule).
    const RenderScene scene(coatedSphereInFurnace(0.3f, 0.7f));
    RenderSettings s;
    s.samplesPerPixel = 4;
    s.threads = 1;
    const RenderOutput one = render(scene, s);
    s.threads = 2;
    EXPECT_EQ(one.image.rgb, render(scene, s).image.rgb);
    // More dimensions are drawn than the fixed blocks hold: the walks'.
    EXPECT_GT(double(one.stats.dimensions) / double(one.stats.paths), double(dims::kDimsPerBounce));
}

}  // namespace
}  // namespace pathlab
