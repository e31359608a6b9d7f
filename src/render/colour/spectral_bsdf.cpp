// The BSDFs of bsdf.h evaluated at a path's sampled wavelengths. The
// materials keep their RGB parameters; reflectances become bounded spectra
// (albedoSpectrum, pbrt-v4's RGBAlbedoSpectrum), and the colourless factors
// (microfacet terms, a dielectric's Fresnel term for a constant index) are
// those of the RGB evaluation.
#include "render/colour/spectral_context.h"

namespace pathlab {
namespace {

using spectral::SampledSpectrum;

// A conductor's or a diffuse transmitter's value as an unbounded spectrum of
// its RGB value: the conversion is homogeneous (rgb_spectrum.h), so the
// colourless factors (the microfacet terms, 1/π, 1/|cosθ|) pass through it.
// The conductor's Fresnel term is thus upsampled from its RGB reflectance
// rather than computed per wavelength from spectra of η and k as pbrt-v4
// does: close for metals' smooth reflectance curves, not the same.
SampledSpectrum upsampled(Vec3f f, const SpectralContext& ctx) {
    return ctx.unbounded({std::max(f.x, 0.0f), std::max(f.y, 0.0f), std::max(f.z, 0.0f)});
}

}  // namespace

SampledSpectrum spectralBsdfF(const Bsdf& bsdf, Vec3f wo, Vec3f wi, const SpectralContext& ctx) {
    switch (bsdf.kind()) {
        case BsdfKind::Diffuse:
            return strictlySameSide(wo, wi) ? ctx.reflectance(bsdf.albedo()) * kInvPi
                                            : SampledSpectrum(0.0f);
        case BsdfKind::Conductor:
        case BsdfKind::DiffuseTransmission:
            return upsampled(bsdf.f(wo, wi), ctx);
        case BsdfKind::Dielectric:  // colourless for a constant index
            return SampledSpectrum(bsdf.f(wo, wi).x);
        case BsdfKind::Layered: {  // a walk seeded by the directions, as Bsdf::f's
            auto r = walkFromDirections(wo, wi);
            return ctx.layeredF(*bsdf.layered(), wo, wi, r);
        }
        case BsdfKind::Mirror:
        case BsdfKind::ThinDielectric:
        case BsdfKind::PassThrough:  // delta lobes only
            break;
    }
    return SampledSpectrum(0.0f);
}

SampledSpectrum spectralSampledF(const Bsdf& bsdf, Vec3f, const BsdfSample& s,
                                 const SpectralContext& ctx) {
    switch (bsdf.kind()) {
        case BsdfKind::Diffuse:  // a sample lies on wo's side
            return ctx.reflectance(bsdf.albedo()) * kInvPi;
        case BsdfKind::Mirror:
            return ctx.reflectance(bsdf.albedo()) / absCosTheta(s.wi);
        case BsdfKind::Conductor:
        case BsdfKind::DiffuseTransmission:
            return upsampled(s.f, ctx);
        case BsdfKind::Dielectric:
        case BsdfKind::ThinDielectric:
        case BsdfKind::PassThrough:  // colourless for a constant index
            return SampledSpectrum(s.f.x);
        case BsdfKind::Layered:  // sampled by layeredSample, which gives f with the sample
            break;
    }
    return SampledSpectrum(0.0f);
}

}  // namespace pathlab
