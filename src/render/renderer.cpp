#include "render/renderer.h"

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <variant>

#include "core/error.h"
#include "core/float_mode.h"
#include "core/thread_annotations.h"
#include "render/camera.h"
#include "render/path_integrator.h"
#include "sampling/registry.h"

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
};

struct TileResult {
    PathCounters counters;
    uint64_t nonFinite = 0;
    std::vector<uint64_t> nonFiniteAt;  // per checkpoint, samples so far
    std::vector<double> secondsAt;      // per checkpoint, pixel time so far
};

// Mean and variance of the mean of the first n samples, from running sums.
void writePixel(const double* sum, const double* sumSq, int n, Vec2i p, Image& image,
                Image& variance) {
    float mean[3], var[3];
    for (int c = 0; c < 3; ++c) {
        const double m = sum[c] / n;
        const double v = n > 1 ? std::max(0.0, (sumSq[c] - n * m * m) / (n - 1)) : 0;
        mean[c] = float(m);
        var[c] = float(v / n);
    }
    image.set(p.x, p.y, Vec3f(mean[0], mean[1], mean[2]));
    variance.set(p.x, p.y, Vec3f(var[0], var[1], var[2]));
}

using Clock = std::chrono::steady_clock;

// Samples first … first + count − 1 of a pixel (count ≤ kPacketWidth): their
// positions in the pixel, and their camera rays traced as one packet.
template <Sampler S>
void traceCameraPacket(const RenderScene& scene, const PinholeCamera& camera, S& sampler,
                       Vec2i pixel, int first, int count, Vec3f* dirs, SurfaceInteraction* si,
                       bool* found) {
    int indices[kPacketWidth];
    for (int k = 0; k < count; ++k) indices[k] = first + k;
    Vec2f u[kPacketWidth];
    drawPixelLanes(sampler, pixel, indices, count, u);
    for (int k = 0; k < count; ++k)
        dirs[k] = camera.direction(float(pixel.x) + u[k].x, float(pixel.y) + u[k].y);
    scene.intersectPacket(camera.eye(), dirs, count, si, found);
}

template <Sampler S>
void renderPixel(const RenderScene& scene, const PinholeCamera& camera, S& sampler, Vec2i pixel,
                 const IntegratorSettings& integrator, const Checkpoints& checkpoints,
                 TileResult& result) {
    const int spp = sampler.samplesPerPixel();
    const Clock::time_point start = checkpoints.timed ? Clock::now() : Clock::time_point{};
    double sum[3] = {0, 0, 0}, sumSq[3] = {0, 0, 0};
    uint64_t nonFinite = 0;  // this pixel's, so far
    size_t next = 0;         // the next checkpoint
    // The pixel's paths go kBatchSamples at a time, a batch ending at each
    // checkpoint so that its time is the time of its samples; their camera
    // rays are nearly parallel and are traced as packets.
    for (int i0 = 0, count; i0 < spp; i0 += count) {
        count = std::min(kBatchSamples, checkpoints.spp[next] - i0);
        Vec3f dirs[kBatchSamples];
        SurfaceInteraction first[kBatchSamples];
        bool found[kBatchSamples];
        for (int p0 = 0; p0 < count; p0 += kPacketWidth)
            traceCameraPacket(scene, camera, sampler, pixel, i0 + p0,
                              std::min(kPacketWidth, count - p0), dirs + p0, first + p0,
                              found + p0);
        result.counters.rays += uint64_t(count);
        result.counters.dimensions += 2 * uint64_t(count);
        Vec3f radiance[kBatchSamples];
        if (integrator.batchPaths)
            estimateRadianceBatch(scene, dirs, found, first, count, sampler, pixel, i0, integrator,
                                  result.counters, radiance);
        else
            for (int k = 0; k < count; ++k)
                radiance[k] = estimateRadiance(scene, camera.eye(), dirs[k], found[k], first[k],
                                               sampler, pixel, i0 + k, integrator, result.counters);
        for (int k = 0; k < count; ++k) {
            Vec3f L = radiance[k];
            if (!isFinite(L)) {  // never let a NaN/Inf reach the image
                ++nonFinite;
                L = Vec3f(0.0f);
            }
            for (int c = 0; c < 3; ++c) sum[c] += L[c], sumSq[c] += double(L[c]) * L[c];
            if (i0 + k + 1 != checkpoints.spp[next]) continue;
            // Summed in index order either way: bit-identical to a render
            // that stops here.
            writePixel(sum, sumSq, i0 + k + 1, pixel, *checkpoints.image[next],
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

template <Sampler S>
TileResult renderTile(const RenderScene& scene, const PinholeCamera& camera, S& sampler,
                      const Tile& tile, const IntegratorSettings& integrator,
                      const Checkpoints& checkpoints) {
    TileResult result;
    result.nonFiniteAt.assign(checkpoints.spp.size(), 0);
    result.secondsAt.assign(checkpoints.spp.size(), 0.0);
    for (int y = tile.y0; y < tile.y1; ++y)
        for (int x = tile.x0; x < tile.x1; ++x)
            renderPixel(scene, camera, sampler, Vec2i{x, y}, integrator, checkpoints, result);
    return result;
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
}

RenderOutput render(const RenderScene& scene, const RenderSettings& settings) {
    validateRenderSettings(settings);
    const auto start = std::chrono::steady_clock::now();
    const Vec2i res =
        settings.resolution.x > 0 ? settings.resolution : scene.description().resolution;
    const AnySampler prototype =
        makeSampler(settings.sampler, SamplerConfig{settings.samplesPerPixel, settings.seed, res});
    const PinholeCamera camera(scene.description().camera, res);
    const IntegratorSettings integrator{settings.maxDepth, settings.russianRoulette,
                                        settings.rouletteDepth, settings.batchPaths};

    std::vector<Tile> tiles;
    for (int y = 0; y < res.y; y += kTileSize)
        for (int x = 0; x < res.x; x += kTileSize)
            tiles.push_back({x, y, std::min(x + kTileSize, res.x), std::min(y + kTileSize, res.y)});

    RenderOutput out{Image(res.x, res.y), Image(res.x, res.y), {}, {}};
    for (int n : settings.prefixSpp)
        out.prefixes.push_back({n, Image(res.x, res.y), Image(res.x, res.y), 0, 0});
    Checkpoints checkpoints;
    for (PrefixImage& p : out.prefixes) {
        checkpoints.spp.push_back(p.spp);
        checkpoints.image.push_back(&p.image);
        checkpoints.variance.push_back(&p.varianceOfMean);
    }
    checkpoints.spp.push_back(settings.samplesPerPixel);
    checkpoints.image.push_back(&out.image);
    checkpoints.variance.push_back(&out.varianceOfMean);
    checkpoints.timed = !out.prefixes.empty();

    std::vector<TileResult> results(tiles.size());
    ProgressBar progress(settings.progress, tiles.size());
    std::optional<tbb::global_control> limit;
    if (settings.threads > 0)
        limit.emplace(tbb::global_control::max_allowed_parallelism, size_t(settings.threads));
    // The happens-before edges parallel_for guarantees, for ThreadSanitizer
    // (core/thread_annotations.h). The tokens are static so that a task reads
    // nothing of the caller's before happensAfter.
    static const char tasksStart = 0, tasksEnd = 0;
    const auto renderOneTile = [&](size_t t) {
        happensAfter(&tasksStart);
        {
            const ScopedFlushDenormals denormals;  // as Embree asks (core/float_mode.h)
            AnySampler sampler = prototype;
            results[t] = std::visit(
                [&](auto& s) {
                    return renderTile(scene, camera, s, tiles[t], integrator, checkpoints);
                },
                sampler);
        }
        progress.advance();
        happensBefore(&tasksEnd);
    };
    happensBefore(&tasksStart);
    const auto parallelStart = std::chrono::steady_clock::now();
    tbb::parallel_for(size_t(0), tiles.size(), renderOneTile);
    const double parallelSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - parallelStart).count();
    happensAfter(&tasksEnd);

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
    out.stats.paths = uint64_t(res.x) * uint64_t(res.y) * uint64_t(settings.samplesPerPixel);
    out.stats.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double fixedSeconds = std::max(0.0, out.stats.seconds - parallelSeconds);
    for (size_t k = 0; k < out.prefixes.size(); ++k)
        out.prefixes[k].seconds =
            fixedSeconds + parallelSeconds * pixelSeconds[k] / std::max(pixelSeconds.back(), 1e-12);
    return out;
}

}  // namespace pathlab
