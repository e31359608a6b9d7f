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
#include "render/diffuse_batch.h"
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
    Colour f;
    if constexpr (Ctx::kSpectral)
        f = ctx.f(bsdf, wo, wi) * absCosTheta(wi);  // layered BSDFs are RGB only
    else
        f = (walks.f ? bsdf.layered()->f(wo, wi, *walks.f) : bsdf.f(wo, wi)) * absCosTheta(wi);
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
// block. Its sample's pdf is only proportional to the walk's density (as
// pbrt-v4's PathIntegrator, multiple importance sampling takes the pdf
// estimate instead): f is rescaled with it, which leaves the weight as it was.
template <Sampler S>
VertexShading shadeLayeredVertex(const RenderScene& scene, VertexDimensions<S>& draws,
                                 const SurfaceInteraction& si, const Bsdf& bsdf, const Frame& frame,
                                 Vec3f wo) {
    const LightSet& lights = scene.lights();
    const LayeredBsdf& layered = *bsdf.layered();
    VertexShading v;
    if (!bsdf.isSpecular()) {
        const float uChoice = lights.choiceUsesSample() ? draws.get1D(dims::kLightChoice) : 0;
        const Vec2f uLight = draws.get2D(dims::kLightPoint);
        auto walkF = walkNumbers(draws, dims::Walk::LightF);
        auto walkPdf = walkNumbers(draws, dims::Walk::LightPdf);
        v.lightSampled = true;
        v.direct =
            sampleDirect(scene, si, frame, bsdf, wo, uChoice, uLight, LightWalks{&walkF, &walkPdf});
    }
    const float uLobe = draws.get1D(dims::kBsdfLobe);
    const Vec2f uDirection = draws.get2D(dims::kBsdfDirection);
    auto walk = walkNumbers(draws, dims::Walk::Sample);
    v.bounce = layered.sample(wo, uLobe, uDirection, walk);
    if (v.bounce && v.bounce->pdfIsProportional && !v.bounce->specular) {
        auto walkPdf = walkNumbers(draws, dims::Walk::SampledPdf);
        const float pdf = layered.pdf(wo, v.bounce->wi, walkPdf);
        v.bounce->f *= pdf / v.bounce->pdf;
        v.bounce->pdf = pdf;
    }
    if (v.bounce) {
        v.wi = frame.toWorld(v.bounce->wi), v.origin = scene.offsetOrigin(si, v.wi);
        v.weight = v.bounce->weight();
    }
    return v;
}

// A vertex's shading in the colour of context ctx (colour/rgb_context.h).
// Layered BSDFs are shaded in RGB only (renderer.cpp rejects them in
// spectral mode before rendering).
template <Sampler S, class Ctx = RgbContext>
VertexShadingOf<typename Ctx::Colour> shadeVertex(const RenderScene& scene,
                                                  VertexDimensions<S>& draws,
                                                  const SurfaceInteraction& si, Vec3f dir,
                                                  const Ctx& ctx = {}) {
    const LightSet& lights = scene.lights();
    const Bsdf bsdf = scene.bsdfAt(si, dir);
    const Frame frame = shadingFrame(bsdf, si.ns);
    const Vec3f wo = frame.toLocal(-dir);
    if constexpr (!Ctx::kSpectral)
        if (bsdf.layered()) return shadeLayeredVertex(scene, draws, si, bsdf, frame, wo);
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
// on the lens or the orthographic screen.) (The renderer traces batches, estimateRadianceBatch;
// this is the reference it is tested against, and spectral mode's integrator:
// ctx chooses the colour the path carries, colour/rgb_context.h.)
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

inline void setBatchLane(DiffuseBatchInput& in, int k, const SurfaceInteraction& si, Vec3f dir,
                         Vec3f albedo, Vec2f uLight, Vec2f uDirection) {
    in.px[k] = si.p.x, in.py[k] = si.p.y, in.pz[k] = si.p.z;
    in.nx[k] = si.ns.x, in.ny[k] = si.ns.y, in.nz[k] = si.ns.z;
    in.gx[k] = si.ng.x, in.gy[k] = si.ng.y, in.gz[k] = si.ng.z;
    in.dx[k] = dir.x, in.dy[k] = dir.y, in.dz[k] = dir.z;
    in.ar[k] = albedo.x, in.ag[k] = albedo.y, in.ab[k] = albedo.z;
    in.lightU[k] = uLight.x, in.lightV[k] = uLight.y;
    in.dirU[k] = uDirection.x, in.dirV[k] = uDirection.y;
}

inline void setBatchLightSample(DiffuseBatchInput& in, int k,
                                const std::optional<LightSample>& ls) {
    in.lightValid[k] = ls.has_value();
    if (!ls) return;
    in.lightWx[k] = ls->wi.x, in.lightWy[k] = ls->wi.y, in.lightWz[k] = ls->wi.z;
    in.lightDistance[k] = ls->distance;
    in.lightR[k] = ls->radiance.x, in.lightG[k] = ls->radiance.y, in.lightB[k] = ls->radiance.z;
    in.lightPdf[k] = ls->pdf;
    in.lightDelta[k] = ls->delta;
}

// The state of the paths estimateRadianceBatch traces together. Path k's
// vertex at the current depth is in si[k] (found[k]: the ray that looked for
// it hit); specularBounce[k]: the bounce to it was specular, so its emission
// is unweighted, as the camera ray's.
struct BatchPaths {
    Vec3f beta[kBatchSamples], dir[kBatchSamples], prevPoint[kBatchSamples],
        prevNormal[kBatchSamples];
    float prevBsdfPdf[kBatchSamples] = {};
    bool alive[kBatchSamples] = {};
    bool specularBounce[kBatchSamples] = {};
    // A group's shading, reused: lanes past the live ones go to Embree too,
    // masked, and hold what an earlier group left there.
    DiffuseBatchInput in{};
    DiffuseBatchOutput out{};
};

// A vertex that is not Lambertian, shaded on its own (shadeVertex, as
// estimateRadiance's loop shades it) into lane j of a group's output.
// Returns whether the bounce is specular.
template <Sampler S>
bool shadeLaneAlone(const RenderScene& scene, S& sampler, Vec2i pixel, int sampleIndex, int depth,
                    const IntegratorSettings& settings, const SurfaceInteraction& si, Vec3f dir,
                    int j, DiffuseBatchOutput& out, PathCounters& counters) {
    VertexDimensions<S> draws(sampler, pixel, sampleIndex, depth, counters, settings.firstBounce,
                              settings.maxDepth);
    const VertexShading v = shadeVertex(scene, draws, si, dir);
    out.shadow[j] = v.direct.has_value();
    if (const auto& d = v.direct) {
        out.sox[j] = d->origin.x, out.soy[j] = d->origin.y, out.soz[j] = d->origin.z;
        out.sdx[j] = d->toLight.x, out.sdy[j] = d->toLight.y, out.sdz[j] = d->toLight.z;
        out.shadowTMax[j] = d->tMax;
        const Vec3f c = d->contribution;
        out.directR[j] = c.x, out.directG[j] = c.y, out.directB[j] = c.z;
    }
    out.bounce[j] = v.bounce.has_value();
    if (!v.bounce) return false;
    const Vec3f weight = v.weight;
    out.ox[j] = v.origin.x, out.oy[j] = v.origin.y, out.oz[j] = v.origin.z;
    out.wx[j] = v.wi.x, out.wy[j] = v.wi.y, out.wz[j] = v.wi.z;
    out.weightR[j] = weight.x, out.weightG[j] = weight.y, out.weightB[j] = weight.z;
    out.pdf[j] = v.bounce->pdf;
    return v.bounce->specular;
}

// A group's Lambertian vertices in its first lanes, the others after them;
// returns how many are Lambertian.
inline int lambertianFirst(const RenderScene& scene, const SurfaceInteraction* si, const int* paths,
                           int live, int* lane) {
    int lambertian = 0;
    if (scene.allLambertian()) {
        for (int j = 0; j < live; ++j) lane[j] = paths[j];
        return live;
    }
    for (int j = 0; j < live; ++j)
        if (scene.isLambertian(si[paths[j]].material)) lane[lambertian++] = paths[j];
    for (int j = 0, other = lambertian; j < live; ++j)
        if (!scene.isLambertian(si[paths[j]].material)) lane[other++] = paths[j];
    return lambertian;
}

// One vertex of up to kBatchLanes live paths (groupPaths[j]): the Lambertian
// ones' draws and one shadeDiffuseBatch, the others shaded one at a time
// (shadeLaneAlone), then the group's shadow rays as one Embree packet,
// Russian roulette, and its bounce rays as one packet, whose hits replace the
// paths' vertices.
template <Sampler S>
void advanceBatchLanes(const RenderScene& scene, const int* groupPaths, int live, int depth,
                       S& sampler, Vec2i pixel, int firstIndex, const IntegratorSettings& settings,
                       BatchPaths& paths, bool* found, SurfaceInteraction* si,
                       PathCounters& counters, Vec3f* L) {
    const LightSet& lights = scene.lights();
    // One area light sampled by area: the kernel samples it; otherwise each
    // lane's light sample is drawn here, one at a time.
    const AreaLight* onlyLight = lights.onlyAreaLight();
    int lane[kBatchLanes], index[kBatchLanes];
    const int lambertian = lambertianFirst(scene, si, groupPaths, live, lane);
    for (int j = 0; j < live; ++j) index[j] = firstIndex + lane[j];
    // The Lambertian paths' dimensions, one dimension for all of them at a time.
    const int base = dims::bounceBase(depth, settings.firstBounce);
    float uChoice[kBatchLanes] = {};
    Vec2f uLight[kBatchLanes], uDirection[kBatchLanes];
    const bool choice = lights.choiceUsesSample();
    if (lambertian > 0)
        drawVertexLanes(sampler, pixel, index, lambertian, base, choice, uChoice, uLight,
                        uDirection);
    counters.dimensions += uint64_t(lambertian) * (choice ? 5 : 4);
    DiffuseBatchInput& in = paths.in;
    DiffuseBatchOutput& out = paths.out;
    for (int j = 0; j < lambertian; ++j) {
        const int k = lane[j];
        setBatchLane(in, j, si[k], paths.dir[k], scene.lambertianAlbedoAt(si[k]), uLight[j],
                     uDirection[j]);
        if (!onlyLight)
            setBatchLightSample(in, j, lights.sample(si[k].p, si[k].ns, uChoice[j], uLight[j]));
    }
    if (lambertian > 0) shadeDiffuseBatch(onlyLight, scene.epsilon(), in, lambertian, out);
    for (int j = 0; j < live; ++j) {
        const int k = lane[j];
        paths.specularBounce[k] =
            j >= lambertian && shadeLaneAlone(scene, sampler, pixel, index[j], depth, settings,
                                              si[k], paths.dir[k], j, out, counters);
    }

    bool blocked[kBatchLanes];
    scene.occludedLanes(
        {out.sox, out.soy, out.soz, out.sdx, out.sdy, out.sdz, out.shadowTMax, out.shadow, live},
        blocked);
    // Russian roulette's numbers are drawn only for the paths it can end;
    // the other paths' fate is settled here.
    int continues[kBatchLanes] = {};
    float q[kBatchLanes];
    int playing[kBatchLanes], playingIndex[kBatchLanes], players = 0;
    for (int j = 0; j < live; ++j) {
        const int k = lane[j];
        if (out.shadow[j]) {
            ++counters.shadowRays;
            if (!blocked[j])
                L[k] += paths.beta[k] * Vec3f(out.directR[j], out.directG[j], out.directB[j]);
        }
        paths.alive[k] = out.bounce[j] != 0;
        if (!paths.alive[k]) continue;
        paths.beta[k] *= Vec3f(out.weightR[j], out.weightG[j], out.weightB[j]);
        paths.prevBsdfPdf[k] = out.pdf[j];
        paths.prevPoint[k] = si[k].p;
        paths.prevNormal[k] = si[k].ns;
        paths.dir[k] = {out.wx[j], out.wy[j], out.wz[j]};
        q[j] = terminationProbability(settings, depth, paths.beta[k]);
        if (q[j] > 0) {
            playing[players] = j, playingIndex[players++] = index[j];
            continue;
        }
        paths.alive[k] = !isBlack(paths.beta[k]);
        continues[j] = paths.alive[k];
        counters.rays += uint64_t(paths.alive[k]);
    }
    if (players > 0) {
        float u[kBatchLanes];
        drawLanes1D(sampler, pixel, playingIndex, players, base + dims::kRoulette, u);
        counters.dimensions += uint64_t(players);
        for (int n = 0; n < players; ++n) {
            const int j = playing[n], k = lane[j];
            paths.beta[k] *= 1 / (1 - q[j]);
            paths.alive[k] = u[n] >= q[j] && !isBlack(paths.beta[k]);
            continues[j] = paths.alive[k];
            counters.rays += uint64_t(paths.alive[k]);
        }
    }

    scene.intersectLanes({out.ox, out.oy, out.oz, out.wx, out.wy, out.wz, nullptr, continues, live},
                         lane, si, found);
}

// The paths of up to kBatchSamples consecutive samples of a pixel, traced
// together: the same estimator as estimateRadiance, bit for bit, but depth by
// depth the live paths are packed into groups of kBatchLanes — so that as
// paths end the rest still fill whole packets — and each group's Lambertian
// vertices are shaded as one shadeDiffuseBatch (the others one at a time),
// its shadow rays and bounce rays each traced as one Embree packet.
// A sampler's values are pure functions of (pixel, index, dimension, seed), so
// the draws may be made in any order. On entry found[k] and si[k] hold camera
// ray k's hit; they are the paths' working state, overwritten. L[k] receives
// path k's radiance. (The camera rays' origins are not needed: the first
// vertex's emission depends on the direction only, and later rays start at
// the vertices.)
template <Sampler S>
void estimateRadianceBatch(const RenderScene& scene, const Vec3f* dirs, bool* found,
                           SurfaceInteraction* si, int count, S& sampler, Vec2i pixel,
                           int firstIndex, const IntegratorSettings& settings,
                           PathCounters& counters, Vec3f* L) {
    static_assert(kPacketWidth == kBatchLanes, "a packet's rays are one batch's lanes");
    const LightSet& lights = scene.lights();
    BatchPaths paths;
    for (int k = 0; k < count; ++k)
        L[k] = Vec3f(0.0f), paths.beta[k] = Vec3f(1.0f), paths.dir[k] = dirs[k],
        paths.alive[k] = true;
    for (int depth = 0;; ++depth) {
        int lane[kBatchSamples], live = 0;
        for (int k = 0; k < count; ++k) {
            if (!paths.alive[k]) continue;
            addEmission(lights, found[k], si[k], paths.dir[k], paths.beta[k],
                        depth == 0 || paths.specularBounce[k], paths.prevBsdfPdf[k],
                        paths.prevPoint[k], paths.prevNormal[k], L[k]);
            paths.alive[k] = found[k] && depth != settings.maxDepth;
            if (paths.alive[k]) lane[live++] = k;
        }
        if (live == 0) return;
        for (int j0 = 0; j0 < live; j0 += kBatchLanes)
            advanceBatchLanes(scene, lane + j0, std::min(kBatchLanes, live - j0), depth, sampler,
                              pixel, firstIndex, settings, paths, found, si, counters, L);
    }
}

}  // namespace pathlab
