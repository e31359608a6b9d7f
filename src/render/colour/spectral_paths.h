// Spectral mode's paths (RenderSettings::spectral): each camera sample
// carries four wavelengths, sampled from one sampler dimension as pbrt-v4's
// RayIntegrator::EvaluatePixelSample does (SampledWavelengths::sampleVisible:
// pbrt-v4's visible-range importance density, the four stratified from the one
// number). That dimension is the first after the camera's — 2, or 4 with a
// thin lens — and every path vertex's block moves up by one behind it
// (docs/rendering.md, "Dimension layout"); RGB mode's layout is unchanged.
// The path is the scalar integrator's (estimateRadiance) with the spectral
// colour context, and its radiance becomes linear sRGB through the CIE 1931
// matching functions before the film sees it, so film, metrics and study are
// those of RGB mode.
#pragma once

#include "render/colour/spectral_context.h"
#include "render/path_integrator.h"

namespace pathlab {

namespace dims {
// The wavelength dimension of spectral mode, and its first path vertex's block.
constexpr int wavelength(bool lens) {
    return firstBounce(lens);
}
constexpr int spectralFirstBounce(bool lens) {
    return firstBounce(lens) + 1;
}
}  // namespace dims

// The sample's wavelengths from its wavelength dimension: pbrt-v4's visible
// density by default, or hero-wavelength sampling (the same one dimension).
template <Sampler S>
spectral::SampledWavelengths sampleWavelengths(S& sampler, Vec2i pixel, int sampleIndex,
                                               int wavelengthDimension,
                                               spectral::WavelengthSampling mode) {
    sampler.startPixelSample(pixel, sampleIndex, wavelengthDimension);
    return spectral::SampledWavelengths::sample(mode, sampler.get1D());
}

// Radiance, as linear sRGB, of `count` consecutive samples of a pixel whose
// camera rays have been traced (found, si), as estimateRadianceBatch's
// arguments; settings.firstBounce is spectralFirstBounce.
template <Sampler S>
void estimateSpectralRadiance(const RenderScene& scene, const Vec3f* origins, const Vec3f* dirs,
                              const bool* found, const SurfaceInteraction* si, int count,
                              S& sampler, Vec2i pixel, int firstIndex,
                              const IntegratorSettings& settings, int wavelengthDimension,
                              PathCounters& counters, Vec3f* L) {
    SigmoidCache cache;
    for (int k = 0; k < count; ++k) {
        const SpectralContext ctx(sampleWavelengths(sampler, pixel, firstIndex + k,
                                                    wavelengthDimension, settings.wavelengths),
                                  cache);
        ++counters.dimensions;
        const spectral::SampledSpectrum radiance =
            estimateRadiance(scene, origins[k], dirs[k], found[k], si[k], sampler, pixel,
                             firstIndex + k, settings, counters, ctx);
        L[k] = ctx.toRgb(radiance);
    }
}

// Throws InputError naming the first of the scene's features that spectral
// mode does not render yet (spectral_support.cpp).
void checkSpectralSupport(const SceneDescription& scene);

}  // namespace pathlab
