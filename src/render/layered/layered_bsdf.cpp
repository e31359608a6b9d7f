#include "render/layered/layered_bsdf.h"

#include <algorithm>
#include <limits>

#include "render/sampling_routines.h"

namespace pathlab {
namespace {

bool usable(const std::optional<BsdfSample>& s) {
    return s && !isBlack(s->f) && s->pdf > 0 && s->wi.z != 0;
}

// A distance along z to the next interaction in a medium of σt = 1 seen
// along a direction of |cosθ| = cosAbs: exponential in the path length.
float sampleDepth(float u, float cosAbs) {
    return -std::log1p(-u) * cosAbs;
}

// Russian roulette inside the walk, pbrt-v4's rule: after four events, when
// the throughput's largest component is below ¼. False: the walk ends.
bool walkSurvives(int depth, float throughput, WalkNumbers& r, float* scale) {
    *scale = 1;
    if (depth <= 3 || throughput >= 0.25f) return true;
    const float q = std::max(0.0f, 1 - throughput);
    if (r.next() < q) return false;
    *scale = 1 - q;
    return true;
}

Vec2f next2D(WalkNumbers& r) {
    const float x = r.next();
    return {x, r.next()};
}

}  // namespace

float henyeyGreenstein(Vec3f wo, Vec3f wi, float g) {
    const float denom = 1 + g * g + 2 * g * dot(wo, wi);
    return (1 - g * g) / (4 * kPi * denom * std::sqrt(std::max(denom, 1e-12f)));
}

Vec3f sampleHenyeyGreenstein(Vec3f wo, float g, Vec2f u) {
    // The cosine of the scattering angle about the propagation direction −wo,
    // by inverting the phase function's CDF (Pharr et al. 2023, eq. 11.12).
    float cosS;
    if (std::abs(g) < 1e-3f) {
        cosS = 1 - 2 * u.x;
    } else {
        const float s = (1 - g * g) / (1 - g + 2 * g * u.x);
        cosS = std::clamp((1 + g * g - s * s) / (2 * g), -1.0f, 1.0f);
    }
    const float sinS = std::sqrt(std::max(0.0f, 1 - cosS * cosS));
    const float phi = 2 * kPi * u.y;
    const Frame frame(-wo);
    return frame.toWorld(Vec3f(sinS * std::cos(phi), sinS * std::sin(phi), cosS));
}

LayeredBsdf::LayeredBsdf(DielectricInterface coating, Bsdf base, LayerParameters params)
    : top_(coating), bottom_(base), params_(params) {
    params_.thickness = std::max(params_.thickness, std::numeric_limits<float>::min());
    params_.maxDepth = std::max(params_.maxDepth, 0);
    params_.nSamples = std::max(params_.nSamples, 1);
}

bool LayeredBsdf::isSpecular() const {
    return top_.isSpecular() && bottom_.isSpecular() && isBlack(params_.albedo);
}

// The density, over directions inside the layers, with which the presampled
// connection (wis, sampled from wi through the coating) would have produced
// the inner direction −w: the weight against an event's own sample w must
// compare densities of the same variable. (pbrt-v4 takes the coating's
// density of wi given −w instead, a density over outer directions; with a
// rough coating the two weights then do not sum to one, and its estimate of
// f is biased — 7% too high for a rough coating (α = 0.3) over a Lambertian
// base, tested in LayeredBsdf.SampleWeightsMatchTheValueByDirection.)
float LayeredBsdf::connectionPdf(Vec3f wi, Vec3f w) const {
    return top_.pdf(wi, -w, Transport::Importance, Lobes::Transmission);
}

float LayeredBsdf::transmittance(float dz, Vec3f w) const {
    if (std::abs(dz) <= std::numeric_limits<float>::min()) return 1;
    return std::exp(-std::abs(dz / w.z));
}

Vec3f LayeredBsdf::f(Vec3f wo, Vec3f wi, WalkNumbers& r) const {
    if (wo.z < 0) wo = -wo, wi = -wi;
    // The base is opaque: nothing reaches the other side.
    if (!sameHemisphere(wo, wi)) return Vec3f(0.0f);
    const int n = params_.nSamples;
    Vec3f f = top_.f(wo, wi, Transport::Radiance) * float(n);
    for (int s = 0; s < n; ++s) {
        // Into the layers along wo, and from the light's side along wi.
        const float uo = r.next();
        const auto wos = top_.sample(wo, uo, next2D(r), Transport::Radiance, Lobes::Transmission);
        if (!usable(wos)) continue;
        const float ui = r.next();
        const auto wis = top_.sample(wi, ui, next2D(r), Transport::Importance, Lobes::Transmission);
        if (!usable(wis)) continue;
        f += walkF(wo, wi, *wos, *wis, r);
    }
    return f / float(n);
}

// One walk of the evaluation: from the coating's transmitted sample wos,
// connecting each event to wi through the coating, either along the
// presampled wis or along the event's own sampled direction, the two
// combined by the power heuristic (pbrt-v4's LayeredBxDF::f).
Vec3f LayeredBsdf::walkF(Vec3f, Vec3f wi, const BsdfSample& wos, const BsdfSample& wis,
                         WalkNumbers& r) const {
    const float exitZ = params_.thickness;
    const bool scatters = !isBlack(params_.albedo);
    Vec3f f(0.0f), beta = wos.f * (absCosTheta(wos.wi) / wos.pdf);
    float z = params_.thickness;
    Vec3f w = wos.wi;
    for (int depth = 0; depth < params_.maxDepth; ++depth) {
        float rr;
        if (!walkSurvives(depth, maxComponent(beta), r, &rr)) break;
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
                f += beta * params_.albedo * wis.f *
                     (pPhase * wt * transmittance(zp - exitZ, wis.wi) / wis.pdf);
                const Vec3f wp = sampleHenyeyGreenstein(-w, params_.g, next2D(r));
                if (wp.z == 0) continue;
                const float phasePdf = henyeyGreenstein(-w, wp, params_.g);
                beta *= params_.albedo;  // the phase function's weight p/pdf is 1
                w = wp, z = zp;
                if (z < exitZ && w.z > 0 && !top_.isSpecular()) {
                    const Vec3f fExit = top_.f(-w, wi, Transport::Radiance);
                    if (!isBlack(fExit)) {
                        const float exitPdf = connectionPdf(wi, w);
                        const float wtExit = powerHeuristic(phasePdf, exitPdf);
                        f += beta * fExit * (transmittance(zp - exitZ, w) * wtExit);
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
            beta *= bs->f * (absCosTheta(bs->wi) / bs->pdf);
            w = bs->wi;
            continue;
        }
        // At the base: connect to wis, then sample the base.
        if (!bottom_.isSpecular()) {
            const float wt =
                top_.isSpecular() ? 1 : powerHeuristic(wis.pdf, bottom_.pdf(-w, -wis.wi));
            f += beta * bottom_.f(-w, -wis.wi) * wis.f *
                 (absCosTheta(wis.wi) * wt * transmittance(params_.thickness, wis.wi) / wis.pdf);
        }
        const float uc = r.next();
        const auto bs = bottom_.sample(-w, uc, next2D(r));
        if (!usable(bs)) break;
        beta *= bs->f * (absCosTheta(bs->wi) / bs->pdf);
        w = bs->wi;
        if (!top_.isSpecular()) {
            const Vec3f fExit = top_.f(-w, wi, Transport::Radiance);
            if (!isBlack(fExit)) {
                float wt = 1;
                if (!bottom_.isSpecular()) wt = powerHeuristic(bs->pdf, connectionPdf(wi, w));
                f += beta * fExit * (transmittance(params_.thickness, bs->wi) * wt);
            }
        }
    }
    return f;
}

std::optional<BsdfSample> LayeredBsdf::sample(Vec3f wo, float uc, Vec2f u, WalkNumbers& r) const {
    const bool flip = wo.z < 0;
    if (flip) wo = -wo;
    auto bs = top_.sample(wo, uc, u, Transport::Radiance);
    if (!usable(bs)) return std::nullopt;
    if (sameHemisphere(wo, bs->wi)) {  // reflected by the coating itself
        if (flip) bs->wi = -bs->wi;
        bs->pdfIsProportional = true;
        return bs;
    }
    Vec3f w = bs->wi;
    bool specularPath = bs->specular;
    Vec3f f = bs->f * absCosTheta(bs->wi);
    float pdf = bs->pdf, z = params_.thickness;
    for (int depth = 0; depth < params_.maxDepth; ++depth) {
        float rr;
        if (!walkSurvives(depth, maxComponent(f) / pdf, r, &rr)) return std::nullopt;
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
                f *= params_.albedo * p;
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
        f *= bs->f;
        pdf *= bs->pdf;
        specularPath = specularPath && bs->specular;
        w = bs->wi;
        if (z != 0 && w.z > 0) {  // through the coating: out of the layers
            BsdfSample out{flip ? -w : w, f, pdf, specularPath};
            out.pdfIsProportional = true;
            return out;
        }
        f *= absCosTheta(bs->wi);
    }
    return std::nullopt;
}

float LayeredBsdf::pdf(Vec3f wo, Vec3f wi, WalkNumbers& r) const {
    if (wo.z < 0) wo = -wo, wi = -wi;
    float pdfSum = 0;
    if (sameHemisphere(wo, wi)) {
        const int n = params_.nSamples;
        pdfSum = float(n) * top_.pdf(wo, wi, Transport::Radiance, Lobes::Reflection);
        for (int s = 0; s < n; ++s) pdfSum += pdfThreeSegments(wo, wi, r);
        pdfSum /= float(n);
    }
    // Mixed with the uniform sphere density, as pbrt-v4 does, so that the
    // estimate is never zero where the walk can go.
    return 0.1f * uniformSpherePdf() + 0.9f * pdfSum;
}

// One estimate of the density of the paths that enter the coating, reflect
// once at the base and leave (transmission, reflection, transmission): the
// base's density between the two refracted directions, or where both are
// rough the two one-sided estimates combined by the power heuristic.
float LayeredBsdf::pdfThreeSegments(Vec3f wo, Vec3f wi, WalkNumbers& r) const {
    const float uo = r.next();
    const auto wos = top_.sample(wo, uo, next2D(r), Transport::Radiance, Lobes::Transmission);
    const float ui = r.next();
    const auto wis = top_.sample(wi, ui, next2D(r), Transport::Importance, Lobes::Transmission);
    if (!usable(wos) || !usable(wis)) return 0;
    if (top_.isSpecular()) return bottom_.pdf(-wos->wi, -wis->wi);
    const float uc = r.next();
    const auto rs = bottom_.sample(-wos->wi, uc, next2D(r));
    if (!usable(rs)) return 0;
    if (bottom_.isSpecular()) return top_.pdf(-rs->wi, wi, Transport::Radiance);
    const float rPdf = bottom_.pdf(-wos->wi, -wis->wi);
    const float tPdf = top_.pdf(-rs->wi, wi, Transport::Radiance);
    return powerHeuristic(wis->pdf, rPdf) * rPdf + powerHeuristic(rs->pdf, tPdf) * tPdf;
}

}  // namespace pathlab
