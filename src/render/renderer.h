// The tile renderer: splits the image into 16×16 tiles rendered in parallel
// with oneTBB. Each tile gets its own copy of the sampler; each pixel's samples
// are summed in index order, so the image is bit-identical for any thread count.
#pragma once

#include <atomic>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/image.h"
#include "render/integrator_settings.h"
#include "render/render_scene.h"
#include "render/running_sums.h"

namespace pathlab {

// Watching and stopping a render from another thread (the Python module's
// progress callback and Ctrl-C): the renderer counts finished tiles, and once
// `cancel` is set it starts no further tile and throws RenderCancelled.
struct RenderControl {
    std::atomic<bool> cancel{false};
    std::atomic<size_t> tilesDone{0}, tilesTotal{0};
};

struct RenderCancelled : std::runtime_error {
    RenderCancelled() : std::runtime_error("render cancelled") {}
};

struct RenderSettings {
    std::string sampler = "independent";
    int samplesPerPixel = 16;
    uint64_t seed = 0;
    Vec2i resolution{0, 0};  // 0×0: the scene's own
    int maxDepth = 8;
    bool russianRoulette = true;
    int rouletteDepth = kDefaultRouletteDepth;  // bounces before roulette may end a path
    bool batchPaths = true;                     // IntegratorSettings::batchPaths
    // Carry four sampled wavelengths per path instead of RGB
    // (render/colour/spectral_paths.h); the image is linear sRGB either way.
    bool spectral = false;
    // How spectral mode draws its wavelengths (IntegratorSettings::wavelengths);
    // anything but the default needs `spectral`.
    spectral::WavelengthSampling wavelengths = spectral::WavelengthSampling::Visible;
    int threads = 0;  // 0: all cores
    bool progress = false;
    // Also keep the image after each of these sample counts (ascending, each
    // below samplesPerPixel). Only for progressive samplers (SamplerInfo), for
    // which each is bit-identical to a render at that spp.
    std::vector<int> prefixSpp;
    // Keep every pixel as the weighted film does (Σ w·L / Σ w, with its
    // variance estimate) even when the filter's weights are all 1 — for the
    // box and triangle filters the same image, bit for bit, as the plain mean.
    // Off only to compare the two.
    bool weightedFilm = false;
    RenderControl* control = nullptr;  // optional; outlives the render
    // Optional: continue from these sums of an earlier render of the same
    // scene and settings with fewer spp (progressive samplers only, no
    // prefixes), rendering only the samples after its spp, and leave the sums
    // of all samplesPerPixel in it; emptied when the render is cancelled.
    RunningSums* resume = nullptr;
    // Optional, with `resume` empty: render only samples [first, end) of each
    // pixel of this render of samplesPerPixel — the very samples the whole
    // render draws there, whatever the sampler, since its sample k depends on
    // the pixel, k, the seed and samplesPerPixel only — and leave their sums
    // alone in `resume` (RunningSums::first = first). Sums of consecutive
    // ranges added in a fixed order (addRunningSums) make one render of them
    // all, the same bits whichever process rendered each range.
    std::optional<SampleRange> sampleRange;
};

struct RenderStats {
    double seconds = 0;
    uint64_t paths = 0;
    uint64_t rays = 0;        // camera + bounce rays
    uint64_t shadowRays = 0;  // next-event visibility rays
    uint64_t dimensions = 0;  // sampler dimensions drawn (a 2D draw counts 2)
    uint64_t nonFinite = 0;   // samples that were NaN/Inf and were discarded
};

// The image of the first `spp` samples of every pixel.
struct PrefixImage {
    int spp = 0;
    Image image, varianceOfMean;
    // What a render of `spp` samples takes: the render's fixed cost plus its
    // parallel time × the share of per-pixel time spent on these samples.
    double seconds = 0;
    uint64_t nonFinite = 0;
};

// The images cover the film's pixel bounds (render/film.h): the whole
// resolution unless the scene's film has a crop window.
struct RenderOutput {
    Image image;           // filtered radiance per pixel (the plain mean for a box of radius ½)
    Image varianceOfMean;  // per pixel and channel: sample variance / spp
    RenderStats stats;
    std::vector<PrefixImage> prefixes;  // one per RenderSettings::prefixSpp
};

// Throws InputError when a setting is out of range or the sampler is unknown.
void validateRenderSettings(const RenderSettings& settings);

RenderOutput render(const RenderScene& scene, const RenderSettings& settings);

// The image and variance that a render of `sums.spp` samples per pixel with
// these settings writes from such sums (e.g. merged sample ranges): bit for
// bit render()'s image when `sums` are the sums of a whole render. Only
// `stats.paths` of the statistics is set.
RenderOutput imageOfRunningSums(const RenderScene& scene, const RenderSettings& settings,
                                const RunningSums& sums);

}  // namespace pathlab
