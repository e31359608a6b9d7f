// BSDFs in the local shading frame (normal = +z, directions point away from
// the surface). Conventions follow pbrt-v4 (ch. 9): f() excludes the cosine;
// a sample returns f, the solid-angle pdf, and for delta lobes f = R/|cosθi|
// with pdf equal to the discrete lobe probability.
#pragma once

#include <optional>

#include "core/math.h"
#include "render/microfacet.h"
#include "render/sampling_routines.h"

namespace pathlab {

struct BsdfSample {
    Vec3f wi;
    Vec3f f;
    float pdf = 0;
    bool specular = false;
    // f and pdf are the sample's throughput pair but pdf is not the density
    // pdf() gives for wi (a stochastic BSDF's walk, layered_bsdf.h): multiple
    // importance sampling must ask pdf() instead.
    bool pdfIsProportional = false;
    // The throughput factor f·|cosθi|/pdf.
    Vec3f weight() const { return f * (absCosTheta(wi) / pdf); }
};

// PassThrough is pbrt-v4's "interface" material: no surface, the ray goes on
// unchanged (a specular transmission with weight 1).
enum class BsdfKind {
    Diffuse,
    Mirror,
    Dielectric,
    Conductor,
    ThinDielectric,
    DiffuseTransmission,
    PassThrough,
    Layered  // coateddiffuse, coatedconductor: render/layered/layered_bsdf.h
};

class LayeredBsdf;

class Bsdf {
  public:
    static Bsdf diffuse(Vec3f albedo);
    static Bsdf mirror(Vec3f reflectance);
    // alphaX/alphaY: GGX roughness along the shading frame's x and y axes;
    // below GgxDistribution::kSmoothAlpha the interface is smooth (a delta).
    static Bsdf dielectric(float eta, float alphaX = 0, float alphaY = 0);
    static Bsdf conductor(Vec3f eta, Vec3f k, float alpha) {
        return conductor(eta, k, alpha, alpha);
    }
    static Bsdf conductor(Vec3f eta, Vec3f k, float alphaX, float alphaY);
    static Bsdf thinDielectric(float eta);
    static Bsdf diffuseTransmission(Vec3f reflectance, Vec3f transmittance);
    static Bsdf passThrough();
    // The layered BSDF is not copied: the scene owns it (RenderScene).
    static Bsdf layered(const LayeredBsdf* layered);

    BsdfKind kind() const { return kind_; }
    // A Lambertian BSDF's albedo (its reflectance R: f = R/π).
    Vec3f albedo() const { return color_; }
    // True when every lobe is a Dirac delta: next-event estimation cannot help.
    // Inline: the integrator asks at every vertex, and the diffuse answer is
    // one comparison.
    bool isSpecular() const { return specular_; }
    // Which of sample()'s random numbers it reads: the lobe choice only where
    // there are two lobes (reflection and transmission), the direction only
    // where some lobe is not a delta. The integrator draws no others.
    bool usesLobeSample() const {
        return kind_ == BsdfKind::Dielectric || kind_ == BsdfKind::ThinDielectric ||
               kind_ == BsdfKind::DiffuseTransmission || kind_ == BsdfKind::Layered;
    }
    bool usesDirectionSample() const { return !isSpecular(); }
    // Roughness differs along the frame's x and y: the frame's orientation
    // about the normal matters (shadingFrame).
    bool isAnisotropic() const { return alpha_ != alphaY_; }
    // The layered BSDF, whose walk the integrator feeds from the sampler;
    // null for the other kinds. (Its f, pdf and sample here draw the walk
    // from PCG32 seeded by the directions, as pbrt-v4 does.)
    const LayeredBsdf* layered() const { return layered_; }

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
    std::optional<BsdfSample> sampleConductor(Vec3f wo, Vec2f u) const;

    GgxDistribution ggx() const { return GgxDistribution(alpha_, alphaY_); }

    BsdfKind kind_ = BsdfKind::Diffuse;
    bool specular_ = false;
    Vec3f color_{0.0f};       // albedo / reflectance
    Vec3f eta_{1.5f}, k_{0};  // eta_.x is the dielectric's index; k_: diffuse transmittance
    float alpha_ = 0, alphaY_ = 0;
    const LayeredBsdf* layered_ = nullptr;
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

// The local frame a BSDF is evaluated in. Isotropic BSDFs do not depend on
// the tangent's direction and take Frame's own. An anisotropic one takes as
// x axis the tangent of the circle of latitude about world z,
// normalize((0, 0, 1) × n): pbrt-v4's ∂p/∂u on an unrotated sphere (its
// roughness u runs along ∂p/∂u). Where n is parallel to z, Frame's own.
inline Frame shadingFrame(const Bsdf& bsdf, Vec3f n) {
    if (!bsdf.isAnisotropic()) return Frame(n);
    const Vec3f t{-n.y, n.x, 0};
    const float len2 = dot(t, t);
    if (!(len2 > 1e-12f)) return Frame(n);
    Frame f;
    f.n = n;
    f.s = t / std::sqrt(len2);
    f.t = cross(n, f.s);
    return f;
}

// Unpolarised Fresnel reflectance of a dielectric interface (pbrt-v4 eq. 9.6);
// eta = n_inside / n_outside, cosThetaI signed (negative: arriving from inside).
float fresnelDielectric(float cosThetaI, float eta);
// Fresnel reflectance of a conductor with complex index eta + i k (pbrt-v4 9.3.6).
float fresnelComplex(float cosThetaI, float eta, float k);
// Refraction of wi about n; false on total internal reflection. etaRelative
// receives the relative index along wi's side.
bool refract(Vec3f wi, Vec3f n, float eta, float* etaRelative, Vec3f* wt);

}  // namespace pathlab
