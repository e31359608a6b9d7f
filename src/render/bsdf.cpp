#include "render/bsdf.h"

#include "render/layered/layered_bsdf.h"
#include "render/sampling_routines.h"
#include "render/transmission_lobes.h"

namespace pathlab {
namespace {

// Two-sided opaque surfaces: evaluate with both directions flipped to the
// upper hemisphere when wo is below.
inline void flipToUpper(Vec3f& wo, Vec3f& wi) {
    if (wo.z < 0) wo = -wo, wi = -wi;
}

Vec3f conductorFresnel(float cosTheta, Vec3f eta, Vec3f k) {
    return {fresnelComplex(cosTheta, eta.x, k.x), fresnelComplex(cosTheta, eta.y, k.y),
            fresnelComplex(cosTheta, eta.z, k.z)};
}

}  // namespace

float fresnelDielectric(float cosThetaI, float eta) {
    cosThetaI = std::clamp(cosThetaI, -1.0f, 1.0f);
    if (cosThetaI < 0) eta = 1 / eta, cosThetaI = -cosThetaI;
    const float sin2T = (1 - cosThetaI * cosThetaI) / (eta * eta);
    if (sin2T >= 1) return 1;  // total internal reflection
    const float cosT = std::sqrt(1 - sin2T);
    const float rPar = (eta * cosThetaI - cosT) / (eta * cosThetaI + cosT);
    const float rPerp = (cosThetaI - eta * cosT) / (cosThetaI + eta * cosT);
    return (rPar * rPar + rPerp * rPerp) / 2;
}

float fresnelComplex(float cosThetaI, float eta, float k) {
    // The Fresnel equations for a complex index η + ik, written in real
    // arithmetic (pbrt-v3 §8.2.1, eq. 8.3): with a² + b² = |(η + ik)² − sin²θ|
    // and a its real part's square root's, the s-polarised reflectance is
    // (a² + b² − 2a cosθ + cos²θ) / (a² + b² + 2a cosθ + cos²θ) and the
    // p-polarised one that times a like ratio. The same value as complex
    // division and square root (tested against them), without std::complex's
    // library calls, which took 14% of a frame of glass and metal.
    const float c = std::clamp(cosThetaI, 0.0f, 1.0f);
    const float cos2 = c * c, sin2 = 1 - cos2;
    const float t0 = eta * eta - k * k - sin2;
    const float a2b2 = std::sqrt(t0 * t0 + 4 * eta * eta * k * k);
    const float a = std::sqrt(std::max(0.0f, (a2b2 + t0) / 2));
    const float t1 = a2b2 + cos2, t2 = 2 * c * a;
    const float rs = (t1 - t2) / (t1 + t2);
    const float t3 = cos2 * a2b2 + sin2 * sin2, t4 = t2 * sin2;
    const float rp = rs * (t3 - t4) / (t3 + t4);
    return (rs + rp) / 2;
}

bool refract(Vec3f wi, Vec3f n, float eta, float* etaRelative, Vec3f* wt) {
    float cosI = dot(n, wi);
    if (cosI < 0) eta = 1 / eta, cosI = -cosI, n = -n;
    const float sin2T = std::max(0.0f, 1 - cosI * cosI) / (eta * eta);
    if (sin2T >= 1) return false;
    const float cosT = std::sqrt(1 - sin2T);
    *wt = -wi / eta + n * (cosI / eta - cosT);
    *etaRelative = eta;
    return true;
}

Bsdf Bsdf::diffuse(Vec3f albedo) {
    Bsdf b;
    b.kind_ = BsdfKind::Diffuse;
    b.color_ = albedo;
    return b;
}
Bsdf Bsdf::mirror(Vec3f reflectance) {
    Bsdf b;
    b.kind_ = BsdfKind::Mirror;
    b.specular_ = true;
    b.color_ = reflectance;
    return b;
}
Bsdf Bsdf::dielectric(float eta, float alphaX, float alphaY) {
    Bsdf b;
    b.kind_ = BsdfKind::Dielectric;
    b.eta_ = Vec3f(eta);
    b.alpha_ = alphaX, b.alphaY_ = alphaY;
    // An index-matched interface refracts nothing: smooth whatever its
    // roughness (as pbrt-v4's DielectricBxDF).
    b.specular_ = eta == 1 || b.ggx().effectivelySmooth();
    return b;
}
Bsdf Bsdf::conductor(Vec3f eta, Vec3f k, float alphaX, float alphaY) {
    Bsdf b;
    b.kind_ = BsdfKind::Conductor;
    b.eta_ = eta;
    b.k_ = k;
    b.alpha_ = alphaX, b.alphaY_ = alphaY;
    b.specular_ = b.ggx().effectivelySmooth();
    return b;
}
Bsdf Bsdf::thinDielectric(float eta) {
    Bsdf b;
    b.kind_ = BsdfKind::ThinDielectric;
    b.eta_ = Vec3f(eta);
    b.specular_ = true;
    return b;
}
Bsdf Bsdf::diffuseTransmission(Vec3f reflectance, Vec3f transmittance) {
    Bsdf b;
    b.kind_ = BsdfKind::DiffuseTransmission;
    b.color_ = reflectance;
    b.k_ = transmittance;
    return b;
}
Bsdf Bsdf::passThrough() {
    Bsdf b;
    b.kind_ = BsdfKind::PassThrough;
    b.specular_ = true;
    return b;
}

Bsdf Bsdf::layered(const LayeredBsdf* layered) {
    Bsdf b;
    b.kind_ = BsdfKind::Layered;
    b.layered_ = layered;
    b.specular_ = layered->isSpecular();
    // Anisotropic when the coating is, or else the base: shadingFrame then
    // orients the frame as for a conductor.
    const GgxDistribution& top = layered->coating().ggx;
    b.alpha_ = top.alphaX, b.alphaY_ = top.alphaY;
    if (!b.isAnisotropic() && layered->base().isAnisotropic()) b.alpha_ = 0, b.alphaY_ = 1;
    return b;
}

Vec3f Bsdf::fNonDiffuse(Vec3f wo, Vec3f wi) const {
    if (kind_ == BsdfKind::Layered) {
        auto r = walkFromDirections(wo, wi);
        return layered_->f(wo, wi, r);
    }
    if (isSpecular()) return Vec3f(0.0f);
    if (kind_ == BsdfKind::Dielectric) return roughDielectricF(ggx(), eta_.x, wo, wi);
    if (kind_ == BsdfKind::DiffuseTransmission) return diffuseTransmissionF(color_, k_, wo, wi);
    flipToUpper(wo, wi);
    if (wi.z <= 0 || wo.z <= 0) return Vec3f(0.0f);
    // Conductor: Torrance–Sparrow with GGX (pbrt-v4 eq. 9.33).
    Vec3f wm = wi + wo;
    if (dot(wm, wm) == 0) return Vec3f(0.0f);
    wm = normalize(wm);
    const GgxDistribution ggx = this->ggx();
    const Vec3f F = conductorFresnel(std::abs(dot(wo, wm)), eta_, k_);
    return F * (ggx.D(wm) * ggx.G(wo, wi) / (4 * wi.z * wo.z));
}

float Bsdf::pdfNonDiffuse(Vec3f wo, Vec3f wi) const {
    if (kind_ == BsdfKind::Layered) {
        auto r = walkFromDirections(wi, wo);
        return layered_->pdf(wo, wi, r);
    }
    if (isSpecular()) return 0;
    if (kind_ == BsdfKind::Dielectric) return roughDielectricPdf(ggx(), eta_.x, wo, wi);
    if (kind_ == BsdfKind::DiffuseTransmission) return diffuseTransmissionPdf(color_, k_, wo, wi);
    flipToUpper(wo, wi);
    if (wi.z <= 0 || wo.z <= 0) return 0;
    Vec3f wm = wi + wo;
    if (dot(wm, wm) == 0) return 0;
    wm = normalize(wm);
    // Change of variables from half vector to reflected direction (eq. 9.34).
    return ggx().visibleD(wo, wm) / (4 * std::abs(dot(wo, wm)));
}

std::optional<BsdfSample> Bsdf::sampleNonDiffuse(Vec3f wo, float uLobe, Vec2f u) const {
    if (wo.z == 0) return std::nullopt;
    switch (kind_) {
        case BsdfKind::Diffuse:
            break;  // inline in bsdf.h
        case BsdfKind::Mirror: {
            const Vec3f wi{-wo.x, -wo.y, wo.z};
            return BsdfSample{wi, color_ / absCosTheta(wi), 1.0f, true};
        }
        case BsdfKind::Dielectric:
            if (isSpecular()) return sampleSmoothDielectric(eta_.x, wo, uLobe);
            return sampleRoughDielectric(ggx(), eta_.x, wo, uLobe, u);
        case BsdfKind::Conductor:
            return sampleConductor(wo, u);
        case BsdfKind::ThinDielectric:
            return sampleThinDielectric(eta_.x, wo, uLobe);
        case BsdfKind::DiffuseTransmission:
            return sampleDiffuseTransmission(color_, k_, wo, uLobe, u);
        case BsdfKind::PassThrough:
            return BsdfSample{-wo, Vec3f(1 / absCosTheta(wo)), 1.0f, true};
        case BsdfKind::Layered: {
            auto r = walkFromDirections(wo, Vec3f(u.x, u.y, 0), uLobe);
            return layered_->sample(wo, uLobe, u, r);
        }
    }
    return std::nullopt;
}

std::optional<BsdfSample> Bsdf::sampleConductor(Vec3f wo, Vec2f u) const {
    if (isSpecular()) {
        const Vec3f wi{-wo.x, -wo.y, wo.z};
        const Vec3f F = conductorFresnel(absCosTheta(wo), eta_, k_);
        return BsdfSample{wi, F / absCosTheta(wi), 1.0f, true};
    }
    const float side = wo.z < 0 ? -1.0f : 1.0f;
    const Vec3f woUp = wo * side;
    const GgxDistribution ggx = this->ggx();
    const Vec3f wm = ggx.sampleVisibleNormal(woUp, u);
    Vec3f wi = reflect(woUp, wm);
    if (wi.z <= 0) return std::nullopt;
    const float pdf = ggx.visibleD(woUp, wm) / (4 * std::abs(dot(woUp, wm)));
    const Vec3f F = conductorFresnel(std::abs(dot(woUp, wm)), eta_, k_);
    const Vec3f f = F * (ggx.D(wm) * ggx.G(woUp, wi) / (4 * wi.z * woUp.z));
    if (pdf <= 0) return std::nullopt;
    return BsdfSample{wi * side, f, pdf, false};
}

}  // namespace pathlab
