// The lobes that transmit light, in the local shading frame (pbrt-v4 sec. 9.5,
// 9.7 and its ThinDielectricBxDF / DiffuseTransmissionBxDF). Conventions as in
// bsdf.h: f excludes the cosine; the solid-angle density; radiance transport
// (transmitted radiance is divided by η'², pbrt-v4 sec. 9.5.2, so the
// transport is not symmetric: f(wo, wi) η'² = f(wi, wo), with η' the index
// of wi's side over wo's).
#pragma once

#include <optional>

#include "render/bsdf.h"
#include "render/microfacet.h"

namespace pathlab {

// Rough dielectric interface of relative index eta (inside over outside; the
// normal points outside): GGX reflection and transmission (Walter et al.
// 2007), the lobe chosen by the Fresnel reflectance of the sampled
// microfacet. f and pdf are generalised half-vector forms (eqs. 16–17 of
// Walter et al.; pbrt-v4 eqs. 9.40 and 9.37).
Vec3f roughDielectricF(const GgxDistribution& ggx, float eta, Vec3f wo, Vec3f wi);
float roughDielectricPdf(const GgxDistribution& ggx, float eta, Vec3f wo, Vec3f wi);
std::optional<BsdfSample> sampleRoughDielectric(const GgxDistribution& ggx, float eta, Vec3f wo,
                                                float uLobe, Vec2f u);

// Smooth dielectric: specular reflection or refraction chosen by uLobe.
std::optional<BsdfSample> sampleSmoothDielectric(float eta, Vec3f wo, float uLobe);

// A thin slab of index eta: the sum of its internal reflections, with the
// transmitted ray going straight through (pbrt-v4's ThinDielectricBxDF).
std::optional<BsdfSample> sampleThinDielectric(float eta, Vec3f wo, float uLobe);

// Lambertian reflection R/π into wo's side and transmission T/π into the
// other; the side is chosen in proportion to max(R) and max(T).
Vec3f diffuseTransmissionF(Vec3f R, Vec3f T, Vec3f wo, Vec3f wi);
float diffuseTransmissionPdf(Vec3f R, Vec3f T, Vec3f wo, Vec3f wi);
std::optional<BsdfSample> sampleDiffuseTransmission(Vec3f R, Vec3f T, Vec3f wo, float uLobe,
                                                    Vec2f u);

}  // namespace pathlab
