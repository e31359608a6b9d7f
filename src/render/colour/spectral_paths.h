// Spectral mode's paths (RenderSettings::spectral): each camera sample
// carries four wavelengths, sampled from one sampler dimension as pbrt-v4's
// RayIntegrator::EvaluatePixelSample does (SampledWavelengths::sampleVisible:
// pbrt-v4's visible-range importance density, the four stratified from the one
// number). That dimension is the first after the camera's — 2, or 4 with a
// thin lens — and every path vertex's block moves up by one behind it
// (docs/rendering.md, "Dimension layout"); RGB mode's layout is unchanged.
// The paths are RGB mode's — batched (estimateRadianceBatch) or, with
// batchPaths off, one at a time (estimateRadiance) — with spectral colour
// contexts, and each path's radiance becomes linear sRGB through the CIE 1931
// matching functions before the film sees it, so film, metrics and study are
// those of RGB mode.
#pragma once

#include "render/batched_paths.h"
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
// camera rays have been traced (found, si: as estimateRadianceBatch's
// arguments, overwritten when batched); settings.firstBounce is
// spectralFirstBounce. Each sample's wavelengths are sampled first (one call
// per sample), then its path is traced with its own spectral context: the
// batch's paths together, as RGB mode's, unless settings.batchPaths is off.
// The batched paths' values are the scalar integrator's bit for bit.
template <Sampler S>
void estimateSpectralRadiance(const RenderScene& scene, const Vec3f* origins, const Vec3f* dirs,
                              bool* found, SurfaceInteraction* si, int count, S& sampler,
                              Vec2i pixel, int firstIndex, const IntegratorSettings& settings,
                              int wavelengthDimension, PathCounters& counters, Vec3f* L) {
    static_assert(SpectralContext::kChannels <= kMaxBatchChannels);
    // The thread's cache outlives the batch, so that a scene's few constant
    // colours are looked up in the coefficient table once per thread rather
    // than once per batch (a batch is a pixel's samples: 16 paths at 16 spp).
    // Exact, so which thread rendered a pixel changes no bit.
    static thread_local SigmoidCache cache;
    SpectralContext ctx[kBatchSamples];
    for (int k = 0; k < count; ++k) {
        ctx[k] = SpectralContext(sampleWavelengths(sampler, pixel, firstIndex + k,
                                                   wavelengthDimension, settings.wavelengths),
                                 cache);
        ++counters.dimensions;
    }
    spectral::SampledSpectrum radiance[kBatchSamples];
    if (settings.batchPaths) {
        const SpectralContext* contexts = ctx;
        estimateRadianceBatch(scene, dirs, found, si, count, sampler, pixel, firstIndex, settings,
                              counters, radiance, contexts);
    } else {
        for (int k = 0; k < count; ++k)
            radiance[k] = estimateRadiance(scene, origins[k], dirs[k], found[k], si[k], sampler,
                                           pixel, firstIndex + k, settings, counters, ctx[k]);
    }
    for (int k = 0; k < count; ++k) L[k] = ctx[k].toRgb(radiance[k]);
}

}  // namespace pathlab
