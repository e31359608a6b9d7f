// A render's options as a user types them — the `pathlab render` flags or the
// Python module's keywords — checked and turned into RenderSettings. Both
// front ends call this, so both refuse the same values with the same message,
// each naming its own spelling of the option.
#pragma once

#include <cstdint>
#include <string>

#include "render/renderer.h"
#include "scene/scene.h"

namespace pathlab {

// How the front end spells each option in its messages.
struct RenderOptionNames {
    std::string spp, maxDepth, rouletteDepth, seed, size;
};
// `pathlab render`'s flags.
const RenderOptionNames& cliRenderOptionNames();

struct RenderOptionValues {
    // Read wide, so an absurd count is refused by range, not by a conversion.
    int64_t spp = 16, maxDepth = 8, rouletteDepth = kDefaultRouletteDepth;
    std::string seed = "0";  // parseSeed
    std::string size;        // "WIDTHxHEIGHT"; empty: the scene's
    bool russianRoulette = true;
    // Which of sampler, spp, seed and max depth the user gave: the others
    // take the scene file's choice (pbrt-v4's Sampler and Integrator).
    bool samplerGiven = false, sppGiven = false, seedGiven = false, depthGiven = false;
};

// The scene file's sampler, spp, seed and depth where the user was silent.
void applySceneDefaults(const RenderDefaults& defaults, RenderOptionValues& values,
                        RenderSettings& settings);

// Checks the values, puts them into `settings` (whose sampler and threads are
// already set) and validates the whole; throws InputError naming the option.
void settleRenderSettings(const RenderOptionValues& values, const RenderOptionNames& names,
                          RenderSettings& settings);

// "WIDTHxHEIGHT", each from 1 to kMaxImageSide; throws InputError naming `option`.
Vec2i parseImageSize(const std::string& text, const std::string& option);

}  // namespace pathlab
