#include "render/transmission_lobes.h"

#include "render/sampling_routines.h"

namespace pathlab {
namespace {

// The generalised half vector of wo and wi (Walter et al. eq. 16), turned to
// the upper hemisphere; nothing when it is degenerate or a microfacet of it
// would be back-facing to either direction. etap: the relative index along
// the transmitted path (1 for reflection).
struct HalfVector {
    Vec3f wm;
    float etap;
    bool reflect;
};
std::optional<HalfVector> halfVector(float eta, Vec3f wo, Vec3f wi) {
    const float cosO = wo.z, cosI = wi.z;
    if (cosO == 0 || cosI == 0) return std::nullopt;
    const bool reflect = cosO * cosI > 0;
    const float etap = reflect ? 1 : (cosO > 0 ? eta : 1 / eta);
    Vec3f wm = wi * etap + wo;
    if (dot(wm, wm) == 0) return std::nullopt;
    wm = normalize(wm);
    if (wm.z < 0) wm = -wm;
    if (dot(wm, wi) * cosI < 0 || dot(wm, wo) * cosO < 0) return std::nullopt;
    return HalfVector{wm, etap, reflect};
}

}  // namespace

Vec3f roughDielectricF(const GgxDistribution& ggx, float eta, Vec3f wo, Vec3f wi) {
    const auto h = halfVector(eta, wo, wi);
    if (!h) return Vec3f(0.0f);
    const float F = fresnelDielectric(dot(wo, h->wm), eta);
    if (h->reflect) return Vec3f(ggx.D(h->wm) * ggx.G(wo, wi) * F / std::abs(4 * wi.z * wo.z));
    const float denom = dot(wi, h->wm) + dot(wo, h->wm) / h->etap;
    const float ft = ggx.D(h->wm) * (1 - F) * ggx.G(wo, wi) *
                     std::abs(dot(wi, h->wm) * dot(wo, h->wm) / (wi.z * wo.z * denom * denom));
    return Vec3f(ft / (h->etap * h->etap));
}

float roughDielectricPdf(const GgxDistribution& ggx, float eta, Vec3f wo, Vec3f wi) {
    const auto h = halfVector(eta, wo, wi);
    if (!h) return 0;
    const float R = fresnelDielectric(dot(wo, h->wm), eta);
    if (h->reflect) return ggx.visibleD(wo, h->wm) / (4 * std::abs(dot(wo, h->wm))) * R;
    // The half vector's change of variables for refraction (Walter et al. eq. 17).
    const float denom = dot(wi, h->wm) + dot(wo, h->wm) / h->etap;
    const float dwmDwi = std::abs(dot(wi, h->wm)) / (denom * denom);
    return ggx.visibleD(wo, h->wm) * dwmDwi * (1 - R);
}

std::optional<BsdfSample> sampleRoughDielectric(const GgxDistribution& ggx, float eta, Vec3f wo,
                                                float uLobe, Vec2f u) {
    if (wo.z == 0) return std::nullopt;
    const Vec3f wm = ggx.sampleVisibleNormal(wo, u);
    const float R = fresnelDielectric(dot(wo, wm), eta);
    if (uLobe < R) {
        const Vec3f wi = reflect(wo, wm);
        if (!sameHemisphere(wo, wi)) return std::nullopt;
        const float pdf = ggx.visibleD(wo, wm) / (4 * std::abs(dot(wo, wm))) * R;
        const float f = ggx.D(wm) * ggx.G(wo, wi) * R / std::abs(4 * wi.z * wo.z);
        if (!(pdf > 0)) return std::nullopt;
        return BsdfSample{wi, Vec3f(f), pdf, false};
    }
    Vec3f wi;
    float etap;
    if (!refract(wo, wm, eta, &etap, &wi) || sameHemisphere(wo, wi) || wi.z == 0)
        return std::nullopt;
    const float denom = dot(wi, wm) + dot(wo, wm) / etap;
    const float pdf = ggx.visibleD(wo, wm) * std::abs(dot(wi, wm)) / (denom * denom) * (1 - R);
    const float ft = (1 - R) * ggx.D(wm) * ggx.G(wo, wi) *
                     std::abs(dot(wi, wm) * dot(wo, wm) / (wi.z * wo.z * denom * denom));
    if (!(pdf > 0)) return std::nullopt;
    return BsdfSample{wi, Vec3f(ft / (etap * etap)), pdf, false};
}

std::optional<BsdfSample> sampleSmoothDielectric(float eta, Vec3f wo, float uLobe) {
    const float R = fresnelDielectric(wo.z, eta), T = 1 - R;
    if (uLobe < R) {
        const Vec3f wi{-wo.x, -wo.y, wo.z};
        return BsdfSample{wi, Vec3f(R / absCosTheta(wi)), R, true};
    }
    Vec3f wi;
    float etap;
    if (!refract(wo, Vec3f(0, 0, 1), eta, &etap, &wi)) return std::nullopt;
    // Radiance is compressed by 1/η² entering a denser medium (pbrt-v4 sec. 9.5.2,
    // "non-symmetric scattering due to refraction").
    return BsdfSample{wi, Vec3f(T / absCosTheta(wi) / (etap * etap)), T, true};
}

std::optional<BsdfSample> sampleThinDielectric(float eta, Vec3f wo, float uLobe) {
    float R = fresnelDielectric(absCosTheta(wo), eta), T = 1 - R;
    // Inter-reflection inside the slab: R' = R + T²R / (1 − R²) (the geometric
    // series of pbrt-v4 eq. 9.46), T' = 1 − R' (no absorption).
    if (R < 1) R += T * T * R / (1 - R * R), T = 1 - R;
    if (uLobe < R) {
        const Vec3f wi{-wo.x, -wo.y, wo.z};
        return BsdfSample{wi, Vec3f(R / absCosTheta(wi)), R, true};
    }
    const Vec3f wi = -wo;
    return BsdfSample{wi, Vec3f(T / absCosTheta(wi)), T, true};
}

namespace {
float reflectProbability(Vec3f R, Vec3f T) {
    const float pr = maxComponent(R), pt = maxComponent(T);
    return pr + pt > 0 ? pr / (pr + pt) : 0;
}
}  // namespace

Vec3f diffuseTransmissionF(Vec3f R, Vec3f T, Vec3f wo, Vec3f wi) {
    if (wo.z == 0 || wi.z == 0) return Vec3f(0.0f);
    return (sameHemisphere(wo, wi) ? R : T) * kInvPi;
}

float diffuseTransmissionPdf(Vec3f R, Vec3f T, Vec3f wo, Vec3f wi) {
    if (wo.z == 0 || wi.z == 0) return 0;
    const float p = reflectProbability(R, T);
    return cosineHemispherePdf(absCosTheta(wi)) * (sameHemisphere(wo, wi) ? p : 1 - p);
}

std::optional<BsdfSample> sampleDiffuseTransmission(Vec3f R, Vec3f T, Vec3f wo, float uLobe,
                                                    Vec2f u) {
    if (wo.z == 0) return std::nullopt;
    const float p = reflectProbability(R, T);
    if (!(maxComponent(R) + maxComponent(T) > 0)) return std::nullopt;
    Vec3f wi = sampleCosineHemisphere(u);
    const bool reflect = uLobe < p;
    // Reflection: into wo's side; transmission: into the other.
    wi.z = std::copysign(wi.z, reflect ? wo.z : -wo.z);
    if (wi.z == 0) return std::nullopt;
    const float pdf = cosineHemispherePdf(absCosTheta(wi)) * (reflect ? p : 1 - p);
    return BsdfSample{wi, (reflect ? R : T) * kInvPi, pdf, false};
}

}  // namespace pathlab
