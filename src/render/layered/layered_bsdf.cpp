#include "render/layered/layered_bsdf.h"

#include <algorithm>
#include <limits>

#include "render/layered/layered_walk.h"
#include "render/sampling_routines.h"

namespace pathlab {

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

// RGB mode's walks: the colour is RGB (layered_walk.h).
Vec3f LayeredBsdf::f(Vec3f wo, Vec3f wi, WalkNumbers& r) const {
    return fIn(wo, wi, r, RgbLayerColours{&bottom_, params_.albedo});
}

std::optional<BsdfSample> LayeredBsdf::sample(Vec3f wo, float uc, Vec2f u, WalkNumbers& r) const {
    auto s = sampleIn(wo, uc, u, r, RgbLayerColours{&bottom_, params_.albedo});
    if (!s) return std::nullopt;
    s->sample.f = s->f;
    return s->sample;
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
    using layered_walk::next2D, layered_walk::usable;
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
