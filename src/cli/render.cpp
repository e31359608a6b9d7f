// `pathlab render`: one image of a scene with a chosen sampler.
#include <cstdio>
#include <memory>
#include <regex>

#include "cli/commands.h"
#include "core/error.h"
#include "core/image.h"
#include "render/renderer.h"
#include "scene/loader.h"

namespace pathlab::cli {
namespace {

struct RenderOptions {
    std::string scene, output, size;
    RenderSettings settings;
    bool noRoulette = false;
};

Vec2i parseSize(const std::string& text) {
    static const std::regex pattern(R"((\d{1,6})x(\d{1,6}))");
    std::smatch m;
    if (!std::regex_match(text, m, pattern))
        throw InputError("--size must look like WIDTHxHEIGHT (e.g. 512x512), got '" + text + "'");
    return {std::stoi(m[1]), std::stoi(m[2])};
}

void runRender(RenderOptions& o) {
    RenderSettings& s = o.settings;
    s.russianRoulette = !o.noRoulette;
    if (!o.size.empty()) {
        s.resolution = parseSize(o.size);
        if (s.resolution.x == 0 || s.resolution.y == 0)
            throw InputError("--size must be at least 1x1, got '" + o.size + "'");
    }
    validateRenderSettings(s);
    checkWritable(o.output);  // fail before rendering, not after
    s.progress = true;
    const RenderScene scene(loadScene(o.scene));
    const RenderOutput out = render(scene, s);
    writeImage(o.output, out.image);
    const RenderStats& st = out.stats;
    const double rays = double(st.rays + st.shadowRays);
    std::fprintf(stderr,
                 "rendered %s (%dx%d, %d spp, %s) in %.3f s: %.3g paths/s, %.3g rays/s%s\n",
                 o.output.c_str(), out.image.width, out.image.height, s.samplesPerPixel,
                 s.sampler.c_str(), st.seconds, double(st.paths) / st.seconds, rays / st.seconds,
                 st.nonFinite ? (", " + std::to_string(st.nonFinite) +
                                 " NaN/Inf samples discarded")
                                    .c_str()
                              : "");
}

}  // namespace

void addRenderCommand(CLI::App& app) {
    auto opts = std::make_shared<RenderOptions>();
    CLI::App* cmd = app.add_subcommand("render", "Render one image of a scene");
    cmd->add_option("--scene", opts->scene, "cornell-box, wolf, or a scene file (.json/.obj)")
        ->required();
    cmd->add_option("--sampler", opts->settings.sampler, "Sampler name (see `pathlab samplers`)")
        ->capture_default_str();
    cmd->add_option("--spp", opts->settings.samplesPerPixel, "Samples per pixel")
        ->capture_default_str();
    cmd->add_option("--seed", opts->settings.seed, "Seed of the sampler's randomisation")
        ->capture_default_str();
    cmd->add_option("--size", opts->size, "Image size WIDTHxHEIGHT (default: the scene's)");
    cmd->add_option("--max-depth", opts->settings.maxDepth,
                    "Maximum path depth (1 = direct lighting only)")
        ->capture_default_str();
    cmd->add_flag("--no-russian-roulette", opts->noRoulette, "Disable Russian roulette");
    cmd->add_option("--threads", opts->settings.threads, "Worker threads (0 = all cores)")
        ->capture_default_str();
    cmd->add_option("-o,--output", opts->output, "Output image (.exr linear, .png sRGB, .pfm)")
        ->required();
    cmd->callback([opts] { runRender(*opts); });
}

}  // namespace pathlab::cli
