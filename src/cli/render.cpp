// `pathlab render`: one image of a scene with a chosen sampler.
#include <cstdio>
#include <memory>
#include <regex>

#include "cli/commands.h"
#include "cli/options.h"
#include "core/error.h"
#include "core/image.h"
#include "render/renderer.h"
#include "scene/loader.h"

namespace pathlab::cli {
namespace {

// The renderer's limits (validateRenderSettings), checked here on the wide values.
constexpr int64_t kMaxSamplesPerPixel = int64_t(1) << 24;
constexpr int64_t kMaxDepth = 1024;

struct RenderOptions {
    std::string scene, output, size;
    RenderSettings settings;
    std::string seed = std::to_string(settings.seed);  // parseSeed
    // Read wide, so an absurd count is refused by range, not by a conversion.
    int64_t spp = 16, maxDepth = 8, rouletteDepth = kDefaultRouletteDepth;
    bool noRoulette = false;
    bool solidAngleLights = false;
    bool lenient = false;
    // Given on the command line? Otherwise a scene file's own choice (pbrt-v4's
    // Sampler and Integrator directives) applies.
    const CLI::Option *samplerGiven = nullptr, *sppGiven = nullptr, *seedGiven = nullptr,
                      *depthGiven = nullptr;
};

// The scene file's sampler, spp, seed and depth where the command line is silent.
void applySceneDefaults(RenderOptions& o, const RenderDefaults& d) {
    if (!d.sampler.empty() && o.samplerGiven->count() == 0) o.settings.sampler = d.sampler;
    if (d.samplesPerPixel > 0 && o.sppGiven->count() == 0) o.spp = d.samplesPerPixel;
    if (d.hasSeed && o.seedGiven->count() == 0) o.seed = std::to_string(d.seed);
    if (d.maxDepth >= 0 && o.depthGiven->count() == 0) o.maxDepth = d.maxDepth;
}

// A decimal count, saturated: "99999999999999999999" is simply very large.
int64_t parseCount(const std::string& digits) {
    int64_t v = 0;
    for (char c : digits) v = v > (INT64_MAX - 9) / 10 ? INT64_MAX : v * 10 + (c - '0');
    return v;
}

Vec2i parseSize(const std::string& text) {
    static const std::regex pattern(R"((\d+)x(\d+))");
    std::smatch m;
    if (!std::regex_match(text, m, pattern))
        throw InputError("--size must look like WIDTHxHEIGHT (e.g. 512x512), got '" + text + "'");
    const int64_t w = parseCount(m[1]), h = parseCount(m[2]);
    if (w < 1 || h < 1 || w > kMaxImageSide || h > kMaxImageSide)
        throw InputError("--size must be between 1x1 and " + std::to_string(kMaxImageSide) + "x" +
                         std::to_string(kMaxImageSide) + ", got '" + text + "'");
    return {int(w), int(h)};
}

// Out-of-range values are refused here, before they are narrowed.
int checkedInt(int64_t v, int64_t lo, int64_t hi, const std::string& what) {
    if (v < lo || v > hi)
        throw InputError(what + " must be between " + std::to_string(lo) + " and " +
                         std::to_string(hi) + ", got " + std::to_string(v));
    return int(v);
}

// The settings from the options' values, validated.
void settle(RenderOptions& o) {
    RenderSettings& s = o.settings;
    s.russianRoulette = !o.noRoulette;
    s.samplesPerPixel = checkedInt(o.spp, 1, kMaxSamplesPerPixel, "--spp");
    s.maxDepth = checkedInt(o.maxDepth, 0, kMaxDepth, "--max-depth");
    s.rouletteDepth = checkedInt(o.rouletteDepth, 0, kMaxDepth, "--roulette-depth");
    s.seed = parseSeed(o.seed);
    if (!o.size.empty()) s.resolution = parseSize(o.size);
    validateRenderSettings(s);
}

void runRender(RenderOptions& o) {
    settle(o);                // the command line's own mistakes first,
    checkWritable(o.output);  // then the output's, before loading and rendering
    SceneDescription desc = loadScene(o.scene, {o.lenient});
    applySceneDefaults(o, desc.defaults);
    settle(o);
    RenderSettings& s = o.settings;
    s.progress = true;
    const RenderScene scene(std::move(desc),
                            o.solidAngleLights ? LightSampling::SolidAngle : LightSampling::Area);
    const RenderOutput out = render(scene, s);
    writeImage(o.output, out.image);
    const RenderStats& st = out.stats;
    const double rays = double(st.rays + st.shadowRays);
    std::fprintf(stderr, "rendered %s (%dx%d, %d spp, %s) in %.3f s: %.3g paths/s, %.3g rays/s%s\n",
                 o.output.c_str(), out.image.width, out.image.height, s.samplesPerPixel,
                 s.sampler.c_str(), st.seconds, double(st.paths) / st.seconds, rays / st.seconds,
                 st.nonFinite
                     ? (", " + std::to_string(st.nonFinite) + " NaN/Inf samples discarded").c_str()
                     : "");
}

}  // namespace

void addRenderCommand(CLI::App& app) {
    auto opts = std::make_shared<RenderOptions>();
    CLI::App* cmd = app.add_subcommand("render", "Render one image of a scene");
    cmd->add_option("--scene", opts->scene, "cornell-box, wolf, or a scene file (.json/.obj/.pbrt)")
        ->required();
    opts->samplerGiven = cmd->add_option("--sampler", opts->settings.sampler,
                                         "Sampler name (see `pathlab samplers`; default: the "
                                         "scene file's, else independent)")
                             ->capture_default_str();
    opts->sppGiven = cmd->add_option("--spp", opts->spp,
                                     "Samples per pixel (default: the scene "
                                     "file's, else 16)")
                         ->capture_default_str();
    opts->seedGiven = cmd->add_option("--seed", opts->seed, "Seed of the sampler's randomisation")
                          ->capture_default_str();
    cmd->add_option("--size", opts->size, "Image size WIDTHxHEIGHT (default: the scene's)");
    opts->depthGiven = cmd->add_option("--max-depth", opts->maxDepth,
                                       "Maximum path depth (1 = direct lighting only; default: "
                                       "the scene file's, else 8)")
                           ->capture_default_str();
    cmd->add_flag("--lenient", opts->lenient,
                  "pbrt-v4 files: substitute unsupported features (with a warning each) "
                  "instead of stopping");
    cmd->add_flag("--no-russian-roulette", opts->noRoulette, "Disable Russian roulette");
    cmd->add_option("--roulette-depth", opts->rouletteDepth,
                    "Bounces before Russian roulette may end a path (pbrt-v4: 2, Mitsuba 3: 4)")
        ->capture_default_str();
    cmd->add_flag("--solid-angle-lights", opts->solidAngleLights,
                  "Sample rectangular lights by solid angle instead of by area");
    cmd->add_option("--threads", opts->settings.threads, "Worker threads (0 = all cores)")
        ->capture_default_str();
    cmd->add_option("-o,--output", opts->output, "Output image (.exr linear, .png sRGB, .pfm)")
        ->required();
    cmd->callback([opts] { runRender(*opts); });
}

}  // namespace pathlab::cli
