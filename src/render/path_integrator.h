// Unidirectional path tracing of the rendering equation (Kajiya 1986) with
// next-event estimation and BSDF sampling combined by multiple importance
// sampling (Veach & Guibas 1995, power heuristic), Russian roulette, and a
// maximum depth counted as pbrt-v4 does (1 = direct lighting only).
//
// Every random number comes from the sampler, in the fixed layout of
// sampling/sampler.h: vertex `depth` owns the block of dimensions starting at
// dims::bounceBase(depth), so a bounce's dimensions never depend on what earlier
// bounces drew. A vertex draws only the dimensions it uses (no light choice with
// one light, no lobe choice off glass, no light sample at a specular vertex, no
// roulette before it starts) and skips the others: a sampler's value is a pure
// function of (pixel, index, dimension, seed), so skipping changes no value that
// is drawn — it only saves computing those that would be thrown away.
#pragma once

#include <limits>

#include "render/integrator_settings.h"
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
    VertexDimensions(S& sampler, Vec2i pixel, int sampleIndex, int depth, PathCounters& counters)
        : sampler_(sampler),
          pixel_(pixel),
          index_(sampleIndex),
          base_(dims::bounceBase(depth)),
          counters_(counters) {}
    float get1D(int offset) {
        seek(offset, 1);
        return sampler_.get1D();
    }
    Vec2f get2D(int offset) {
        seek(offset, 2);
        return sampler_.get2D();
    }

  private:
    void seek(int offset, int count) {
        if (offset != next_) sampler_.startPixelSample(pixel_, index_, base_ + offset);
        next_ = offset + count;
        counters_.dimensions += uint64_t(count);
    }
    S& sampler_;
    Vec2i pixel_;
    int index_, base_;
    int next_ = -1;  // the offset the sampler would produce next
    PathCounters& counters_;
};

// Next-event estimation at a non-specular vertex: one light sample, weighted
// against the BSDF's density for the same direction (power heuristic).
inline Vec3f estimateDirect(const RenderScene& scene, const SurfaceInteraction& si,
                            const Frame& frame, const Bsdf& bsdf, Vec3f wo, float uChoice,
                            Vec2f uLight, PathCounters& counters) {
    const auto ls = scene.lights().sample(si.p, si.ns, uChoice, uLight);
    if (!ls) return Vec3f(0.0f);
    const Vec3f wi = frame.toLocal(ls->wi);
    const Vec3f f = bsdf.f(wo, wi) * absCosTheta(wi);
    if (isBlack(f)) return Vec3f(0.0f);
    ++counters.shadowRays;
    // The shadow ray runs from the nudged origin to the light point itself, as
    // pbrt-v4's SpawnRayTo: with the unnormalised difference as its direction,
    // t = 1 is the light, and it stops at 1 − 10⁻⁴ so it cannot hit the light
    // and block itself. (A ray along wi from the nudged origin runs parallel to
    // the segment, ε off it, and crosses the light's plane up to ε/cosθ early:
    // grazing samples of a nearby light were blocked by the light.)
    const Vec3f origin = scene.offsetOrigin(si, ls->wi);
    const bool blocked =
        std::isinf(ls->distance)
            ? scene.occluded(origin, ls->wi, ls->distance)
            : scene.occluded(origin, si.p + ls->wi * ls->distance - origin, 1 - 1e-4f);
    if (blocked) return Vec3f(0.0f);
    const float weight = powerHeuristic(ls->pdf, bsdf.pdf(wo, wi));
    return f * ls->radiance * (weight / ls->pdf);
}

// The radiance arriving along a path whose first segment (origin → first
// surface, or escape when !found) has already been traced: the camera rays of
// a pixel are traced together as a packet (renderer.cpp). Later rays are traced
// here one at a time.
template <Sampler S>
Vec3f estimateRadiance(const RenderScene& scene, Vec3f origin, Vec3f dir, bool found,
                       SurfaceInteraction si, S& sampler, Vec2i pixel, int sampleIndex,
                       const IntegratorSettings& settings, PathCounters& counters) {
    const LightSet& lights = scene.lights();
    Vec3f L(0.0f), beta(1.0f), prevPoint, prevNormal;
    bool specularBounce = false;
    float prevBsdfPdf = 0;
    for (int depth = 0;; ++depth) {
        if (depth > 0) {
            ++counters.rays;
            found = scene.intersect(origin, dir, &si);
        }
        const bool unweighted = depth == 0 || specularBounce;
        if (!found) {
            const Vec3f env = lights.environment();
            if (!isBlack(env))
                L += beta * env *
                     (unweighted ? 1.0f : powerHeuristic(prevBsdfPdf, lights.pdfEnvironment()));
            break;
        }
        if (si.light >= 0) {
            const Vec3f Le = lights.areaLight(si.light).emitted(-dir);
            if (!isBlack(Le))
                L += beta * Le *
                     (unweighted
                          ? 1.0f
                          : powerHeuristic(prevBsdfPdf, lights.pdfAreaLight(si.light, prevPoint,
                                                                            prevNormal, si.p)));
        }
        if (depth == settings.maxDepth) break;

        VertexDimensions<S> draws(sampler, pixel, sampleIndex, depth, counters);
        const Bsdf bsdf = scene.bsdfAt(si);
        const Frame frame(si.ns);
        const Vec3f wo = frame.toLocal(-dir);
        if (!bsdf.isSpecular()) {
            const float uChoice = lights.choiceUsesSample() ? draws.get1D(dims::kLightChoice) : 0;
            const Vec2f uLight = draws.get2D(dims::kLightPoint);
            L += beta * estimateDirect(scene, si, frame, bsdf, wo, uChoice, uLight, counters);
        }

        const float uLobe = bsdf.usesLobeSample() ? draws.get1D(dims::kBsdfLobe) : 0;
        const Vec2f uDirection =
            bsdf.usesDirectionSample() ? draws.get2D(dims::kBsdfDirection) : Vec2f{};
        const auto bs = bsdf.sample(wo, uLobe, uDirection);
        if (!bs) break;
        const Vec3f wi = frame.toWorld(bs->wi);
        beta *= bs->weight();
        specularBounce = bs->specular;
        prevBsdfPdf = bs->pdf;
        prevPoint = si.p;
        prevNormal = si.ns;
        origin = scene.offsetOrigin(si, wi);
        dir = wi;

        if (settings.russianRoulette && depth >= settings.rouletteDepth) {
            const float q = std::max(0.0f, 1 - maxComponent(beta));
            if (q > 0 && draws.get1D(dims::kRoulette) < q) break;
            beta *= 1 / (1 - q);
        }
        if (isBlack(beta)) break;
    }
    return L;
}

}  // namespace pathlab
