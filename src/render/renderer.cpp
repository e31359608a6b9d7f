#include "render/renderer.h"

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <memory>
#include <mutex>
#include <type_traits>
#include <variant>

#include "core/error.h"
#include "core/float_mode.h"
#include "core/thread_annotations.h"
#include "render/batched_paths.h"
#include "render/camera_model.h"
#include "render/camera_samples.h"
#include "render/colour/spectral_paths.h"
#include "render/film.h"
#include "render/path_integrator.h"
#include "render/pixel_filter.h"
#include "render/running_sums.h"
#include "sampling/registry.h"
#include "spectral/rgb_spectrum_table.h"
#include "spectral/white_balance.h"

namespace pathlab {
namespace {

constexpr int kTileSize = 16;
// The samplers follow this renderer's draw order (sampling/sampler.h): a
// camera packet's positions are one lane draw of kCameraPacketSamples, and a
// batch of kBatchSamples is whole camera packets.
static_assert(kPacketWidth == kCameraPacketSamples);

struct Tile {
    int x0, y0, x1, y1;
};

// Where a pixel's running sums are written out: after each prefix's sample
// count, and after all samples (the last checkpoint).
struct Checkpoints {
    std::vector<int> spp;  // ascending; the last is samplesPerPixel
    std::vector<Image*> image, variance;
    bool timed = false;  // measure the time each prefix takes
    int sumsFirst = 0;   // the sample the running sums begin at (RunningSums::first)
};

struct TileResult {
    PathCounters counters;
    uint64_t nonFinite = 0;
    std::vector<uint64_t> nonFiniteAt;  // per checkpoint, samples so far
    std::vector<double> secondsAt;      // per checkpoint, pixel time so far
};

// What every tile shares about the frame: how film positions become rays,
// which pixels of the full image are rendered, and the film's scale.
struct FrameSetup {
    CameraModel camera;
    FilterSampler filter;
    PixelBounds bounds;
    float scale;
    spectral::RgbBalance balance;  // the film's white balance, per sample
    // A pixel's camera rays all start at one point (a pinhole): Embree traces
    // them as one coherent packet from it.
    bool sharedOrigin;
};

// Throws InputError when the film's crop, filter or scale, or the camera,
// make no sense.
FrameSetup makeFrame(const SceneDescription& desc, Vec2i resolution) {
    if (!(std::isfinite(desc.film.scale) && desc.film.scale > 0))
        throw InputError("film scale must be positive, got " + std::to_string(desc.film.scale));
    CameraModel camera(desc.camera, resolution);
    const bool shared = camera.isPinhole() || camera.projective().sharedOrigin();
    return FrameSetup{std::move(camera),
                      FilterSampler(desc.film.filter),
                      filmPixelBounds(desc.film, resolution),
                      desc.film.scale,
                      spectral::linearSrgbWhiteBalance(desc.film.whiteBalance),
                      shared};
}

// Mean and variance of the mean of the first n samples, from running sums,
// times the film's scale (variance by its square).
void writePixel(const PlainSums& sums, int n, Vec2i p, double scale, Image& image,
                Image& variance) {
    const double *sum = sums.sum, *sumSq = sums.sumSq;
    float mean[3], var[3];
    for (int c = 0; c < 3; ++c) {
        double m = sum[c] / n;
        double v = n > 1 ? std::max(0.0, (sumSq[c] - n * m * m) / (n - 1)) : 0;
        if (scale != 1) m *= scale, v *= scale * scale;
        mean[c] = float(m);
        var[c] = float(v / n);
    }
    image.set(p.x, p.y, Vec3f(mean[0], mean[1], mean[2]));
    variance.set(p.x, p.y, Vec3f(var[0], var[1], var[2]));
}

// pbrt-v4's RGBFilm pixel, Σ w·L / Σ w, and the variance of that ratio by the
// delta method — Σ w²(L − μ)² / (Σ w)², the usual estimate for
// self-normalised importance sampling (Owen, "Monte Carlo theory, methods and
// examples", 2013, §9.2) — times n/(n − 1), which makes it the plain mean's
// s²/n when every weight is 1. When the weights cancel exactly (Σ w = 0, as
// two samples of opposite sign do), the ratio is 0/0 and pbrt-v4 leaves the
// pixel black; pathlab takes Σ |w|·L / Σ |w| instead, which a scene of
// constant radiance still returns exactly.
void writeWeightedPixel(const WeightedSums& s, int n, Vec2i p, double scale, Image& image,
                        Image& variance) {
    const bool cancelled = s.w == 0;
    const double total = cancelled ? s.absW : s.w;
    float mean[3], var[3];
    for (int c = 0; c < 3; ++c) {
        const double m = total != 0 ? (cancelled ? s.absWL[c] : s.wL[c]) / total : 0;
        const double spread = s.w2L2[c] - 2 * m * s.w2L[c] + m * m * s.w2;
        const double v =
            n > 1 && total != 0 ? std::max(0.0, spread) / (total * total) * n / (n - 1) : 0;
        mean[c] = float(m * scale);
        var[c] = float(v * scale * scale);
    }
    image.set(p.x, p.y, Vec3f(mean[0], mean[1], mean[2]));
    variance.set(p.x, p.y, Vec3f(var[0], var[1], var[2]));
}

using Clock = std::chrono::steady_clock;

// Samples first … first + count − 1 of a pixel (count ≤ kPacketWidth): their
// camera rays and filter weights (drawCameraSamples), traced as one packet.
template <Sampler S>
void traceCameraPacket(const RenderScene& scene, const FrameSetup& frame, S& sampler, Vec2i pixel,
                       int first, int count, Vec3f* origins, Vec3f* dirs, float* weights,
                       SurfaceInteraction* si, bool* found) {
    drawCameraSamples(frame.camera, frame.filter, sampler, pixel, first, count, origins, dirs,
                      weights);
    if (frame.sharedOrigin) {
        scene.intersectPacket(origins[0], dirs, count, si, found);
        return;
    }
    // Rays from points of a lens or an orthographic screen: a packet of
    // rays of any origins (intersectPacket assumes one).
    float ox[kPacketWidth] = {}, oy[kPacketWidth] = {}, oz[kPacketWidth] = {};
    float dx[kPacketWidth] = {}, dy[kPacketWidth] = {}, dz[kPacketWidth] = {};
    int active[kPacketWidth] = {}, to[kPacketWidth];
    for (int k = 0; k < count; ++k) {
        ox[k] = origins[k].x, oy[k] = origins[k].y, oz[k] = origins[k].z;
        dx[k] = dirs[k].x, dy[k] = dirs[k].y, dz[k] = dirs[k].z;
        active[k] = 1, to[k] = k;
    }
    scene.intersectLanes({ox, oy, oz, dx, dy, dz, nullptr, active, count}, to, si, found);
}

// A batch of a pixel's samples: their camera rays, first hits and radiance.
// One per tile, reused pixel after pixel, as the batched integrator keeps its
// paths (batched_paths.h): constructing these ≈ 5 KB, zeroed, for every
// pixel was a tenth of a 1-spp pass.
struct PixelBatch {
    Vec3f origins[kBatchSamples], dirs[kBatchSamples];
    float weights[kBatchSamples];
    SurfaceInteraction first[kBatchSamples];
    bool found[kBatchSamples];
    Vec3f radiance[kBatchSamples];
};

// kWeighted: the filter's weights vary (Σ w·L / Σ w); otherwise every weight
// is 1 and the pixel is the plain mean, summed exactly as it always was.
template <bool kWeighted>
using PixelSums = std::conditional_t<kWeighted, WeightedSums, PlainSums>;

// Adds samples firstSample … (the last checkpoint) − 1 of the pixel to `sums`.
template <bool kWeighted, Sampler S>
void renderPixel(const RenderScene& scene, const FrameSetup& frame, S& sampler, Vec2i pixel,
                 const IntegratorSettings& integrator, const Checkpoints& checkpoints,
                 PixelSums<kWeighted>& sums, int firstSample, PixelBatch& batch,
                 TileResult& result) {
    const int end = checkpoints.spp.back();
    const Clock::time_point start = checkpoints.timed ? Clock::now() : Clock::time_point{};
    const Vec2i at{pixel.x - frame.bounds.min.x, pixel.y - frame.bounds.min.y};  // in the image
    const uint64_t cameraDimensions = frame.camera.hasLens() ? 4 : 2;
    uint64_t nonFinite = 0;  // this pixel's, so far
    size_t next = 0;         // the next checkpoint
    // The pixel's paths go kBatchSamples at a time, a batch ending at each
    // checkpoint so that its time is the time of its samples; their camera
    // rays are traced as packets.
    for (int i0 = firstSample, count; i0 < end; i0 += count) {
        count = std::min(kBatchSamples, checkpoints.spp[next] - i0);
        Vec3f* const origins = batch.origins;
        Vec3f* const dirs = batch.dirs;
        float* const weights = batch.weights;
        SurfaceInteraction* const first = batch.first;
        bool* const found = batch.found;
        for (int p0 = 0; p0 < count; p0 += kPacketWidth)
            traceCameraPacket(scene, frame, sampler, pixel, i0 + p0,
                              std::min(kPacketWidth, count - p0), origins + p0, dirs + p0,
                              weights + p0, first + p0, found + p0);
        result.counters.rays += uint64_t(count);
        result.counters.dimensions += cameraDimensions * uint64_t(count);
        Vec3f* const radiance = batch.radiance;
        if (integrator.spectral)
            estimateSpectralRadiance(scene, origins, dirs, found, first, count, sampler, pixel, i0,
                                     integrator, integrator.wavelengthDimension, result.counters,
                                     radiance);
        else if (integrator.batchPaths)
            estimateRadianceBatch(scene, dirs, found, first, count, sampler, pixel, i0, integrator,
                                  result.counters, radiance);
        else
            for (int k = 0; k < count; ++k)
                radiance[k] = estimateRadiance(scene, origins[k], dirs[k], found[k], first[k],
                                               sampler, pixel, i0 + k, integrator, result.counters);
        for (int k = 0; k < count; ++k) {
            Vec3f L = frame.balance.identity ? radiance[k] : frame.balance(radiance[k]);
            if (!isFinite(L)) {  // never let a NaN/Inf reach the image
                ++nonFinite;
                L = Vec3f(0.0f);
            }
            if constexpr (kWeighted)
                sums.add(weights[k], L);
            else
                sums.add(L);
            if (i0 + k + 1 != checkpoints.spp[next]) continue;
            // Summed in index order either way: bit-identical to a render
            // that stops here.
            const int summed = i0 + k + 1 - checkpoints.sumsFirst;
            if constexpr (kWeighted)
                writeWeightedPixel(sums, summed, at, frame.scale, *checkpoints.image[next],
                                   *checkpoints.variance[next]);
            else
                writePixel(sums, summed, at, frame.scale, *checkpoints.image[next],
                           *checkpoints.variance[next]);
            result.nonFiniteAt[next] += nonFinite;
            if (checkpoints.timed)
                result.secondsAt[next] +=
                    std::chrono::duration<double>(Clock::now() - start).count();
            ++next;
        }
    }
    result.nonFinite += nonFinite;
}

// The pixel's sums in `resume` (RenderSettings::resume), or fresh ones.
template <bool kWeighted>
PixelSums<kWeighted>& pixelSums(RunningSums* resume, const PixelBounds& b, int x, int y,
                                PixelSums<kWeighted>& fresh) {
    if (!resume) return fresh = {};
    const size_t index = size_t(y - b.min.y) * size_t(b.width()) + size_t(x - b.min.x);
    if constexpr (kWeighted)
        return resume->weighted[index];
    else
        return resume->plain[index];
}

template <bool kWeighted, Sampler S>
TileResult renderTile(const RenderScene& scene, const FrameSetup& frame, S& sampler,
                      const Tile& tile, const IntegratorSettings& integrator,
                      const Checkpoints& checkpoints, RunningSums* resume, int firstSample) {
    TileResult result;
    result.nonFiniteAt.assign(checkpoints.spp.size(), 0);
    result.secondsAt.assign(checkpoints.spp.size(), 0.0);
    PixelSums<kWeighted> fresh;
    const auto batch = std::make_unique<PixelBatch>();
    for (int y = tile.y0; y < tile.y1; ++y)
        for (int x = tile.x0; x < tile.x1; ++x)
            renderPixel<kWeighted>(scene, frame, sampler, Vec2i{x, y}, integrator, checkpoints,
                                   pixelSums<kWeighted>(resume, frame.bounds, x, y, fresh),
                                   firstSample, *batch, result);
    return result;
}

// Sizes empty running sums for the image, or checks that earlier ones fit it.
void prepareRunningSums(RunningSums& sums, size_t pixels, bool weighted) {
    if (sums.spp == 0) {
        sums.plain.assign(weighted ? 0 : pixels, PlainSums{});
        sums.weighted.assign(weighted ? pixels : 0, WeightedSums{});
        return;
    }
    if ((weighted ? sums.weighted.size() : sums.plain.size()) != pixels)
        throw std::logic_error("running sums of another image or film");
}

class ProgressBar {
  public:
    ProgressBar(bool enabled, size_t total) : enabled_(enabled && isatty(2)), total_(total) {}
    void advance() {
        const size_t done = ++done_;
        if (!enabled_) return;
        std::lock_guard<std::mutex> lock(mutex_);
        const int percent = int(100 * done / total_);
        if (percent == lastPercent_) return;
        lastPercent_ = percent;
        std::fprintf(stderr, "\r[%-40s] %3d%%",
                     std::string(size_t(percent * 40 / 100), '=').c_str(), percent);
        if (done == total_) std::fprintf(stderr, "\n");
    }

  private:
    bool enabled_;
    size_t total_;
    std::atomic<size_t> done_{0};
    std::mutex mutex_;
    int lastPercent_ = -1;
};

}  // namespace

void validateRenderSettings(const RenderSettings& s) {
    if (s.samplesPerPixel < 1 || s.samplesPerPixel > (1 << 24))
        throw InputError("spp must be between 1 and 16777216, got " +
                         std::to_string(s.samplesPerPixel));
    if (s.resolution.x < 0 || s.resolution.y < 0 || s.resolution.x > 16384 ||
        s.resolution.y > 16384 || (s.resolution.x == 0) != (s.resolution.y == 0))
        throw InputError("image size must be between 1x1 and 16384x16384, got " +
                         std::to_string(s.resolution.x) + "x" + std::to_string(s.resolution.y));
    if (s.maxDepth < 0 || s.maxDepth > 1024)
        throw InputError("max depth must be between 0 and 1024, got " + std::to_string(s.maxDepth));
    if (s.rouletteDepth < 0 || s.rouletteDepth > 1024)
        throw InputError("roulette depth must be between 0 and 1024, got " +
                         std::to_string(s.rouletteDepth));
    if (s.threads < 0 || s.threads > 4096)
        throw InputError("threads must be between 0 (all cores) and 4096, got " +
                         std::to_string(s.threads));
    if (s.wavelengths != spectral::WavelengthSampling::Visible && !s.spectral)
        throw InputError(std::string("wavelength sampling '") +
                         spectral::wavelengthSamplingName(s.wavelengths) +
                         "' needs spectral mode (--spectral)");
    const SamplerInfo& info = samplerInfo(s.sampler);
    int previous = 0;
    for (int n : s.prefixSpp) {
        if (n <= previous || n >= s.samplesPerPixel)
            throw InputError("prefix sample counts must ascend and stay below spp " +
                             std::to_string(s.samplesPerPixel) + ", got " + std::to_string(n));
        previous = n;
    }
    if (!s.prefixSpp.empty() && !info.progressive)
        throw InputError("sampler '" + s.sampler +
                         "' is not progressive: its first samples are not a render of fewer");
    if (s.sampleRange) {
        const SampleRange& r = *s.sampleRange;
        if (r.first < 0 || r.first >= r.end || r.end > s.samplesPerPixel)
            throw InputError("a sample range must lie within 0…" +
                             std::to_string(s.samplesPerPixel) + " and hold samples, got " +
                             std::to_string(r.first) + "…" + std::to_string(r.end));
        if (!s.resume || s.resume->spp != 0 || !s.prefixSpp.empty())
            throw InputError(
                "a sample range is rendered into empty running sums, without prefixes");
    } else if (s.resume && s.resume->spp > 0) {
        if (s.resume->first != 0)
            throw InputError("the sums of a sample range cannot be continued");
        if (!info.progressive)
            throw InputError("sampler '" + s.sampler + "' is not progressive: a render of " +
                             std::to_string(s.samplesPerPixel) + " spp cannot continue one of " +
                             std::to_string(s.resume->spp));
        if (s.resume->spp >= s.samplesPerPixel || !s.prefixSpp.empty())
            throw InputError("a continued render needs more spp than the " +
                             std::to_string(s.resume->spp) + " it continues, and no prefixes");
    }
}

RenderOutput render(const RenderScene& scene, const RenderSettings& settings) {
    validateRenderSettings(settings);
    // Spectral mode's RGB-to-spectrum table is read (or made) once per
    // process, like the scene's acceleration structure, before the clock.
    if (settings.spectral) spectral::defaultRgbToSpectrumTable();
    const auto start = std::chrono::steady_clock::now();
    const SceneDescription& desc = scene.description();
    // The full image the camera maps; the rendered image is its crop.
    const Vec2i res = settings.resolution.x > 0 ? settings.resolution : desc.resolution;
    const AnySampler prototype =
        makeSampler(settings.sampler, SamplerConfig{settings.samplesPerPixel, settings.seed, res});
    const FrameSetup frame = makeFrame(desc, res);
    const bool weighted = settings.weightedFilm || !frame.filter.constantWeight();
    IntegratorSettings integrator{settings.maxDepth, settings.russianRoulette,
                                  settings.rouletteDepth, settings.batchPaths};
    const bool lens = frame.camera.hasLens();
    integrator.firstBounce = dims::firstBounce(lens);
    if (settings.spectral) {
        integrator.spectral = true;
        integrator.wavelengthDimension = dims::wavelength(lens);
        integrator.firstBounce = dims::spectralFirstBounce(lens);
        integrator.wavelengths = settings.wavelengths;
    }

    const PixelBounds& b = frame.bounds;
    std::vector<Tile> tiles;
    for (int y = b.min.y; y < b.max.y; y += kTileSize)
        for (int x = b.min.x; x < b.max.x; x += kTileSize)
            tiles.push_back(
                {x, y, std::min(x + kTileSize, b.max.x), std::min(y + kTileSize, b.max.y)});

    const int w = b.width(), h = b.height();
    RenderOutput out{Image(w, h), Image(w, h), {}, {}};
    for (int n : settings.prefixSpp) out.prefixes.push_back({n, Image(w, h), Image(w, h), 0, 0});
    Checkpoints checkpoints;
    for (PrefixImage& p : out.prefixes) {
        checkpoints.spp.push_back(p.spp);
        checkpoints.image.push_back(&p.image);
        checkpoints.variance.push_back(&p.varianceOfMean);
    }
    // A sample range ends early; its sums start afresh at its first sample.
    const std::optional<SampleRange>& range = settings.sampleRange;
    RunningSums* const resume = settings.resume;
    const int firstSample = range ? range->first : resume ? resume->spp : 0;
    checkpoints.spp.push_back(range ? range->end : settings.samplesPerPixel);
    checkpoints.sumsFirst = range ? range->first : 0;
    checkpoints.image.push_back(&out.image);
    checkpoints.variance.push_back(&out.varianceOfMean);
    checkpoints.timed = !out.prefixes.empty();
    if (resume) prepareRunningSums(*resume, size_t(w) * size_t(h), weighted);

    std::vector<TileResult> results(tiles.size());
    ProgressBar progress(settings.progress, tiles.size());
    RenderControl* const control = settings.control;
    if (control) control->tilesTotal = tiles.size();
    std::optional<tbb::global_control> limit;
    if (settings.threads > 0)
        limit.emplace(tbb::global_control::max_allowed_parallelism, size_t(settings.threads));
    // The happens-before edges parallel_for guarantees, for ThreadSanitizer
    // (core/thread_annotations.h). The tokens are static so that a task reads
    // nothing of the caller's before happensAfter.
    static const char tasksStart = 0, tasksEnd = 0;
    const auto renderOneTile = [&](size_t t) {
        happensAfter(&tasksStart);
        if (control && control->cancel.load(std::memory_order_relaxed)) {
            happensBefore(&tasksEnd);
            return;
        }
        {
            const ScopedFlushDenormals denormals;  // as Embree asks (core/float_mode.h)
            AnySampler sampler = prototype;
            results[t] = std::visit(
                [&](auto& s) {
                    return weighted ? renderTile<true>(scene, frame, s, tiles[t], integrator,
                                                       checkpoints, resume, firstSample)
                                    : renderTile<false>(scene, frame, s, tiles[t], integrator,
                                                        checkpoints, resume, firstSample);
                },
                sampler);
        }
        progress.advance();
        if (control) ++control->tilesDone;
        happensBefore(&tasksEnd);
    };
    happensBefore(&tasksStart);
    const auto parallelStart = std::chrono::steady_clock::now();
    tbb::parallel_for(size_t(0), tiles.size(), renderOneTile);
    const double parallelSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - parallelStart).count();
    happensAfter(&tasksEnd);
    if (control && control->cancel) {
        if (resume) *resume = {};  // some pixels summed more samples than others
        throw RenderCancelled();
    }

    std::vector<double> pixelSeconds(checkpoints.spp.size(), 0.0);
    for (const TileResult& r : results) {
        out.stats.rays += r.counters.rays;
        out.stats.shadowRays += r.counters.shadowRays;
        out.stats.dimensions += r.counters.dimensions;
        out.stats.nonFinite += r.nonFinite;
        for (size_t k = 0; k < pixelSeconds.size(); ++k) pixelSeconds[k] += r.secondsAt[k];
        for (size_t k = 0; k < out.prefixes.size(); ++k)
            out.prefixes[k].nonFinite += r.nonFiniteAt[k];
    }
    if (resume) {
        resume->first = checkpoints.sumsFirst;
        resume->spp = checkpoints.spp.back() - checkpoints.sumsFirst;
    }
    out.stats.paths = uint64_t(w) * uint64_t(h) * uint64_t(checkpoints.spp.back() - firstSample);
    out.stats.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double fixedSeconds = std::max(0.0, out.stats.seconds - parallelSeconds);
    for (size_t k = 0; k < out.prefixes.size(); ++k)
        out.prefixes[k].seconds =
            fixedSeconds + parallelSeconds * pixelSeconds[k] / std::max(pixelSeconds.back(), 1e-12);
    return out;
}

}  // namespace pathlab

namespace pathlab {

RenderOutput imageOfRunningSums(const RenderScene& scene, const RenderSettings& settings,
                                const RunningSums& sums) {
    const SceneDescription& desc = scene.description();
    const Vec2i res = settings.resolution.x > 0 ? settings.resolution : desc.resolution;
    const FrameSetup frame = makeFrame(desc, res);
    const PixelBounds& b = frame.bounds;
    const int w = b.width(), h = b.height();
    const bool weighted = !sums.weighted.empty();
    if ((weighted ? sums.weighted.size() : sums.plain.size()) != size_t(w) * size_t(h) ||
        sums.spp < 1)
        throw std::logic_error("running sums of another image or film");
    RenderOutput out{Image(w, h), Image(w, h), {}, {}};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * size_t(w) + size_t(x);
            if (weighted)
                writeWeightedPixel(sums.weighted[i], sums.spp, {x, y}, frame.scale, out.image,
                                   out.varianceOfMean);
            else
                writePixel(sums.plain[i], sums.spp, {x, y}, frame.scale, out.image,
                           out.varianceOfMean);
        }
    out.stats.paths = uint64_t(w) * uint64_t(h) * uint64_t(sums.spp);
    return out;
}

}  // namespace pathlab
