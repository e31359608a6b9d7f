// Unidirectional path tracing of the rendering equation (Kajiya 1986) with
// next-event estimation and BSDF sampling combined by multiple importance
// sampling (Veach & Guibas 1995, power heuristic), Russian roulette, and a
// maximum depth counted as pbrt-v4 does (1 = direct lighting only).
//
// Every random number comes from the sampler, in the fixed layout of
// sampling/sampler.h: vertex `depth` owns the block of dimensions starting at
// dims::bounceBase(depth, settings.firstBounce) — after the pixel's, and the
// lens's when the camera has one — so a bounce's dimensions never depend on
// what earlier bounces drew. A vertex draws only the dimensions it uses (no light choice with
// one light, no lobe choice off glass, no light sample at a specular vertex, no
// roulette before it starts) and skips the others: a sampler's value is a pure
// function of (pixel, index, dimension, seed), so skipping changes no value that
// is drawn — it only saves computing those that would be thrown away.
#pragma once

#include <limits>
#include <optional>

#include "render/colour/rgb_context.h"
#include "render/integrator_settings.h"
#include "render/layered/walk_dimensions.h"
#include "render/render_scene.h"
#include "render/sampling_routines.h"
#include "sampling/sampler.h"

namespace pathlab {

struct PathCounters {
    uint64_t rays = 0;        // closest-hit rays: camera and bounce
    uint64_t shadowRays = 0;  // visibility rays of next-event estimation
    uint64_t dimensions = 0;  // sampler dimensions drawn (a 2D draw counts 2)
};

// The draws of one path vertex, by their offset in the vertex's block of
// dimensions (dims::kLightChoice …). The sampler is repositioned only when a
// draw does not follow the previous one.
template <Sampler S>
class VertexDimensions {
  public:
    VertexDimensions(S& sampler, Vec2i pixel, int sampleIndex, int depth, PathCounters& counters,
                     int firstBounce = dims::kFirstBounce, int maxDepth = 0)
        : sampler_(sampler),
          pixel_(pixel),
          index_(sampleIndex),
          base_(dims::bounceBase(depth, firstBounce)),
          depth_(depth),
          firstBounce_(firstBounce),
          maxDepth_(maxDepth),
          counters_(counters) {}
    float get1D(int offset) {
        seek(offset, 1);
        return sampler_.get1D();
    }
    Vec2f get2D(int offset) {
        seek(offset, 2);
        return sampler_.get2D();
    }
    // The first dimension of one of a layered BSDF's walks at this vertex, as
    // an offset from the vertex's fixed block (render/layered/walk_dimensions.h).
    int walkOffset(dims::Walk walk) const {
        return dims::walkBase(depth_, walk, maxDepth_, firstBounce_) - base_;
    }

  private:
    void seek(int offset, int count) {
        if (offset != next_) sampler_.startPixelSample(pixel_, index_, base_ + offset);
        next_ = offset + count;
        counters_.dimensions += uint64_t(count);
    }
    S& sampler_;
    Vec2i pixel_;
    int index_, base_, depth_, firstBounce_, maxDepth_;
    int next_ = -1;  // the offset the sampler would produce next
    PathCounters& counters_;
};

// Next-event estimation at a non-specular vertex, up to its shadow ray: one
// light sample, weighted against the BSDF's density for the same direction
// (power heuristic). Nothing when the sample cannot contribute (no shadow
// ray is traced then); otherwise the shadow ray and what the sample adds if
// the ray is unblocked, in the colour the path carries (colour/rgb_context.h).
template <class Colour>
struct DirectSampleOf {
    Vec3f origin, toLight;  // the shadow ray o + t·d, 0 < t < tMax
    float tMax;
    Colour contribution;
};
using DirectSample = DirectSampleOf<Vec3f>;
// A layered BSDF's walks for f and pdf towards the light sample, from the
// sampler (null: the BSDF's own, seeded by the directions).
struct LightWalks {
    WalkNumbers* f = nullptr;
    WalkNumbers* pdf = nullptr;
};
template <class Ctx = RgbContext>
std::optional<DirectSampleOf<typename Ctx::Colour>> sampleDirect(
    const RenderScene& scene, const SurfaceInteraction& si, const Frame& frame, const Bsdf& bsdf,
    Vec3f wo, float uChoice, Vec2f uLight, LightWalks walks = {}, const Ctx& ctx = {}) {
    using Colour = typename Ctx::Colour;
    const auto ls = scene.lights().sample(si.p, si.ns, uChoice, uLight);
    if (!ls) return std::nullopt;
    const Vec3f wi = frame.toLocal(ls->wi);
    const Colour f =
        (walks.f ? ctx.layeredF(*bsdf.layered(), wo, wi, *walks.f) : ctx.f(bsdf, wo, wi)) *
        absCosTheta(wi);
    if (isBlack(f)) return std::nullopt;
    // The shadow ray runs from the nudged origin to the light point itself, as
    // pbrt-v4's SpawnRayTo: with the unnormalised difference as its direction,
    // t = 1 is the light, and it stops at 1 − 10⁻⁴ so it cannot hit the light
    // and block itself. (A ray along wi from the nudged origin runs parallel to
    // the segment, ε off it, and crosses the light's plane up to ε/cosθ early:
    // grazing samples of a nearby light were blocked by the light.)
    const Vec3f origin = scene.offsetOrigin(si, ls->wi);
    const float weight =
        ls->delta ? 1.0f
                  : powerHeuristic(ls->pdf, walks.pdf ? bsdf.layered()->pdf(wo, wi, *walks.pdf)
                                                      : bsdf.pdf(wo, wi));
    const Colour contribution = f * ctx.emission(ls->radiance) * (weight / ls->pdf);
    using Sample = DirectSampleOf<Colour>;
    if (std::isinf(ls->distance)) return Sample{origin, ls->wi, ls->distance, contribution};
    return Sample{origin, si.p + ls->wi * ls->distance - origin, 1 - 1e-4f, contribution};
}

// A sample's estimate: its contribution unless its shadow ray is blocked.
template <class Colour>
Colour traceShadowRay(const RenderScene& scene, const DirectSampleOf<Colour>& d,
                      PathCounters& counters) {
    ++counters.shadowRays;
    return scene.occluded(d.origin, d.toLight, d.tMax) ? Colour(0.0f) : d.contribution;
}

// Russian roulette's probability of ending the path after vertex `depth`
// with throughput beta (pbrt-v4's rule); 0 where roulette does not play.
template <class Colour>
float terminationProbability(const IntegratorSettings& settings, int depth, const Colour& beta) {
    if (!settings.russianRoulette || depth < settings.rouletteDepth) return 0;
    return std::max(0.0f, 1 - maxComponent(beta));
}

// After a vertex's bounce: Russian roulette, from vertex rouletteDepth on
// (its number drawn only when it can end the path), then the end of a path
// whose throughput is zero. False when the path ends.
template <Sampler S, class Colour>
bool pathContinues(const IntegratorSettings& settings, int depth, VertexDimensions<S>& draws,
                   Colour& beta) {
    const float q = terminationProbability(settings, depth, beta);
    if (q > 0) {
        if (draws.get1D(dims::kRoulette) < q) return false;
        beta *= 1 / (1 - q);
    }
    return !isBlack(beta);
}

// An escaped ray's radiance from the image environment map, weighted
// against the map's light sample for the same direction.
template <class Ctx = RgbContext, class Colour = typename Ctx::Colour>
void addEnvironmentMap(const LightSet& lights, Vec3f dir, const Colour& beta, bool unweighted,
                       float prevBsdfPdf, Colour& L, const Ctx& ctx = {}) {
    const Vec3f Le = lights.environmentMapRadiance(dir);
    if (isBlack(Le)) return;
    L += beta * ctx.emission(Le) *
         (unweighted ? 1.0f : powerHeuristic(prevBsdfPdf, lights.pdfEnvironmentMap(dir)));
}

// What the ray that found a vertex (or escaped: !found) adds to L: the
// environment or the emission of the light it hit, weighted against the light
// sample that could have reached the same point (power heuristic) — unweighted
// for the camera ray and after a specular bounce, which no light sample
// competes with.
template <class Ctx = RgbContext, class Colour = typename Ctx::Colour>
void addEmission(const LightSet& lights, bool found, const SurfaceInteraction& si, Vec3f dir,
                 const Colour& beta, bool unweighted, float prevBsdfPdf, Vec3f prevPoint,
                 Vec3f prevNormal, Colour& L, const Ctx& ctx = {}) {
    if (!found) {
        const Vec3f env = lights.environment();
        if (!isBlack(env))
            L += beta * ctx.emission(env) *
                 (unweighted ? 1.0f : powerHeuristic(prevBsdfPdf, lights.pdfEnvironment()));
        if (lights.hasEnvironmentMap())
            addEnvironmentMap(lights, dir, beta, unweighted, prevBsdfPdf, L, ctx);
        return;
    }
    if (si.light >= 0) {
        const Vec3f Le = lights.areaLight(si.light).emittedAt(si.p, -dir);
        if (!isBlack(Le))
            L += beta * ctx.emission(Le) *
                 (unweighted ? 1.0f
                             : powerHeuristic(prevBsdfPdf, lights.pdfAreaLight(si.light, prevPoint,
                                                                               prevNormal, si.p)));
    }
}

// A vertex shaded on its own: its draws (through `draws`, the vertex's
// dimensions), next-event estimation unless the BSDF is specular, and the
// BSDF sample with the bounce's world direction and nudged origin. The
// scalar integrator shades every vertex so, the batched one those that are
// not Lambertian. `weight` is the bounce's throughput factor f·|cosθi|/pdf in
// the path's colour.
template <class Colour>
struct VertexShadingOf {
    bool lightSampled = false;  // next-event estimation ran (non-specular BSDF)
    std::optional<DirectSampleOf<Colour>> direct;
    std::optional<BsdfSample> bounce;
    Vec3f wi, origin;  // where bounce is set
    Colour weight;     // where bounce is set
};
using VertexShading = VertexShadingOf<Vec3f>;
// The numbers of one layered walk at a vertex: the sampler's, at the walk's
// dimensions, then PCG32 (walk_numbers.h).
template <Sampler S>
struct WalkDraw {
    VertexDimensions<S>* draws;
    int first;
    float operator()(int i) const { return draws->get1D(first + i); }
};
template <Sampler S>
SamplerWalkNumbers<WalkDraw<S>> walkNumbers(VertexDimensions<S>& draws, dims::Walk walk) {
    return SamplerWalkNumbers<WalkDraw<S>>(WalkDraw<S>{&draws, draws.walkOffset(walk)});
}

// shadeVertex at a layered BSDF, whose walks draw from the vertex's layered
// block, in either colour: the walks draw the same dimensions in both.
// Its sample's pdf is only proportional to the walk's density (as
// pbrt-v4's PathIntegrator, multiple importance sampling takes the pdf
// estimate instead): f is rescaled with it, which leaves the weight as it was.
template <Sampler S, class Ctx>
VertexShadingOf<typename Ctx::Colour> shadeLayeredVertex(const RenderScene& scene,
                                                         VertexDimensions<S>& draws,
                                                         const SurfaceInteraction& si,
                                                         const Bsdf& bsdf, const Frame& frame,
                                                         Vec3f wo, const Ctx& ctx) {
    const LightSet& lights = scene.lights();
    const LayeredBsdf& layered = *bsdf.layered();
    VertexShadingOf<typename Ctx::Colour> v;
    if (!bsdf.isSpecular()) {
        const float uChoice = lights.choiceUsesSample() ? draws.get1D(dims::kLightChoice) : 0;
        const Vec2f uLight = draws.get2D(dims::kLightPoint);
        auto walkF = walkNumbers(draws, dims::Walk::LightF);
        auto walkPdf = walkNumbers(draws, dims::Walk::LightPdf);
        v.lightSampled = true;
        v.direct = sampleDirect(scene, si, frame, bsdf, wo, uChoice, uLight,
                                LightWalks{&walkF, &walkPdf}, ctx);
    }
    const float uLobe = draws.get1D(dims::kBsdfLobe);
    const Vec2f uDirection = draws.get2D(dims::kBsdfDirection);
    auto walk = walkNumbers(draws, dims::Walk::Sample);
    auto s = ctx.layeredSample(layered, wo, uLobe, uDirection, walk);
    if (!s) return v;
    if (s->sample.pdfIsProportional && !s->sample.specular) {
        auto walkPdf = walkNumbers(draws, dims::Walk::SampledPdf);
        const float pdf = layered.pdf(wo, s->sample.wi, walkPdf);
        s->f *= pdf / s->sample.pdf;
        s->sample.pdf = pdf;
    }
    if constexpr (!Ctx::kSpectral) s->sample.f = s->f;
    v.bounce = s->sample;
    v.wi = frame.toWorld(v.bounce->wi), v.origin = scene.offsetOrigin(si, v.wi);
    v.weight = s->f * (absCosTheta(v.bounce->wi) / v.bounce->pdf);
    return v;
}

// A vertex's shading in the colour of context ctx (colour/rgb_context.h).
template <Sampler S, class Ctx = RgbContext>
VertexShadingOf<typename Ctx::Colour> shadeVertex(const RenderScene& scene,
                                                  VertexDimensions<S>& draws,
                                                  const SurfaceInteraction& si, Vec3f dir,
                                                  const Ctx& ctx = {}) {
    const LightSet& lights = scene.lights();
    const Bsdf bsdf = scene.bsdfAt(si, dir);
    const Frame frame = shadingFrame(bsdf, si.ns);
    const Vec3f wo = frame.toLocal(-dir);
    if (bsdf.layered()) return shadeLayeredVertex(scene, draws, si, bsdf, frame, wo, ctx);
    VertexShadingOf<typename Ctx::Colour> v;
    if (!bsdf.isSpecular()) {
        const float uChoice = lights.choiceUsesSample() ? draws.get1D(dims::kLightChoice) : 0;
        const Vec2f uLight = draws.get2D(dims::kLightPoint);
        v.lightSampled = true;
        v.direct = sampleDirect(scene, si, frame, bsdf, wo, uChoice, uLight, {}, ctx);
    }
    const float uLobe = bsdf.usesLobeSample() ? draws.get1D(dims::kBsdfLobe) : 0;
    const Vec2f uDirection =
        bsdf.usesDirectionSample() ? draws.get2D(dims::kBsdfDirection) : Vec2f{};
    v.bounce = bsdf.sample(wo, uLobe, uDirection);
    if (v.bounce) {
        v.wi = frame.toWorld(v.bounce->wi), v.origin = scene.offsetOrigin(si, v.wi);
        v.weight = ctx.sampledF(bsdf, wo, *v.bounce) * (absCosTheta(v.bounce->wi) / v.bounce->pdf);
    }
    return v;
}

// The radiance arriving along a path whose first segment (origin → first
// surface, or escape when !found) has already been traced: the camera rays of
// a pixel are traced together as a packet (renderer.cpp). Later rays are traced
// here one at a time. (`origin` is the camera ray's own: the eye, or its point
// on the lens or the orthographic screen.) (The renderer traces batches,
// estimateRadianceBatch in batched_paths.h; this is the reference it is tested
// against in both colour modes: ctx chooses the colour the path carries,
// colour/rgb_context.h.)
template <Sampler S, class Ctx = RgbContext>
typename Ctx::Colour estimateRadiance(const RenderScene& scene, Vec3f origin, Vec3f dir, bool found,
                                      SurfaceInteraction si, S& sampler, Vec2i pixel,
                                      int sampleIndex, const IntegratorSettings& settings,
                                      PathCounters& counters, const Ctx& ctx = {}) {
    using Colour = typename Ctx::Colour;
    const LightSet& lights = scene.lights();
    Colour L(0.0f), beta(1.0f);
    Vec3f prevPoint, prevNormal;
    bool specularBounce = false;
    float prevBsdfPdf = 0;
    for (int depth = 0;; ++depth) {
        if (depth > 0) {
            ++counters.rays;
            found = scene.intersect(origin, dir, &si);
        }
        addEmission(lights, found, si, dir, beta, depth == 0 || specularBounce, prevBsdfPdf,
                    prevPoint, prevNormal, L, ctx);
        if (!found || depth == settings.maxDepth) break;

        VertexDimensions<S> draws(sampler, pixel, sampleIndex, depth, counters,
                                  settings.firstBounce, settings.maxDepth);
        const auto v = shadeVertex(scene, draws, si, dir, ctx);
        if (v.lightSampled)
            L += beta * (v.direct ? traceShadowRay(scene, *v.direct, counters) : Colour(0.0f));
        if (!v.bounce) break;
        beta *= v.weight;
        specularBounce = v.bounce->specular;
        prevBsdfPdf = v.bounce->pdf;
        prevPoint = si.p;
        prevNormal = si.ns;
        origin = v.origin;
        dir = v.wi;

        if (!pathContinues(settings, depth, draws, beta)) break;
    }
    return L;
}

}  // namespace pathlab
