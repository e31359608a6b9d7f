#include "study/suite_presets.h"

#include <filesystem>

#include "core/error.h"
#include "sampling/registry.h"

namespace pathlab {
namespace {
namespace fs = std::filesystem;

std::vector<int> powersOfTwo(int largest) {
    std::vector<int> out;
    for (int n = 1; n <= largest; n *= 2) out.push_back(n);
    return out;
}

// A scene file of the repository, by its path under scenes/.
StudyScene ownScene(const std::string& relative, const std::string& difficulty) {
    const fs::path path = fs::path(PATHLAB_SOURCE_DIR) / "scenes" / relative;
    return {path.stem().string(), path.lexically_normal().string(), {}, difficulty};
}

StudyScene builtinScene(const std::string& name, const std::string& difficulty) {
    return {name, name, {}, difficulty};
}

}  // namespace

const std::vector<PublicScene>& publicPbrtScenes() {
    // ../shared/scenes/pbrt-v4/README.md's first targets, smallest first.
    static const std::vector<PublicScene> scenes{
        {"killeroos/killeroo-simple.pbrt", kGlossy},
        {"killeroos/killeroo-gold.pbrt", kGlossy},
        {"killeroos/killeroo-coated-gold.pbrt", kGlossy},
        {"lte-orb/lte-orb-simple-ball.pbrt", kEnvironment},
        {"lte-orb/lte-orb-rough-glass.pbrt", kRefractive},
        {"lte-orb/lte-orb-silver.pbrt", kGlossy},
        {"ganesha/ganesha.pbrt", kEnvironment},
    };
    return scenes;
}

// One scene per difficulty at least: the two of the presentation, glossy
// transport twice (smooth and rough conductors with glass, anisotropic
// metals), rough refraction, an environment map whose sun holds most of its
// power, a thin lens, 200 small lights, and image and procedural textures.
StudySpec suitePreset(std::ostream& log) {
    StudySpec s;
    s.name = "suite";
    const std::vector<StudyScene> scenes = {builtinScene("cornell-box", kDiffuseIndirect),
                                            builtinScene("wolf", kDiffuseIndirect),
                                            ownScene("glass-and-metal.json", kGlossy),
                                            ownScene("pbrt/anisotropic-metal.pbrt", kGlossy),
                                            ownScene("pbrt/rough-glass.pbrt", kRefractive),
                                            ownScene("pbrt/envmap-sun.pbrt", kEnvironment),
                                            ownScene("pbrt/depth-of-field.pbrt", kDepthOfField),
                                            ownScene("pbrt/many-lights.pbrt", kManyLights),
                                            ownScene("pbrt/textured.pbrt", kTextured)};
    // A scene file missing from this checkout leaves the suite, said once:
    // the verdict covers the scenes it has rather than none.
    for (const StudyScene& scene : scenes) {
        std::error_code ec;
        if (scene.source == scene.name || fs::is_regular_file(scene.source, ec))
            s.scenes.push_back(scene);
        else
            log << "suite: scene file '" << scene.source
                << "' not found; the suite runs without it\n";
    }
    for (const SamplerInfo& info : samplerInfos()) s.samplers.push_back(info.name);
    s.spp = powersOfTwo(1024);
    s.seeds = 3;
    s.resolution = {256, 256};
    // 16× the largest cell's spp: independent sampling's error at 1024 spp
    // stays about 16 times the reference's own (the noise floor).
    s.reference.spp = 16384;
    s.timeBudgetSeconds = 1.0;
    return s;
}

StudySpec quickSuitePreset() {
    StudySpec s;
    s.name = "quick-suite";
    s.scenes = {builtinScene("cornell-box", kDiffuseIndirect),
                ownScene("pbrt/envmap-sun.pbrt", kEnvironment),
                ownScene("pbrt/rough-glass.pbrt", kRefractive),
                ownScene("pbrt/depth-of-field.pbrt", kDepthOfField)};
    s.samplers = {"independent", "halton-owen", "sobol-owen", "zsobol"};
    s.spp = powersOfTwo(16);
    s.seeds = 3;
    s.resolution = {64, 64};
    s.reference.spp = 256;
    s.timeBudgetSeconds = 0.02;
    return s;
}

bool presetTakesPublicScenes(const std::string& name) {
    return name == "suite" || name == "quick-suite";
}

void addPublicScenes(StudySpec& spec, const std::string& dir, std::ostream& log) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw InputError("--scenes-dir '" + dir + "' is not a directory");
    std::string found, missing;
    for (const PublicScene& p : publicPbrtScenes()) {
        const fs::path file = fs::absolute(fs::path(dir) / p.path).lexically_normal();
        std::string& list = fs::is_regular_file(file, ec) ? found : missing;
        list += (list.empty() ? "" : ", ") + p.path;
        if (&list == &missing) continue;
        spec.scenes.push_back({file.stem().string(), file.string(),
                               "--scenes-dir '" + dir + "': " + p.path, p.difficulty});
    }
    log << "suite: public pbrt-v4 scenes found in '" << dir
        << "': " << (found.empty() ? "none" : found) << "\n"
        << "suite: not found there: " << (missing.empty() ? "none" : missing) << "\n";
}

}  // namespace pathlab
