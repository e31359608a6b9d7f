// BSDFs in the local shading frame (normal = +z, directions point away from
// the surface). Conventions follow pbrt-v4 (ch. 9): f() excludes the cosine;
// a sample returns f, the solid-angle pdf, and for delta lobes f = R/|cosθi|
// with pdf equal to the discrete lobe probability.
#pragma once

#include <optional>

#include "core/math.h"
#include "render/sampling_routines.h"

namespace pathlab {

struct BsdfSample {
    Vec3f wi;
    Vec3f f;
    float pdf = 0;
    bool specular = false;
    // The throughput factor f·|cosθi|/pdf.
    Vec3f weight() const { return f * (absCosTheta(wi) / pdf); }
};

enum class BsdfKind { Diffuse, Mirror, Dielectric, Conductor };

class Bsdf {
  public:
    static Bsdf diffuse(Vec3f albedo);
    static Bsdf mirror(Vec3f reflectance);
    static Bsdf dielectric(float eta);
    static Bsdf conductor(Vec3f eta, Vec3f k, float alpha);

    BsdfKind kind() const { return kind_; }
    // A Lambertian BSDF's albedo (its reflectance R: f = R/π).
    Vec3f albedo() const { return color_; }
    // True when every lobe is a Dirac delta: next-event estimation cannot help.
    // Inline: the integrator asks at every vertex, and the diffuse answer is
    // one comparison.
    bool isSpecular() const {
        return kind_ != BsdfKind::Diffuse &&
               (kind_ != BsdfKind::Conductor || alpha_ < kSmoothConductorAlpha);
    }
    // Below this roughness a conductor's GGX lobe is numerically a delta: it
    // is treated as a perfect mirror.
    static constexpr float kSmoothConductorAlpha = 1e-3f;
    // Which of sample()'s random numbers it reads: the lobe choice only at
    // glass, the direction only where some lobe is not a delta. The integrator
    // draws no others.
    bool usesLobeSample() const { return kind_ == BsdfKind::Dielectric; }
    bool usesDirectionSample() const { return !isSpecular(); }

    // The Lambertian case, nearly every vertex of the built-in scenes, is
    // inline so that it is optimised with the integrator around it; the other
    // materials are out-of-line calls.
    Vec3f f(Vec3f wo, Vec3f wi) const;
    float pdf(Vec3f wo, Vec3f wi) const;
    // uLobe chooses between lobes (reflection or transmission at glass); u
    // chooses the direction within the lobe.
    std::optional<BsdfSample> sample(Vec3f wo, float uLobe, Vec2f u) const;

  private:
    Vec3f fNonDiffuse(Vec3f wo, Vec3f wi) const;
    float pdfNonDiffuse(Vec3f wo, Vec3f wi) const;
    std::optional<BsdfSample> sampleNonDiffuse(Vec3f wo, float uLobe, Vec2f u) const;

    BsdfKind kind_ = BsdfKind::Diffuse;
    Vec3f color_{0.0f};       // albedo / reflectance
    Vec3f eta_{1.5f}, k_{0};  // eta_.x is the dielectric's index
    float alpha_ = 0;
};

// Lambertian reflection is two-sided: it scatters into the hemisphere wo lies
// in (strictly: a direction in the surface plane gets nothing).
inline bool strictlySameSide(Vec3f wo, Vec3f wi) {
    return (wo.z > 0 && wi.z > 0) || (wo.z < 0 && wi.z < 0);
}

inline Vec3f Bsdf::f(Vec3f wo, Vec3f wi) const {
    if (kind_ != BsdfKind::Diffuse) return fNonDiffuse(wo, wi);
    return strictlySameSide(wo, wi) ? color_ * kInvPi : Vec3f(0.0f);
}

inline float Bsdf::pdf(Vec3f wo, Vec3f wi) const {
    if (kind_ != BsdfKind::Diffuse) return pdfNonDiffuse(wo, wi);
    return strictlySameSide(wo, wi) ? cosineHemispherePdf(std::abs(wi.z)) : 0.0f;
}

inline std::optional<BsdfSample> Bsdf::sample(Vec3f wo, float uLobe, Vec2f u) const {
    if (kind_ != BsdfKind::Diffuse) return sampleNonDiffuse(wo, uLobe, u);
    if (wo.z == 0) return std::nullopt;
    Vec3f wi = sampleCosineHemisphere(u);
    // Into wo's hemisphere: wi.z ≥ +0, so this is −wi.z exactly when wo.z < 0.
    // A select rather than a branch — which side wo lies on changes from wall
    // to wall and mispredicted.
    wi.z = std::copysign(wi.z, wo.z);
    if (wi.z == 0) return std::nullopt;
    return BsdfSample{wi, color_ * kInvPi, cosineHemispherePdf(std::abs(wi.z)), false};
}

// Unpolarised Fresnel reflectance of a dielectric interface (pbrt-v4 eq. 9.6);
// eta = n_inside / n_outside, cosThetaI signed (negative: arriving from inside).
float fresnelDielectric(float cosThetaI, float eta);
// Fresnel reflectance of a conductor with complex index eta + i k (pbrt-v4 9.3.6).
float fresnelComplex(float cosThetaI, float eta, float k);
// Refraction of wi about n; false on total internal reflection. etaRelative
// receives the relative index along wi's side.
bool refract(Vec3f wi, Vec3f n, float eta, float* etaRelative, Vec3f* wt);

// Trowbridge–Reitz (GGX) microfacet distribution, isotropic (Walter et al.
// 2007; visible-normal sampling by Heitz 2018, "Sampling the GGX Distribution of
// Visible Normals").
struct GgxDistribution {
    float alpha;
    float D(Vec3f wm) const;
    float lambda(Vec3f w) const;
    float G1(Vec3f w) const { return 1 / (1 + lambda(w)); }
    float G(Vec3f wo, Vec3f wi) const { return 1 / (1 + lambda(wo) + lambda(wi)); }
    // Density of visible normals as seen from wo (Heitz 2018 eq. 3).
    float visibleD(Vec3f wo, Vec3f wm) const;
    Vec3f sampleVisibleNormal(Vec3f wo, Vec2f u) const;
};

}  // namespace pathlab
