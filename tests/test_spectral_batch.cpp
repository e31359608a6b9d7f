// Spectral mode's faster evaluations against the ones they replace, bit for
// bit: the batched paths (render/batched_paths.h with spectral colour
// contexts) against the scalar integrator with the same contexts — the
// kernel's four-channel outputs lane by lane, and whole spectral renders with
// and without batching — the sigmoid at four wavelengths at once, and the
// tabulated spectra's grid lookups.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "render/colour/spectral_paths.h"
#include "render/renderer.h"
#include "sampling/registry.h"
#include "scene/builtin_scenes.h"
#include "scene/loader.h"
#include "spectral/cie_functions.h"
#include "spectral/named_illuminants.h"

namespace pathlab {
namespace {

using spectral::SampledSpectrum;
using spectral::SampledWavelengths;

bool same(float a, float b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}
// Lane k's four channels against a spectrum, bit for bit.
void expectSameSpectrum(const SampledSpectrum& expected, const float (*lanes)[kBatchLanes], int k,
                        const char* what) {
    for (int i = 0; i < spectral::kSpectrumSamples; ++i)
        EXPECT_TRUE(same(expected[i], lanes[i][k]))
            << what << ", lane " << k << ", wavelength " << i << ": " << expected[i] << " against "
            << lanes[i][k];
}

// The Cornell box with its only light (sampled by the kernel), and with a sky
// (light samples drawn by LightSet, a light choice, shadow rays to infinity).
std::vector<RenderScene> lightVariants() {
    std::vector<RenderScene> scenes;
    scenes.emplace_back(cornellBoxScene());
    SceneDescription sky = cornellBoxScene();
    sky.environment = Vec3f(0.3f, 0.4f, 0.5f);
    scenes.emplace_back(sky);
    return scenes;
}

TEST(SpectralBatch, KernelMatchesTheScalarSpectralVertexBitForBit) {
    std::mt19937 rng(11);
    auto unit = [&] { return std::uniform_real_distribution<float>(0.0f, 1.0f)(rng); };
    auto direction = [&] { return normalize(Vec3f(unit() - 0.5f, unit() - 0.5f, unit() - 0.5f)); };
    int shadows = 0, bounces = 0, lanesSeen = 0;
    for (BatchIsa isa : {BatchIsa::Best, BatchIsa::Sse})
        for (const RenderScene& scene : lightVariants()) {
            const AreaLight* onlyLight = scene.lights().onlyAreaLight();
            for (int round = 0; round < 200; ++round) {
                const int lanes = 1 + round % kBatchLanes;
                SpectralContext ctx[kBatchLanes];
                SigmoidCache cache;
                SurfaceInteraction si[kBatchLanes];
                Vec3f dir[kBatchLanes], albedo[kBatchLanes];
                float uChoice[kBatchLanes];
                Vec2f uLight[kBatchLanes], uDirection[kBatchLanes];
                DiffuseBatchInput in{};
                for (int k = 0; k < lanes; ++k) {
                    ctx[k] = SpectralContext(SampledWavelengths::sampleVisible(unit()), cache);
                    si[k].p = Vec3f(unit() * 550, unit() * 548, unit() * 559);
                    si[k].ng = direction();
                    si[k].ns = normalize(si[k].ng + direction() * 0.5f);
                    if (dot(si[k].ns, si[k].ng) < 0) si[k].ns = -si[k].ns;
                    dir[k] = direction();
                    albedo[k] = unit() < 0.1f ? Vec3f(0.0f) : Vec3f(unit(), unit(), unit());
                    uChoice[k] = unit();
                    uLight[k] = {unit(), unit()};
                    uDirection[k] = {unit(), unit()};
                    setBatchLane(in, k, si[k], dir[k], uLight[k], uDirection[k]);
                    setLaneColour<4>(in.albedo, k, ctx[k].reflectance(albedo[k]));
                    if (onlyLight)
                        setLaneColour<4>(in.lightRadiance, k, ctx[k].emission(onlyLight->radiance));
                    else
                        setBatchLightSample(
                            in, k, scene.lights().sample(si[k].p, si[k].ns, uChoice[k], uLight[k]),
                            ctx[k]);
                }
                DiffuseBatchOutput out;
                shadeDiffuseBatchSpectral(onlyLight, scene.epsilon(), in, lanes, out, isa);
                for (int k = 0; k < lanes; ++k) {
                    ++lanesSeen;
                    // What shadeVertex computes at a Lambertian vertex.
                    const Frame frame(si[k].ns);
                    const Vec3f wo = frame.toLocal(-dir[k]);
                    const Bsdf bsdf = Bsdf::diffuse(albedo[k]);
                    const auto d = sampleDirect(scene, si[k], frame, bsdf, wo, uChoice[k],
                                                uLight[k], {}, ctx[k]);
                    ASSERT_EQ(d.has_value(), out.shadow[k] != 0) << "lane " << k;
                    if (d) {
                        ++shadows;
                        expectSameSpectrum(d->contribution, out.direct, k, "direct");
                        EXPECT_TRUE(same(d->toLight.x, out.sdx[k]) &&
                                    same(d->tMax, out.shadowTMax[k]));
                    }
                    const auto bs = bsdf.sample(wo, 0, uDirection[k]);
                    ASSERT_EQ(bs.has_value(), out.bounce[k] != 0) << "lane " << k;
                    if (!bs) continue;
                    ++bounces;
                    const SampledSpectrum weight =
                        ctx[k].sampledF(bsdf, wo, *bs) * (absCosTheta(bs->wi) / bs->pdf);
                    expectSameSpectrum(weight, out.weight, k, "bounce weight");
                }
            }
        }
    // Both outcomes of each test were met.
    EXPECT_GT(shadows, lanesSeen / 8);
    EXPECT_LT(shadows, lanesSeen);
    EXPECT_GT(bounces, lanesSeen / 2);
}

TEST(SpectralBatch, SigmoidAtFourWavelengthsIsTheScalarSigmoidBitForBit) {
    // sampleSigmoid (four lanes at once) against SigmoidPolynomial's scalar
    // value at each wavelength: table colours, the greys' infinite constants
    // (black and white), steep polynomials and NaN coefficients.
    std::mt19937 rng(5);
    auto unit = [&] { return std::uniform_real_distribution<float>(0.0f, 1.0f)(rng); };
    const float inf = std::numeric_limits<float>::infinity();
    std::vector<spectral::SigmoidPolynomial> polys = {
        {0, 0, inf}, {0, 0, -inf}, {0, 0, 0}, {1e-3f, -0.9f, 180.0f}, {0, 0, std::nanf("")}};
    for (int i = 0; i < 200; ++i) {
        polys.push_back(spectral::rgbToSigmoid(Vec3f(unit(), unit(), unit())));
        polys.push_back({(unit() - 0.5f) * 1e-2f, (unit() - 0.5f) * 10, (unit() - 0.5f) * 1e3f});
    }
    int compared = 0;
    for (const spectral::SigmoidPolynomial& poly : polys) {
        const SampledWavelengths w = SampledWavelengths::sampleVisible(unit());
        const SampledSpectrum s = spectral::sampleSigmoid(poly, w);
        for (int i = 0; i < spectral::kSpectrumSamples; ++i, ++compared)
            EXPECT_TRUE(same(poly(w.lambda(i)), s[i]) ||
                        (std::isnan(poly(w.lambda(i))) && std::isnan(s[i])))
                << poly.c0 << " " << poly.c1 << " " << poly.c2 << " at " << w.lambda(i)
                << " nm: " << poly(w.lambda(i)) << " against " << s[i];
    }
    EXPECT_EQ(compared, int(polys.size()) * spectral::kSpectrumSamples);
}

// The linear interpolation between the knots around λ, the interval found by
// binary search (what PiecewiseLinearSpectrum did before its grid lookup).
double bySearch(const spectral::PiecewiseLinearSpectrum& s, double lambda) {
    const std::vector<double>&l = s.wavelengths(), &v = s.values();
    if (lambda < l.front() || lambda > l.back()) return 0;
    const size_t hi = size_t(std::upper_bound(l.begin(), l.end(), lambda) - l.begin());
    if (hi >= l.size()) return v.back();
    const double t = (lambda - l[hi - 1]) / (l[hi] - l[hi - 1]);
    return (1 - t) * v[hi - 1] + t * v[hi];
}

TEST(SpectralLookups, GridLookupsAreTheBinarySearchesBitForBit) {
    // D65 (5-nm knots, the grid) and an irregular spectrum (binary search),
    // at random wavelengths, at every knot and a rounding step either side.
    const spectral::PiecewiseLinearSpectrum& d65 = *spectral::namedIlluminant("stdillum-D65");
    const auto irregular =
        spectral::PiecewiseLinearSpectrum::fromInterleaved({400, 1, 410, 2, 431, 0.5, 700, 3});
    std::mt19937 rng(9);
    for (const spectral::PiecewiseLinearSpectrum* s : {&d65, &irregular}) {
        std::vector<double> at;
        for (int i = 0; i < 2000; ++i)
            at.push_back(std::uniform_real_distribution<double>(300, 850)(rng));
        for (double knot : s->wavelengths())
            for (double l : {std::nextafter(knot, 0.0), knot, std::nextafter(knot, 1e9)})
                at.push_back(l), at.push_back(double(float(l)));
        for (double l : at) ASSERT_EQ((*s)(l), bySearch(*s, l)) << l;
    }
    // The CIE functions at once, as each alone.
    for (int i = 0; i < 5000; ++i) {
        const float l = std::uniform_real_distribution<float>(350, 840)(rng);
        const Vec3f xyz = spectral::cieXyzMatching(l);
        ASSERT_TRUE(same(xyz.x, float(spectral::cieX(l))) &&
                    same(xyz.y, float(spectral::cieY(l))) && same(xyz.z, float(spectral::cieZ(l))))
            << l;
    }
}

std::vector<float> renderImage(const RenderScene& scene, RenderSettings s, bool batch,
                               RenderStats* stats) {
    s.batchPaths = batch;
    s.spectral = true;
    const RenderOutput out = render(scene, s);
    *stats = out.stats;
    std::vector<float> pixels = out.image.rgb;
    pixels.insert(pixels.end(), out.varianceOfMean.rgb.begin(), out.varianceOfMean.rgb.end());
    return pixels;
}

void expectSameSpectralRender(const RenderScene& scene, const RenderSettings& s,
                              const std::string& what) {
    RenderStats scalarStats, batchStats;
    const auto scalar = renderImage(scene, s, false, &scalarStats);
    const auto batch = renderImage(scene, s, true, &batchStats);
    ASSERT_EQ(scalar.size(), batch.size());
    EXPECT_EQ(0, std::memcmp(scalar.data(), batch.data(), scalar.size() * sizeof(float)))
        << what << ": " << s.sampler << ", " << s.samplesPerPixel << " spp, depth " << s.maxDepth;
    EXPECT_EQ(scalarStats.rays, batchStats.rays) << what;
    EXPECT_EQ(scalarStats.shadowRays, batchStats.shadowRays) << what;
    EXPECT_EQ(scalarStats.dimensions, batchStats.dimensions) << what;
}

TEST(SpectralBatch, RendersTheScalarIntegratorsImageOfTheCornellBox) {
    // The only light sampled in the kernel; every sampler; with and without
    // roulette, a short and a long path; then more samples than one batch,
    // with prefixes ending batches early.
    const RenderScene scene(cornellBoxScene());
    for (const SamplerInfo& info : samplerInfos()) {
        RenderSettings s;
        s.sampler = info.name;
        s.resolution = {10, 10};
        s.samplesPerPixel = 8;
        expectSameSpectralRender(scene, s, "cornell box");
    }
    for (bool roulette : {false, true})
        for (int depth : {1, 20}) {
            RenderSettings s;
            s.resolution = {10, 10};
            s.samplesPerPixel = 13;
            s.russianRoulette = roulette;
            s.maxDepth = depth;
            expectSameSpectralRender(scene, s, "cornell box");
        }
    RenderSettings s;
    s.sampler = "sobol";
    s.resolution = {5, 5};
    s.samplesPerPixel = kBatchSamples + 11;
    s.prefixSpp = {3, kBatchSamples / 2 + 1};
    expectSameSpectralRender(scene, s, "cornell box across batches");
}

TEST(SpectralBatch, RendersTheScalarIntegratorsImageOfEveryKindOfVertex) {
    // Lambertian lanes beside glass, mirror, metal, mix, interface, thin
    // dielectric and diffuse transmission shaded one at a time; point, spot
    // and distant lights, skies and a thin lens.
    for (const char* file :
         {"glass-and-metal.json", "pbrt/punctual-lights.pbrt", "pbrt/depth-of-field.pbrt",
          "pbrt/mix-and-interface.pbrt", "pbrt/thin-and-translucent.pbrt"}) {
        const RenderScene scene(loadScene(std::string(PATHLAB_SOURCE_DIR) + "/scenes/" + file));
        RenderSettings s;
        s.sampler = "zsobol";
        s.resolution = {12, 12};
        s.samplesPerPixel = 9;
        expectSameSpectralRender(scene, s, file);
    }
}

}  // namespace
}  // namespace pathlab
