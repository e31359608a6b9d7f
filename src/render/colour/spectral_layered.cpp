// The layered BSDF's walks carrying spectra (layered_walk.h's Colours policy
// for spectral mode): the medium's albedo is a bounded spectrum of its RGB
// (pbrt-v4's CoatedDiffuseMaterial samples its albedo texture as an albedo
// spectrum), and the base's values are the spectral BSDF's
// (spectral_bsdf.cpp), a Lambertian base's reflectance a bounded spectrum, a
// conductor's Fresnel term per wavelength where its η and k are spectra. The
// walk draws the same numbers as in RGB mode.
#include "render/colour/spectral_context.h"
#include "render/layered/layered_walk.h"

namespace pathlab {
namespace {

using spectral::SampledSpectrum;

struct SpectralLayerColours {
    using Colour = SampledSpectrum;
    const Bsdf* base;
    const SpectralContext* ctx;
    SampledSpectrum albedo;
    SampledSpectrum grey(Vec3f v) const { return SampledSpectrum(v.x); }
    SampledSpectrum baseF(Vec3f wo, Vec3f wi) const { return ctx->f(*base, wo, wi); }
    SampledSpectrum sampledBaseF(Vec3f wo, const BsdfSample& s) const {
        return ctx->sampledF(*base, wo, s);
    }
    static float maxOf(const SampledSpectrum& c) { return c.maxComponent(); }
};

SpectralLayerColours coloursOf(const LayeredBsdf& layered, const SpectralContext& ctx) {
    return {&layered.base(), &ctx, ctx.reflectance(layered.parameters().albedo)};
}

}  // namespace

SampledSpectrum spectralLayeredF(const LayeredBsdf& layered, Vec3f wo, Vec3f wi, WalkNumbers& r,
                                 const SpectralContext& ctx) {
    return layered.fIn(wo, wi, r, coloursOf(layered, ctx));
}

std::optional<LayeredSampleOf<SampledSpectrum>> spectralLayeredSample(const LayeredBsdf& layered,
                                                                      Vec3f wo, float uc, Vec2f u,
                                                                      WalkNumbers& r,
                                                                      const SpectralContext& ctx) {
    return layered.sampleIn(wo, uc, u, r, coloursOf(layered, ctx));
}

}  // namespace pathlab
