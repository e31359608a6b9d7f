// `pathlab bench`: the renderer's throughput on the built-in scenes at a fixed
// workload (512×512, max depth 8, 64 spp, independent sampler).
#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "render/renderer.h"
#include "scene/loader.h"

namespace pathlab::cli {
namespace {

struct BenchOptions {
    bool json = false;
    int spp = 64;
    int size = 512;
    int threads = 0;
    std::vector<std::string> scenes{"cornell-box", "wolf"};
};

nlohmann::json benchScene(const std::string& name, const BenchOptions& o) {
    const RenderScene scene(loadScene(name));
    RenderSettings s;
    s.samplesPerPixel = o.spp;
    s.resolution = {o.size, o.size};
    s.maxDepth = 8;
    s.threads = o.threads;
    const RenderStats st = render(scene, s).stats;
    const double rays = double(st.rays + st.shadowRays);
    return {{"scene", name},
            {"width", o.size},
            {"height", o.size},
            {"spp", o.spp},
            {"max_depth", 8},
            {"seconds", st.seconds},
            {"paths", st.paths},
            {"rays", st.rays + st.shadowRays},
            {"shadow_rays", st.shadowRays},
            {"paths_per_second", double(st.paths) / st.seconds},
            {"rays_per_second", rays / st.seconds}};
}

void runBench(const BenchOptions& o) {
    nlohmann::json results = nlohmann::json::array();
    for (const std::string& name : o.scenes) {
        nlohmann::json r = benchScene(name, o);
        if (!o.json)
            std::printf("%-12s %dx%d %3d spp  %8.3f s  %10.4g paths/s  %10.4g rays/s\n",
                        name.c_str(), o.size, o.size, o.spp, r["seconds"].get<double>(),
                        r["paths_per_second"].get<double>(), r["rays_per_second"].get<double>());
        results.push_back(std::move(r));
    }
    if (o.json) std::cout << results.dump(2) << "\n";
}

}  // namespace

void addBenchCommand(CLI::App& app) {
    auto opts = std::make_shared<BenchOptions>();
    CLI::App* cmd = app.add_subcommand(
        "bench", "Measure render throughput (512x512, depth 8, 64 spp, independent)");
    cmd->add_flag("--json", opts->json, "Print the results as JSON");
    cmd->add_option("--spp", opts->spp, "Samples per pixel")->capture_default_str()
        ->check(CLI::Range(1, 1 << 20));
    cmd->add_option("--size", opts->size, "Image width and height")->capture_default_str()
        ->check(CLI::Range(1, 16384));
    cmd->add_option("--threads", opts->threads, "Worker threads (0 = all cores)")
        ->capture_default_str()->check(CLI::Range(0, 4096));
    cmd->add_option("--scene", opts->scenes, "Scenes to render")->capture_default_str();
    cmd->callback([opts] { runBench(*opts); });
}

}  // namespace pathlab::cli
