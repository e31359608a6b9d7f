// The paths of a batch of a pixel's samples traced together, depth by depth
// (estimateRadianceBatch): the estimator of estimateRadiance
// (path_integrator.h), bit for bit, with each group's Lambertian vertices
// shaded by one shadeDiffuseBatch (diffuse_batch.h) and its shadow and bounce
// rays traced as Embree packets.
//
// Written once for both colour modes (colour/rgb_context.h): the batch takes
// its paths' colour contexts, indexed by path — RgbPathContexts in RGB mode,
// one stateless context for all; in spectral mode an array of
// SpectralContext, each path with its own wavelengths. The kernel carries the
// context's channels (3 or 4), each with RGB mode's arithmetic, so a spectral
// path's values are those the scalar integrator computes with the same
// context: the reflectance's spectrum times the same colourless factors, in
// the same order.
#pragma once

#include <type_traits>

#include "render/diffuse_batch.h"
#include "render/path_integrator.h"

namespace pathlab {

// RGB mode's contexts of a batch's paths: the one stateless RgbContext.
struct RgbPathContexts {
    RgbContext operator[](int) const { return {}; }
};
// The context type of a batch's contexts (RgbPathContexts or a pointer to
// an array of contexts).
template <class Contexts>
using ContextOf = std::decay_t<decltype(std::declval<const Contexts&>()[0])>;

// A colour's kChannels channels into lane k of a structure-of-arrays buffer,
// and back.
template <int kChannels, class Colour>
void setLaneColour(float (*lanes)[kBatchLanes], int k, const Colour& c) {
    for (int i = 0; i < kChannels; ++i) lanes[i][k] = c[i];
}
template <class Colour, int kChannels>
Colour laneColour(const float (*lanes)[kBatchLanes], int k) {
    if constexpr (std::is_same_v<Colour, Vec3f>) {
        return {lanes[0][k], lanes[1][k], lanes[2][k]};
    } else {
        Colour c;
        for (int i = 0; i < kChannels; ++i) c[i] = lanes[i][k];
        return c;
    }
}

// Lane k's vertex, ray and draws (its colour: setLaneColour into in.albedo).
inline void setBatchLane(DiffuseBatchInput& in, int k, const SurfaceInteraction& si, Vec3f dir,
                         Vec2f uLight, Vec2f uDirection) {
    in.px[k] = si.p.x, in.py[k] = si.p.y, in.pz[k] = si.p.z;
    in.nx[k] = si.ns.x, in.ny[k] = si.ns.y, in.nz[k] = si.ns.z;
    in.gx[k] = si.ng.x, in.gy[k] = si.ng.y, in.gz[k] = si.ng.z;
    in.dx[k] = dir.x, in.dy[k] = dir.y, in.dz[k] = dir.z;
    in.lightU[k] = uLight.x, in.lightV[k] = uLight.y;
    in.dirU[k] = uDirection.x, in.dirV[k] = uDirection.y;
}
// The same with an RGB albedo.
inline void setBatchLane(DiffuseBatchInput& in, int k, const SurfaceInteraction& si, Vec3f dir,
                         Vec3f albedo, Vec2f uLight, Vec2f uDirection) {
    setBatchLane(in, k, si, dir, uLight, uDirection);
    setLaneColour<3>(in.albedo, k, albedo);
}

// Lane k's light sample, its radiance in the colour of context ctx.
template <class Ctx = RgbContext>
void setBatchLightSample(DiffuseBatchInput& in, int k, const std::optional<LightSample>& ls,
                         const Ctx& ctx = {}) {
    in.lightValid[k] = ls.has_value();
    if (!ls) return;
    in.lightWx[k] = ls->wi.x, in.lightWy[k] = ls->wi.y, in.lightWz[k] = ls->wi.z;
    in.lightDistance[k] = ls->distance;
    setLaneColour<Ctx::kChannels>(in.lightRadiance, k, ctx.emission(ls->radiance));
    in.lightPdf[k] = ls->pdf;
    in.lightDelta[k] = ls->delta;
}

// The state of the paths estimateRadianceBatch traces together. Path k's
// vertex at the current depth is in si[k] (found[k]: the ray that looked for
// it hit); specularBounce[k]: the bounce to it was specular, so its emission
// is unweighted, as the camera ray's. One per thread, reused by every call,
// which resets the paths it traces: zeroing ≈ 5 KB (more in spectral mode)
// for every pixel of a 1-spp pass cost as much as tracing it.
template <class Colour>
struct BatchPathsOf {
    Colour beta[kBatchSamples];
    Vec3f dir[kBatchSamples], prevPoint[kBatchSamples], prevNormal[kBatchSamples];
    float prevBsdfPdf[kBatchSamples] = {};
    bool alive[kBatchSamples] = {};
    bool specularBounce[kBatchSamples] = {};
    // Spectral mode with one area light sampled by area: its emission at
    // each path's wavelengths, converted once per path rather than per vertex.
    Colour onlyLightEmission[kBatchSamples];
    // A group's shading, reused: lanes past the live ones go to Embree too,
    // masked, and hold what an earlier group left there.
    DiffuseBatchInput in{};
    DiffuseBatchOutput out{};
};

// A vertex that is not Lambertian, shaded on its own (shadeVertex, as
// estimateRadiance's loop shades it) into lane j of a group's output.
// Returns whether the bounce is specular.
template <Sampler S, class Ctx>
bool shadeLaneAlone(const RenderScene& scene, S& sampler, Vec2i pixel, int sampleIndex, int depth,
                    const IntegratorSettings& settings, const SurfaceInteraction& si, Vec3f dir,
                    int j, DiffuseBatchOutput& out, PathCounters& counters, const Ctx& ctx) {
    VertexDimensions<S> draws(sampler, pixel, sampleIndex, depth, counters, settings.firstBounce,
                              settings.maxDepth);
    const auto v = shadeVertex(scene, draws, si, dir, ctx);
    out.shadow[j] = v.direct.has_value();
    if (const auto& d = v.direct) {
        out.sox[j] = d->origin.x, out.soy[j] = d->origin.y, out.soz[j] = d->origin.z;
        out.sdx[j] = d->toLight.x, out.sdy[j] = d->toLight.y, out.sdz[j] = d->toLight.z;
        out.shadowTMax[j] = d->tMax;
        setLaneColour<Ctx::kChannels>(out.direct, j, d->contribution);
    }
    out.bounce[j] = v.bounce.has_value();
    if (!v.bounce) return false;
    out.ox[j] = v.origin.x, out.oy[j] = v.origin.y, out.oz[j] = v.origin.z;
    out.wx[j] = v.wi.x, out.wy[j] = v.wi.y, out.wz[j] = v.wi.z;
    setLaneColour<Ctx::kChannels>(out.weight, j, v.weight);
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

// The kernel's input for a group's Lambertian vertices (lanes 0 … lambertian
// − 1, paths lane[j]): vertex, draws, the reflectance in the path's colour and,
// unless the kernel samples the only light, the light sample.
template <class Contexts, class Colour = typename ContextOf<Contexts>::Colour>
void setLambertianLanes(const RenderScene& scene, const int* lane, int lambertian,
                        const float* uChoice, const Vec2f* uLight, const Vec2f* uDirection,
                        const SurfaceInteraction* si, BatchPathsOf<Colour>& paths,
                        const Contexts& ctx) {
    using Ctx = ContextOf<Contexts>;
    const LightSet& lights = scene.lights();
    const bool onlyLight = lights.onlyAreaLight() != nullptr;
    DiffuseBatchInput& in = paths.in;
    for (int j = 0; j < lambertian; ++j) {
        const int k = lane[j];
        const Ctx& c = ctx[k];
        setBatchLane(in, j, si[k], paths.dir[k], uLight[j], uDirection[j]);
        setLaneColour<Ctx::kChannels>(in.albedo, j, c.reflectance(scene.lambertianAlbedoAt(si[k])));
        if (!onlyLight)
            setBatchLightSample(in, j, lights.sample(si[k].p, si[k].ns, uChoice[j], uLight[j]), c);
        else if constexpr (Ctx::kSpectral)
            setLaneColour<Ctx::kChannels>(in.lightRadiance, j, paths.onlyLightEmission[k]);
    }
}

// One vertex of up to kBatchLanes live paths (groupPaths[j]): the Lambertian
// ones' draws and one shadeDiffuseBatch, the others shaded one at a time
// (shadeLaneAlone), then the group's shadow rays as one Embree packet,
// Russian roulette, and its bounce rays as one packet, whose hits replace the
// paths' vertices.
template <Sampler S, class Contexts, class Colour = typename ContextOf<Contexts>::Colour>
void advanceBatchLanes(const RenderScene& scene, const int* groupPaths, int live, int depth,
                       S& sampler, Vec2i pixel, int firstIndex, const IntegratorSettings& settings,
                       BatchPathsOf<Colour>& paths, bool* found, SurfaceInteraction* si,
                       PathCounters& counters, Colour* L, const Contexts& ctx) {
    using Ctx = ContextOf<Contexts>;
    constexpr int kChannels = Ctx::kChannels;
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
    DiffuseBatchOutput& out = paths.out;
    setLambertianLanes(scene, lane, lambertian, uChoice, uLight, uDirection, si, paths, ctx);
    if (lambertian > 0) {
        if constexpr (Ctx::kSpectral)
            shadeDiffuseBatchSpectral(onlyLight, scene.epsilon(), paths.in, lambertian, out);
        else
            shadeDiffuseBatch(onlyLight, scene.epsilon(), paths.in, lambertian, out);
    }
    for (int j = 0; j < live; ++j) {
        const int k = lane[j];
        paths.specularBounce[k] =
            j >= lambertian && shadeLaneAlone(scene, sampler, pixel, index[j], depth, settings,
                                              si[k], paths.dir[k], j, out, counters, ctx[k]);
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
            if (!blocked[j]) L[k] += paths.beta[k] * laneColour<Colour, kChannels>(out.direct, j);
        }
        paths.alive[k] = out.bounce[j] != 0;
        if (!paths.alive[k]) continue;
        paths.beta[k] *= laneColour<Colour, kChannels>(out.weight, j);
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
// path k's radiance in the colour of its context ctx[k]. (The camera rays'
// origins are not needed: the first vertex's emission depends on the
// direction only, and later rays start at the vertices.)
template <Sampler S, class Contexts = RgbPathContexts>
void estimateRadianceBatch(const RenderScene& scene, const Vec3f* dirs, bool* found,
                           SurfaceInteraction* si, int count, S& sampler, Vec2i pixel,
                           int firstIndex, const IntegratorSettings& settings,
                           PathCounters& counters, typename ContextOf<Contexts>::Colour* L,
                           const Contexts& ctx = {}) {
    using Colour = typename ContextOf<Contexts>::Colour;
    static_assert(kPacketWidth == kBatchLanes, "a packet's rays are one batch's lanes");
    static_assert(ContextOf<Contexts>::kChannels <= kMaxBatchChannels);
    const LightSet& lights = scene.lights();
    static thread_local BatchPathsOf<Colour> paths;
    for (int k = 0; k < count; ++k) {
        L[k] = Colour(0.0f), paths.beta[k] = Colour(1.0f), paths.dir[k] = dirs[k];
        paths.prevPoint[k] = paths.prevNormal[k] = Vec3f(0.0f);
        paths.prevBsdfPdf[k] = 0, paths.alive[k] = true, paths.specularBounce[k] = false;
    }
    if constexpr (ContextOf<Contexts>::kSpectral)
        if (const AreaLight* light = lights.onlyAreaLight())
            for (int k = 0; k < count; ++k)
                paths.onlyLightEmission[k] = ctx[k].emission(light->radiance);
    for (int depth = 0;; ++depth) {
        int lane[kBatchSamples], live = 0;
        for (int k = 0; k < count; ++k) {
            if (!paths.alive[k]) continue;
            addEmission(lights, found[k], si[k], paths.dir[k], paths.beta[k],
                        depth == 0 || paths.specularBounce[k], paths.prevBsdfPdf[k],
                        paths.prevPoint[k], paths.prevNormal[k], L[k], ctx[k]);
            paths.alive[k] = found[k] && depth != settings.maxDepth;
            if (paths.alive[k]) lane[live++] = k;
        }
        if (live == 0) return;
        for (int j0 = 0; j0 < live; j0 += kBatchLanes)
            advanceBatchLanes(scene, lane + j0, std::min(kBatchLanes, live - j0), depth, sampler,
                              pixel, firstIndex, settings, paths, found, si, counters, L, ctx);
    }
}

}  // namespace pathlab
