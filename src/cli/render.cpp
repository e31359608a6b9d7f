// `pathlab render`: one image of a scene with a chosen sampler.
#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "core/error.h"
#include "core/image.h"
#include "render/render_options.h"
#include "render/renderer.h"
#include "scene/light_selection.h"
#include "scene/loader.h"

namespace pathlab::cli {
namespace {

struct RenderOptions {
    std::string scene, output;
    RenderSettings settings;
    RenderOptionValues values;
    bool noRoulette = false;
    bool solidAngleLights = false;
    bool sphereLightsByArea = false;
    std::string lightSampler;  // "": the scene file's choice, else power
    std::string wavelengths = "visible";
    bool lenient = false;
    // Given on the command line? Otherwise a scene file's own choice (pbrt-v4's
    // Sampler and Integrator directives) applies.
    const CLI::Option *samplerGiven = nullptr, *sppGiven = nullptr, *seedGiven = nullptr,
                      *depthGiven = nullptr;
};

// The settings from the options' values, validated.
void settle(RenderOptions& o) {
    o.values.russianRoulette = !o.noRoulette;
    // Before the whole is validated, which refuses hero without --spectral.
    o.settings.wavelengths = spectral::parseWavelengthSampling(o.wavelengths, "--wavelengths");
    settleRenderSettings(o.values, cliRenderOptionNames(), o.settings);
    parseLightSelection(o.lightSampler, "--light-sampler");
}

void runRender(RenderOptions& o) {
    settle(o);                // the command line's own mistakes first,
    checkWritable(o.output);  // then the output's, before loading and rendering
    SceneDescription desc = loadScene(o.scene, {o.lenient});
    RenderOptionValues& v = o.values;
    v.samplerGiven = o.samplerGiven->count() > 0, v.sppGiven = o.sppGiven->count() > 0;
    v.seedGiven = o.seedGiven->count() > 0, v.depthGiven = o.depthGiven->count() > 0;
    applySceneDefaults(desc.defaults, v, o.settings);
    settle(o);
    if (!o.lightSampler.empty()) desc.defaults.lightSampler = o.lightSampler;
    RenderSettings& s = o.settings;
    s.progress = true;
    const RenderScene scene(std::move(desc), o.solidAngleLights     ? LightSampling::SolidAngle
                                             : o.sphereLightsByArea ? LightSampling::UniformArea
                                                                    : LightSampling::Area);
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
    opts->sppGiven = cmd->add_option("--spp", opts->values.spp,
                                     "Samples per pixel (default: the scene "
                                     "file's, else 16)")
                         ->capture_default_str();
    opts->seedGiven =
        cmd->add_option("--seed", opts->values.seed, "Seed of the sampler's randomisation")
            ->capture_default_str();
    cmd->add_option("--size", opts->values.size, "Image size WIDTHxHEIGHT (default: the scene's)");
    opts->depthGiven = cmd->add_option("--max-depth", opts->values.maxDepth,
                                       "Maximum path depth (1 = direct lighting only; default: "
                                       "the scene file's, else 8)")
                           ->capture_default_str();
    cmd->add_flag("--lenient", opts->lenient,
                  "pbrt-v4 files: substitute unsupported features (with a warning each) "
                  "instead of stopping");
    cmd->add_flag("--no-russian-roulette", opts->noRoulette, "Disable Russian roulette");
    cmd->add_option("--roulette-depth", opts->values.rouletteDepth,
                    "Bounces before Russian roulette may end a path (pbrt-v4: 2, Mitsuba 3: 4)")
        ->capture_default_str();
    CLI::Option* solidAngle =
        cmd->add_flag("--solid-angle-lights", opts->solidAngleLights,
                      "Sample rectangular lights by solid angle instead of by area");
    cmd->add_flag("--sphere-lights-by-area", opts->sphereLightsByArea,
                  "Sample emitting spheres uniformly by area instead of by the cone they "
                  "subtend (to compare)")
        ->excludes(solidAngle);
    cmd->add_option("--light-sampler", opts->lightSampler,
                    "How a light is chosen for next-event estimation: uniform, power or bvh "
                    "(default: the scene file's, else power)");
    cmd->add_flag("--spectral", opts->settings.spectral,
                  "Carry four sampled wavelengths per path instead of RGB (pbrt-v4's spectral "
                  "rendering; the image is linear sRGB either way)");
    cmd->add_option("--wavelengths", opts->wavelengths,
                    "Spectral mode's wavelength sampling: visible (pbrt-v4's visible density) "
                    "or hero (Wilkie et al. 2014, uniform hero and equally spaced rotations)")
        ->capture_default_str();
    cmd->add_option("--threads", opts->settings.threads, "Worker threads (0 = all cores)")
        ->capture_default_str();
    cmd->add_option("-o,--output", opts->output, "Output image (.exr linear, .png sRGB, .pfm)")
        ->required();
    cmd->callback([opts] { runRender(*opts); });
}

}  // namespace pathlab::cli
