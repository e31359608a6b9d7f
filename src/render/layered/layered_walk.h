// The layered BSDF's random walks (layered_bsdf.h) for any colour the path
// carries. The walk itself is colourless — the coating's Fresnel and
// microfacet terms, the medium's transmittance and phase function do not
// depend on the wavelength — and only the medium's albedo and the base's
// values are coloured, so the walk is written once against a `Colours`
// policy:
//   using Colour                                — Vec3f or spectral::SampledSpectrum
//   Colour albedo                               — the medium's single-scattering albedo
//   Colour grey(Vec3f v)                        — a colourless value (v.x = v.y = v.z)
//   Colour baseF(Vec3f wo, Vec3f wi)            — the base's f
//   Colour sampledBaseF(Vec3f wo, const BsdfSample& s) — f of a sample the base drew
//   float maxOf(const Colour&)                  — the largest component
// RgbLayerColours is RGB mode's, with which fIn and sampleIn are the
// LayeredBsdf's f and sample, operation for operation; spectral mode's is in
// render/colour/spectral_layered.cpp. Only layered_bsdf.cpp and that file
// include this.
#pragma once

#include <algorithm>
#include <cmath>

#include "render/layered/layered_bsdf.h"
#include "render/sampling_routines.h"

namespace pathlab {

struct RgbLayerColours {
    using Colour = Vec3f;
    const Bsdf* base;
    Vec3f albedo;
    Vec3f grey(Vec3f v) const { return v; }
    Vec3f baseF(Vec3f wo, Vec3f wi) const { return base->f(wo, wi); }
    Vec3f sampledBaseF(Vec3f, const BsdfSample& s) const { return s.f; }
    static float maxOf(Vec3f c) { return maxComponent(c); }
};

namespace layered_walk {

inline bool usable(const std::optional<BsdfSample>& s) {
    return s && !isBlack(s->f) && s->pdf > 0 && s->wi.z != 0;
}

// A distance along z to the next interaction in a medium of σt = 1 seen
// along a direction of |cosθ| = cosAbs: exponential in the path length.
inline float sampleDepth(float u, float cosAbs) {
    return -std::log1p(-u) * cosAbs;
}

// Russian roulette inside the walk, pbrt-v4's rule: after four events, when
// the throughput's largest component is below ¼. False: the walk ends.
inline bool walkSurvives(int depth, float throughput, WalkNumbers& r, float* scale) {
    *scale = 1;
    if (depth <= 3 || throughput >= 0.25f) return true;
    const float q = std::max(0.0f, 1 - throughput);
    if (r.next() < q) return false;
    *scale = 1 - q;
    return true;
}

inline Vec2f next2D(WalkNumbers& r) {
    const float x = r.next();
    return {x, r.next()};
}

}  // namespace layered_walk

template <class Colours>
typename Colours::Colour LayeredBsdf::fIn(Vec3f wo, Vec3f wi, WalkNumbers& r,
                                          const Colours& c) const {
    using namespace layered_walk;
    using Colour = typename Colours::Colour;
    if (wo.z < 0) wo = -wo, wi = -wi;
    // The base is opaque: nothing reaches the other side.
    if (!sameHemisphere(wo, wi)) return Colour(0.0f);
    const int n = params_.nSamples;
    Colour f = c.grey(top_.f(wo, wi, Transport::Radiance) * float(n));
    for (int s = 0; s < n; ++s) {
        // Into the layers along wo, and from the light's side along wi.
        const float uo = r.next();
        const auto wos = top_.sample(wo, uo, next2D(r), Transport::Radiance, Lobes::Transmission);
        if (!usable(wos)) continue;
        const float ui = r.next();
        const auto wis = top_.sample(wi, ui, next2D(r), Transport::Importance, Lobes::Transmission);
        if (!usable(wis)) continue;
        f += walkF(wi, *wos, *wis, r, c);
    }
    return f / float(n);
}

// One walk of the evaluation: from the coating's transmitted sample wos,
// connecting each event to wi through the coating, either along the
// presampled wis or along the event's own sampled direction, the two
// combined by the power heuristic (pbrt-v4's LayeredBxDF::f).
template <class Colours>
typename Colours::Colour LayeredBsdf::walkF(Vec3f wi, const BsdfSample& wos, const BsdfSample& wis,
                                            WalkNumbers& r, const Colours& c) const {
    using namespace layered_walk;
    using Colour = typename Colours::Colour;
    const float exitZ = params_.thickness;
    const bool scatters = !isBlack(params_.albedo);
    Colour f(0.0f), beta = c.grey(wos.f * (absCosTheta(wos.wi) / wos.pdf));
    float z = params_.thickness;
    Vec3f w = wos.wi;
    for (int depth = 0; depth < params_.maxDepth; ++depth) {
        float rr;
        if (!walkSurvives(depth, c.maxOf(beta), r, &rr)) break;
        beta = beta / rr;
        if (!scatters) {
            z = z == params_.thickness ? 0 : params_.thickness;
            beta *= transmittance(params_.thickness, w);
        } else {
            const float dz = sampleDepth(r.next(), absCosTheta(w));
            const float zp = w.z > 0 ? z + dz : z - dz;
            if (zp == z) continue;
            if (0 < zp && zp < params_.thickness) {
                // Scattering in the medium: connect to wis, then sample the phase function.
                const float pPhase = henyeyGreenstein(-w, -wis.wi, params_.g);
                const float wt = top_.isSpecular() ? 1 : powerHeuristic(wis.pdf, pPhase);
                f += beta * c.albedo * c.grey(wis.f) *
                     (pPhase * wt * transmittance(zp - exitZ, wis.wi) / wis.pdf);
                const Vec3f wp = sampleHenyeyGreenstein(-w, params_.g, next2D(r));
                if (wp.z == 0) continue;
                const float phasePdf = henyeyGreenstein(-w, wp, params_.g);
                beta *= c.albedo;  // the phase function's weight p/pdf is 1
                w = wp, z = zp;
                if (z < exitZ && w.z > 0 && !top_.isSpecular()) {
                    const Vec3f fExit = top_.f(-w, wi, Transport::Radiance);
                    if (!isBlack(fExit)) {
                        const float exitPdf = connectionPdf(wi, w);
                        const float wtExit = powerHeuristic(phasePdf, exitPdf);
                        f += beta * c.grey(fExit) * (transmittance(zp - exitZ, w) * wtExit);
                    }
                }
                continue;
            }
            z = std::clamp(zp, 0.0f, params_.thickness);
        }
        if (z == exitZ) {
            // Back up at the coating: reflect inside it.
            const float uc = r.next();
            const auto bs = top_.sample(-w, uc, next2D(r), Transport::Radiance, Lobes::Reflection);
            if (!usable(bs)) break;
            beta *= c.grey(bs->f * (absCosTheta(bs->wi) / bs->pdf));
            w = bs->wi;
            continue;
        }
        // At the base: connect to wis, then sample the base.
        if (!bottom_.isSpecular()) {
            const float wt =
                top_.isSpecular() ? 1 : powerHeuristic(wis.pdf, bottom_.pdf(-w, -wis.wi));
            f += beta * c.baseF(-w, -wis.wi) * c.grey(wis.f) *
                 (absCosTheta(wis.wi) * wt * transmittance(params_.thickness, wis.wi) / wis.pdf);
        }
        const float uc = r.next();
        const auto bs = bottom_.sample(-w, uc, next2D(r));
        if (!usable(bs)) break;
        beta *= c.sampledBaseF(-w, *bs) * (absCosTheta(bs->wi) / bs->pdf);
        w = bs->wi;
        if (!top_.isSpecular()) {
            const Vec3f fExit = top_.f(-w, wi, Transport::Radiance);
            if (!isBlack(fExit)) {
                float wt = 1;
                if (!bottom_.isSpecular()) wt = powerHeuristic(bs->pdf, connectionPdf(wi, w));
                f += beta * c.grey(fExit) * (transmittance(params_.thickness, bs->wi) * wt);
            }
        }
    }
    return f;
}

template <class Colours>
std::optional<LayeredSampleOf<typename Colours::Colour>> LayeredBsdf::sampleIn(
    Vec3f wo, float uc, Vec2f u, WalkNumbers& r, const Colours& c) const {
    using namespace layered_walk;
    using Colour = typename Colours::Colour;
    using Sample = LayeredSampleOf<Colour>;
    const bool flip = wo.z < 0;
    if (flip) wo = -wo;
    auto bs = top_.sample(wo, uc, u, Transport::Radiance);
    if (!usable(bs)) return std::nullopt;
    if (sameHemisphere(wo, bs->wi)) {  // reflected by the coating itself
        if (flip) bs->wi = -bs->wi;
        bs->pdfIsProportional = true;
        return Sample{*bs, c.grey(bs->f)};
    }
    Vec3f w = bs->wi;
    bool specularPath = bs->specular;
    Colour f = c.grey(bs->f * absCosTheta(bs->wi));
    float pdf = bs->pdf, z = params_.thickness;
    for (int depth = 0; depth < params_.maxDepth; ++depth) {
        float rr;
        if (!walkSurvives(depth, c.maxOf(f) / pdf, r, &rr)) return std::nullopt;
        pdf *= rr;
        if (w.z == 0) return std::nullopt;
        if (!isBlack(params_.albedo)) {
            const float dz = sampleDepth(r.next(), absCosTheta(w));
            const float zp = w.z > 0 ? z + dz : z - dz;
            if (zp == z) return std::nullopt;
            if (0 < zp && zp < params_.thickness) {
                const Vec3f wp = sampleHenyeyGreenstein(-w, params_.g, next2D(r));
                const float p = henyeyGreenstein(-w, wp, params_.g);
                if (!(p > 0) || wp.z == 0) return std::nullopt;
                f *= c.albedo * p;
                pdf *= p;
                specularPath = false;
                w = wp, z = zp;
                continue;
            }
            z = std::clamp(zp, 0.0f, params_.thickness);
        } else {
            z = z == params_.thickness ? 0 : params_.thickness;
            f *= transmittance(params_.thickness, w);
        }
        const float uLayer = r.next();
        const Vec2f uDir = next2D(r);
        bs = z == 0 ? bottom_.sample(-w, uLayer, uDir)
                    : top_.sample(-w, uLayer, uDir, Transport::Radiance);
        if (!usable(bs)) return std::nullopt;
        f *= z == 0 ? c.sampledBaseF(-w, *bs) : c.grey(bs->f);
        pdf *= bs->pdf;
        specularPath = specularPath && bs->specular;
        w = bs->wi;
        if (z != 0 && w.z > 0) {  // through the coating: out of the layers
            BsdfSample out{flip ? -w : w, Vec3f(0.0f), pdf, specularPath};
            out.pdfIsProportional = true;
            return Sample{out, f};
        }
        f *= absCosTheta(bs->wi);
    }
    return std::nullopt;
}

}  // namespace pathlab
