#include "render/layered/dielectric_interface.h"

#include "render/sampling_routines.h"

namespace pathlab {
namespace {

// The share of the sampling probability left to reflection and transmission
// once the lobes not asked for are removed (pbrt-v4's pr and pt).
struct LobeShares {
    float pr, pt;
    float reflect() const { return pr / (pr + pt); }
    float transmit() const { return pt / (pr + pt); }
};
LobeShares lobeShares(float R, Lobes lobes) {
    return {lobes == Lobes::Transmission ? 0.0f : R, lobes == Lobes::Reflection ? 0.0f : 1 - R};
}

// Radiance entering a denser medium is compressed by 1/η′²; importance is not.
float transportScale(float etap, Transport mode) {
    return mode == Transport::Radiance ? 1 / (etap * etap) : 1.0f;
}

// The generalised half vector of wo and wi (Walter et al. 2007, eq. 16),
// turned up; nothing when degenerate or back-facing to either direction.
bool generalisedHalfVector(float eta, Vec3f wo, Vec3f wi, Vec3f* wm, float* etap) {
    if (wo.z == 0 || wi.z == 0) return false;
    const bool reflect = wo.z * wi.z > 0;
    *etap = reflect ? 1 : (wo.z > 0 ? eta : 1 / eta);
    Vec3f h = wi * *etap + wo;
    if (dot(h, h) == 0) return false;
    h = normalize(h);
    if (h.z < 0) h = -h;
    if (dot(h, wi) * wi.z < 0 || dot(h, wo) * wo.z < 0) return false;
    *wm = h;
    return true;
}

std::optional<BsdfSample> sampleSmooth(float eta, Vec3f wo, float uc, Transport mode, Lobes lobes) {
    const float R = fresnelDielectric(wo.z, eta);
    const LobeShares s = lobeShares(R, lobes);
    if (s.pr == 0 && s.pt == 0) return std::nullopt;
    if (uc < s.reflect()) {
        const Vec3f wi{-wo.x, -wo.y, wo.z};
        return BsdfSample{wi, Vec3f(R / absCosTheta(wi)), s.reflect(), true};
    }
    Vec3f wi;
    float etap;
    if (!refract(wo, Vec3f(0, 0, 1), eta, &etap, &wi) || wi.z == 0) return std::nullopt;
    const float ft = (1 - R) / absCosTheta(wi) * transportScale(etap, mode);
    return BsdfSample{wi, Vec3f(ft), s.transmit(), true};
}

std::optional<BsdfSample> sampleRough(const DielectricInterface& d, Vec3f wo, float uc, Vec2f u,
                                      Transport mode, Lobes lobes) {
    const Vec3f wm = d.ggx.sampleVisibleNormal(wo, u);
    const float R = fresnelDielectric(dot(wo, wm), d.eta);
    const LobeShares s = lobeShares(R, lobes);
    if (s.pr == 0 && s.pt == 0) return std::nullopt;
    if (uc < s.reflect()) {
        const Vec3f wi = reflect(wo, wm);
        if (!sameHemisphere(wo, wi)) return std::nullopt;
        const float pdf = d.ggx.visibleD(wo, wm) / (4 * std::abs(dot(wo, wm))) * s.reflect();
        const float f = d.ggx.D(wm) * d.ggx.G(wo, wi) * R / std::abs(4 * wi.z * wo.z);
        if (!(pdf > 0)) return std::nullopt;
        return BsdfSample{wi, Vec3f(f), pdf, false};
    }
    Vec3f wi;
    float etap;
    if (!refract(wo, wm, d.eta, &etap, &wi) || sameHemisphere(wo, wi) || wi.z == 0)
        return std::nullopt;
    const float denom = dot(wi, wm) + dot(wo, wm) / etap;
    const float dwmDwi = std::abs(dot(wi, wm)) / (denom * denom);
    const float pdf = d.ggx.visibleD(wo, wm) * dwmDwi * s.transmit();
    const float ft = (1 - R) * d.ggx.D(wm) * d.ggx.G(wo, wi) *
                     std::abs(dot(wi, wm) * dot(wo, wm) / (wi.z * wo.z * denom * denom)) *
                     transportScale(etap, mode);
    if (!(pdf > 0)) return std::nullopt;
    return BsdfSample{wi, Vec3f(ft), pdf, false};
}

}  // namespace

Vec3f DielectricInterface::f(Vec3f wo, Vec3f wi, Transport mode) const {
    if (isSpecular()) return Vec3f(0.0f);
    Vec3f wm;
    float etap;
    if (!generalisedHalfVector(eta, wo, wi, &wm, &etap)) return Vec3f(0.0f);
    const float F = fresnelDielectric(dot(wo, wm), eta);
    if (etap == 1 && wo.z * wi.z > 0)
        return Vec3f(ggx.D(wm) * ggx.G(wo, wi) * F / std::abs(4 * wi.z * wo.z));
    const float denom = dot(wi, wm) + dot(wo, wm) / etap;
    const float ft = ggx.D(wm) * (1 - F) * ggx.G(wo, wi) *
                     std::abs(dot(wi, wm) * dot(wo, wm) / (wi.z * wo.z * denom * denom));
    return Vec3f(ft * transportScale(etap, mode));
}

float DielectricInterface::pdf(Vec3f wo, Vec3f wi, Transport, Lobes lobes) const {
    if (isSpecular()) return 0;
    Vec3f wm;
    float etap;
    if (!generalisedHalfVector(eta, wo, wi, &wm, &etap)) return 0;
    const LobeShares s = lobeShares(fresnelDielectric(dot(wo, wm), eta), lobes);
    if (s.pr == 0 && s.pt == 0) return 0;
    if (wo.z * wi.z > 0) return ggx.visibleD(wo, wm) / (4 * std::abs(dot(wo, wm))) * s.reflect();
    const float denom = dot(wi, wm) + dot(wo, wm) / etap;
    return ggx.visibleD(wo, wm) * std::abs(dot(wi, wm)) / (denom * denom) * s.transmit();
}

std::optional<BsdfSample> DielectricInterface::sample(Vec3f wo, float uc, Vec2f u, Transport mode,
                                                      Lobes lobes) const {
    if (wo.z == 0) return std::nullopt;
    if (eta == 1 && lobes != Lobes::Reflection)
        return BsdfSample{-wo, Vec3f(1 / absCosTheta(wo)), 1.0f, true};
    if (isSpecular()) return sampleSmooth(eta, wo, uc, mode, lobes);
    return sampleRough(*this, wo, uc, u, mode, lobes);
}

}  // namespace pathlab
