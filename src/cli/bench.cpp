// `pathlab bench`: the renderer's throughput on the built-in scenes at a fixed
// workload (512×512, max depth 8, 64 spp, independent sampler; the median of
// --runs frames), and where the time goes: the ray-tracing limit (the same
// frame's rays replayed through Embree alone), thread scaling, memory per
// million triangles, the frame's time split between Embree, the sampler and
// the rest and, with --samplers, each sampler's share of a frame.
#include <sys/resource.h>
#include <tbb/info.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "render/renderer.h"
#include "sampling/sampler_cost.h"
#include "scene/loader.h"
#include "scene/ray_replay.h"

namespace pathlab::cli {
namespace {

struct BenchOptions {
    bool json = false;
    bool samplers = false;
    bool scaling = true;
    int spp = 64;
    int size = 512;
    int threads = 0;
    int rounds = 3;  // --samplers: frames per sampler, in rotated order
    int runs = 3;    // frames per scene (median) and raw replays per mode (fastest)
    std::vector<std::string> scenes{"cornell-box", "wolf"};
    int threadCount() const { return threads > 0 ? threads : tbb::info::default_concurrency(); }
};

constexpr int kMaxDepth = 8;

// Text lines go to stdout unless --json, where one JSON document does.
void say(const BenchOptions& o, const char* format, auto... args) {
    if (!o.json) std::printf(format, args...);
}

RenderSettings settingsFor(const BenchOptions& o, const std::string& sampler, int threads) {
    RenderSettings s;
    s.sampler = sampler;
    s.samplesPerPixel = o.spp;
    s.resolution = {o.size, o.size};
    s.maxDepth = kMaxDepth;
    s.threads = threads;
    return s;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

double raysPerSecond(const RenderStats& st, double seconds) {
    return double(st.rays + st.shadowRays) / seconds;
}

// The cost model's single-threaded ns per dimension for `sampler` at the
// bench's image size and spp (sampling/sampler_cost.h: paths of depth 4,
// 200 000 of them).
double costModelNanoseconds(const std::string& sampler, const BenchOptions& o) {
    const int batchSize = std::min(o.spp, kBatchSamples);
    return nanosecondsPerDimension(sampler, o.spp, {o.size, o.size}, 4,
                                   (200000 + batchSize - 1) / batchSize);
}

// The frame's rays replayed through Embree alone, in each query mode, with
// the renderer's thread count. Recorded from one full batch per pixel
// (kBatchSamples spp: the rays come in the renderer's packets, and their
// distribution is that of any spp) over a 36th of the pixels, which keeps
// the recording to about 32 bytes × 5 rays × 64 samples × size²/36. A mode's
// rate is the fastest of its --runs replays: the limit is what Embree can
// do, a replay takes only tens of milliseconds, and other work on the
// machine can only slow it.
nlohmann::json rayLimit(RenderScene& scene, const BenchOptions& o, double rendererRaysPerSecond) {
    RayRecorder recorder;
    scene.setRayRecorder(&recorder);
    RenderSettings s = settingsFor(o, "independent", o.threads);
    s.samplesPerPixel = kBatchSamples;
    s.resolution = {std::max(1, o.size / 6), std::max(1, o.size / 6)};
    render(scene, s);
    scene.setRayRecorder(nullptr);
    const std::vector<RecordedRay> rays = recorder.gather();
    nlohmann::json modes = nlohmann::json::object(), modeRuns = nlohmann::json::object();
    double best = 0;
    for (ReplayMode mode : {ReplayMode::Single, ReplayMode::Packet8, ReplayMode::Stream}) {
        replayRays(scene.accel(), rays, mode, o.threads);  // warm caches
        std::vector<double> rates;
        for (int run = 0; run < o.runs; ++run)
            rates.push_back(replayRays(scene.accel(), rays, mode, o.threads).raysPerSecond());
        const double rate = *std::max_element(rates.begin(), rates.end());
        modes[replayModeName(mode)] = rate;
        modeRuns[replayModeName(mode)] = rates;
        best = std::max(best, rate);
        say(o, "  embree alone, %-7s  %10.4g rays/s\n", replayModeName(mode).c_str(), rate);
    }
    const double efficiency = rendererRaysPerSecond / best;
    say(o, "  efficiency (renderer rays/s / best raw)  %.2f\n", efficiency);
    return {{"recorded_rays", rays.size()},
            {"raw_rays_per_second", modes},
            {"raw_rays_per_second_runs", modeRuns},
            {"best_raw_rays_per_second", best},
            {"efficiency", efficiency}};
}

// Where the frame's wall time goes: Embree (the frame's rays at the best raw
// rate, on as many threads), the sampler (the cost model's ns per dimension ×
// the dimensions the frame drew, spread over the threads) and what remains —
// shading, light sampling, the film and the tiles' bookkeeping.
nlohmann::json timeSplit(const RenderStats& st, double seconds, double bestRaw,
                         const BenchOptions& o) {
    const double embree = double(st.rays + st.shadowRays) / bestRaw;
    const double ns = costModelNanoseconds("independent", o);
    const double sampler = ns * 1e-9 * double(st.dimensions) / o.threadCount();
    const double rest = seconds - embree - sampler;
    say(o,
        "  time split: embree %.3f s (%.0f%%), sampler %.3f s (%.0f%%), shading, lights and "
        "film %.3f s (%.0f%%)\n",
        embree, 100 * embree / seconds, sampler, 100 * sampler / seconds, rest,
        100 * rest / seconds);
    return {{"embree_seconds", embree},
            {"sampler_seconds", sampler},
            {"sampler_ns_per_dimension", ns},
            {"dimensions", st.dimensions},
            {"rest_seconds", rest}};
}

// The scene's frame `runs` times. With scaling, each frame on all threads is
// followed by one on a single thread, and the scaling efficiency is the median
// of the ratios within those pairs: a shared machine's speed drifts between
// runs by more than the few percent measured here.
nlohmann::json benchScene(const std::string& name, RenderScene& scene, const BenchOptions& o) {
    const bool scaling = o.scaling && o.threadCount() > 1;
    RenderStats st;
    std::vector<double> seconds, oneSeconds, scalings;
    for (int run = 0; run < o.runs; ++run) {
        st = render(scene, settingsFor(o, "independent", o.threads)).stats;
        seconds.push_back(st.seconds);
        if (!scaling) continue;
        const RenderStats one = render(scene, settingsFor(o, "independent", 1)).stats;
        oneSeconds.push_back(one.seconds);
        scalings.push_back(one.seconds / (st.seconds * o.threadCount()));
    }
    // Every run traces the same rays: only the time differs.
    const double time = median(seconds);
    const auto [fastest, slowest] = std::minmax_element(seconds.begin(), seconds.end());
    say(o,
        "%-12s %dx%d %3d spp  %8.3f s  %10.4g paths/s  %10.4g rays/s  (%d threads; median of %d "
        "runs, %.3f-%.3f s)\n",
        name.c_str(), o.size, o.size, o.spp, time, double(st.paths) / time, raysPerSecond(st, time),
        o.threadCount(), o.runs, *fastest, *slowest);
    nlohmann::json r = {{"scene", name},
                        {"width", o.size},
                        {"height", o.size},
                        {"spp", o.spp},
                        {"max_depth", kMaxDepth},
                        {"threads", o.threadCount()},
                        {"runs", o.runs},
                        {"seconds", time},
                        {"seconds_runs", seconds},
                        {"paths", st.paths},
                        {"rays", st.rays + st.shadowRays},
                        {"shadow_rays", st.shadowRays},
                        {"paths_per_second", double(st.paths) / time},
                        {"rays_per_second", raysPerSecond(st, time)}};
    r["ray_limit"] = rayLimit(scene, o, raysPerSecond(st, time));
    r["time_split"] =
        timeSplit(st, time, r["ray_limit"]["best_raw_rays_per_second"].get<double>(), o);
    if (scaling) {
        const double efficiency = median(scalings);
        say(o, "  1 thread %.3f s; scaling to %d threads: %.1f%% efficient (median of %d pairs)\n",
            median(oneSeconds), o.threadCount(), 100 * efficiency, o.runs);
        r["scaling"] = {{"seconds_1_thread", median(oneSeconds)},
                        {"efficiency", efficiency},
                        {"efficiency_runs", scalings}};
    }
    return r;
}

// Resident set size now, in bytes (Linux /proc).
double residentBytes() {
    std::ifstream statm("/proc/self/statm");
    double pages = 0, resident = 0;
    statm >> pages >> resident;
    return resident * double(sysconf(_SC_PAGESIZE));
}

// A flat grid of n×n vertices: 2(n−1)² triangles, lit by the environment.
SceneDescription gridScene(int n) {
    SceneDescription d;
    d.name = "grid";
    d.materials.push_back(Material{});
    d.environment = Vec3f(1.0f);
    Mesh m;
    m.positions.reserve(size_t(n) * size_t(n));
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            m.positions.push_back({float(x), 0.01f * float((x * y) % 7), float(y)});
    for (int y = 0; y + 1 < n; ++y)
        for (int x = 0; x + 1 < n; ++x) {
            const uint32_t a = uint32_t(y * n + x), b = a + 1, c = a + uint32_t(n), e = c + 1;
            m.indices.insert(m.indices.end(), {a, b, e, a, e, c});
        }
    d.meshes.push_back(std::move(m));
    d.camera.eye = {float(n) / 2, float(n), float(n) / 2 - 1};
    d.camera.target = {float(n) / 2, 0, float(n) / 2};
    return d;
}

// Memory of a ready-to-render scene per million triangles: description,
// Embree BVH, normals and light tables, measured as the growth of the process.
nlohmann::json memoryPerMillionTriangles(const BenchOptions& o) {
    const double before = residentBytes();
    size_t triangles = 0;
    double after = 0;
    {
        SceneDescription d = gridScene(708);
        triangles = d.meshes[0].triangleCount();
        const RenderScene scene(std::move(d));
        after = residentBytes();
    }
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    const double perMillion = (after - before) / 1048576.0 / (double(triangles) / 1e6);
    say(o, "memory: %.0f MiB per million triangles (%zu-triangle grid); peak RSS %.0f MiB\n",
        perMillion, triangles, double(usage.ru_maxrss) / 1024.0);
    return {{"triangles", triangles},
            {"mib_per_million_triangles", perMillion},
            {"peak_rss_mib", double(usage.ru_maxrss) / 1024.0}};
}

// CPU seconds (user + system, all threads) the process has used so far.
double processCpuSeconds() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    const auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * t.tv_usec; };
    return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

struct TimedFrame {
    double wall = 0, cpu = 0;
    uint64_t dimensions = 0;
};

TimedFrame timedFrame(const RenderScene& scene, const BenchOptions& o, const std::string& name) {
    const double cpuStart = processCpuSeconds();
    const RenderStats st = render(scene, settingsFor(o, name, o.threads)).stats;
    return {st.seconds, processCpuSeconds() - cpuStart, st.dimensions};
}

// Each sampler's frame on the Cornell box next to independent's, and the part
// of it the sampler itself explains: ns per dimension × dimensions drawn.
// A shared machine's speed drifts by more than the differences measured here,
// so frames are timed in CPU seconds (which another process's load moves less
// than wall time) and every sampler's frame is rendered between two
// independent frames, its ratio taken to their mean: a drift that is linear
// over the three frames cancels, and so does any cost of coming first or
// second in a pair. Consecutive sandwiches share their independent frame. A
// round does this for every sampler, `independent` included — its ratio is
// the comparison's noise floor — each round starting one sampler further on;
// the median over rounds is reported.
nlohmann::json samplerShares(const BenchOptions& o) {
    const RenderScene scene(loadScene("cornell-box"));
    const std::vector<SamplerInfo>& infos = samplerInfos();
    const size_t count = infos.size();
    std::vector<std::vector<double>> seconds(count), cpu(count), before(count), after(count);
    std::vector<uint64_t> dimensions(count);
    say(o, "sampler shares, cornell-box %dx%d %d spp, median of %d rounds:\n", o.size, o.size,
        o.spp, o.rounds);
    for (int round = 0; round < o.rounds; ++round) {
        double previous = timedFrame(scene, o, "independent").cpu;
        for (size_t k = 0; k < count; ++k) {
            const size_t i = (k + size_t(round)) % count;
            const TimedFrame frame = timedFrame(scene, o, infos[i].name);
            const double next = timedFrame(scene, o, "independent").cpu;
            seconds[i].push_back(frame.wall);
            cpu[i].push_back(frame.cpu);
            before[i].push_back(previous);
            after[i].push_back(next);
            dimensions[i] = frame.dimensions;
            previous = next;
        }
    }
    nlohmann::json rows = nlohmann::json::array();
    for (size_t i = 0; i < count; ++i) {
        std::vector<double> ratios;
        for (size_t r = 0; r < cpu[i].size(); ++r)
            ratios.push_back(cpu[i][r] / (0.5 * (before[i][r] + after[i][r])));
        const double frame = median(seconds[i]), ratio = median(ratios);
        const double ns = costModelNanoseconds(infos[i].name, o);
        // Dimensions are drawn on every thread at once.
        const double samplerSeconds = ns * 1e-9 * double(dimensions[i]) / o.threadCount();
        rows.push_back({{"sampler", infos[i].name},
                        {"seconds", frame},
                        {"dimensions", dimensions[i]},
                        {"ns_per_dimension", ns},
                        {"sampler_share", samplerSeconds / frame},
                        {"cpu_seconds_runs", cpu[i]},
                        {"independent_before_runs", before[i]},
                        {"independent_after_runs", after[i]},
                        {"vs_independent", ratio - 1}});
        say(o, "  %-12s %8.3f s  %5.1f ns/dim  share %5.1f%%  vs independent %+6.1f%%%s\n",
            infos[i].name.c_str(), frame, ns, 100 * samplerSeconds / frame, 100 * (ratio - 1),
            infos[i].name == "independent" ? "  (noise floor)" : "");
    }
    return rows;
}

void runBench(const BenchOptions& o) {
    // Loaded first: a scene that cannot be loaded stops the bench before
    // anything is measured or printed.
    std::vector<std::unique_ptr<RenderScene>> scenes;
    for (const std::string& name : o.scenes)
        scenes.push_back(std::make_unique<RenderScene>(loadScene(name)));
    nlohmann::json out;
    out["memory"] = memoryPerMillionTriangles(o);
    out["scenes"] = nlohmann::json::array();
    for (size_t i = 0; i < scenes.size(); ++i)
        out["scenes"].push_back(benchScene(o.scenes[i], *scenes[i], o));
    if (o.samplers) out["samplers"] = samplerShares(o);
    if (o.json) std::cout << out.dump(2) << "\n";
}

}  // namespace

void addBenchCommand(CLI::App& app) {
    auto opts = std::make_shared<BenchOptions>();
    CLI::App* cmd = app.add_subcommand(
        "bench", "Measure render throughput (512x512, depth 8, 64 spp, independent)");
    cmd->add_flag("--json", opts->json, "Print the results as JSON");
    cmd->add_flag("--samplers", opts->samplers,
                  "Also time every sampler's Cornell-box frame and its share of it");
    cmd->add_flag("!--no-scaling", opts->scaling, "Skip the single-thread render");
    cmd->add_option("--spp", opts->spp, "Samples per pixel")
        ->capture_default_str()
        ->check(CLI::Range(1, 1 << 20));
    cmd->add_option("--size", opts->size, "Image width and height")
        ->capture_default_str()
        ->check(CLI::Range(1, 16384));
    cmd->add_option("--threads", opts->threads, "Worker threads (0 = all cores)")
        ->capture_default_str()
        ->check(CLI::Range(0, 4096));
    cmd->add_option("--rounds", opts->rounds, "With --samplers: frames per sampler (median)")
        ->capture_default_str()
        ->check(CLI::Range(1, 100));
    cmd->add_option("--runs", opts->runs,
                    "Frames per scene (the median is reported) and replays per query mode (the "
                    "fastest)")
        ->capture_default_str()
        ->check(CLI::Range(1, 100));
    cmd->add_option("--scene", opts->scenes, "Scenes to render")->capture_default_str();
    cmd->callback([opts] { runBench(*opts); });
}

}  // namespace pathlab::cli
