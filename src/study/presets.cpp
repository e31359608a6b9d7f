#include "study/presets.h"

#include <iostream>

#include "core/error.h"
#include "study/suite_presets.h"

namespace pathlab {
namespace {

std::vector<int> powersOfTwo(int largest) {
    std::vector<int> out;
    for (int n = 1; n <= largest; n *= 2) out.push_back(n);
    return out;
}

// The presentation's comparison: its five strategies plus the three that
// frame them (pure random, and pbrt-v4's two best), on its two scenes, at
// 1…256 spp, 3 seeds, 256×256, against 4096-spp references. It must finish
// within ten minutes on two cores, references included: 8 min 45 s measured
// with an empty cache (docs/study.md). docs/study-spec.toml is the same study.
StudySpec seedPreset() {
    StudySpec s;
    s.name = "seed";
    s.scenes = {{"cornell-box", "cornell-box"}, {"wolf", "wolf"}};
    s.samplers = {"standard",   "halton",      "halton-rd",  "halton-owen",
                  "blue-noise", "independent", "sobol-owen", "zsobol"};
    s.spp = powersOfTwo(256);
    s.seeds = 3;
    s.resolution = {256, 256};
    s.reference.spp = 4096;
    s.timeBudgetSeconds = 1.0;
    return s;
}

// Small enough for a test: one scene, four samplers, 64×64.
StudySpec quickPreset() {
    StudySpec s;
    s.name = "quick";
    s.scenes = {{"cornell-box", "cornell-box"}};
    s.samplers = {"standard", "halton-rd", "blue-noise", "independent"};
    s.spp = powersOfTwo(16);
    s.seeds = 2;
    s.resolution = {64, 64};
    s.reference.spp = 256;
    s.timeBudgetSeconds = 0.02;
    return s;
}

StudySpec fullPreset() {
    StudySpec s;
    s.name = "full";
    s.scenes = {{"cornell-box", "cornell-box"}, {"wolf", "wolf"}};
    s.samplers = {
        "standard",    "halton",     "halton-rd",       "halton-owen", "blue-noise",
        "independent", "stratified", "sobol",           "sobol-xor",   "sobol-global-owen",
        "sobol-owen",  "zsobol",     "sobol-bluenoise", "pmj02",       "cascaded-sobol"};
    s.spp = powersOfTwo(4096);
    s.seeds = 8;
    s.resolution = {512, 512};
    s.reference.spp = 65536;
    s.timeBudgetSeconds = 10.0;
    return s;
}

}  // namespace

std::vector<std::string> presetNames() {
    return {"seed", "quick", "full", "suite", "quick-suite"};
}

StudySpec presetSpec(const std::string& name) {
    if (name == "seed") return seedPreset();
    if (name == "quick") return quickPreset();
    if (name == "full") return fullPreset();
    if (name == "suite") return suitePreset(std::cerr);
    if (name == "quick-suite") return quickSuitePreset();
    throw InputError("unknown preset '" + name +
                     "' (known: seed, quick, full, suite, quick-suite)");
}

}  // namespace pathlab
