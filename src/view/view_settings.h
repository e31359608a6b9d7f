// What `pathlab view` renders and how it shows it. The render settings
// restart accumulation when they change; the display settings (exposure,
// tone map) only change how the same sums are shown.
#pragma once

#include <cstdint>
#include <nlohmann/json_fwd.hpp>
#include <string>

#include "core/math.h"
#include "view/pass_scheduler.h"

namespace pathlab::view {

enum class ToneMap { Linear, Srgb, Aces };

struct ViewSettings {
    // The render: changing any of these starts accumulation over.
    std::string scene = "cornell-box";  // a built-in name or a file path
    std::string sampler = "independent";
    std::string compare;  // a second sampler rendered at equal spp; empty: none
    uint64_t seed = 0;
    Vec2i size{0, 0};  // 0×0: the scene's own
    int maxDepth = 8;
    bool russianRoulette = true;
    std::string lightSampler;      // uniform, power or bvh; empty: the scene's own
    bool spectral = false;         // four sampled wavelengths per path instead of RGB
    int maxSpp = 65536;            // accumulation stops there
    EqualBy equal = EqualBy::Spp;  // A and B at equal spp, or equal render time
    // The display.
    float exposure = 0;  // stops: pixels are multiplied by 2^exposure
    ToneMap toneMap = ToneMap::Srgb;
    bool paused = false;

    bool sameRender(const ViewSettings& o) const {
        return scene == o.scene && sampler == o.sampler && compare == o.compare && seed == o.seed &&
               size.x == o.size.x && size.y == o.size.y && maxDepth == o.maxDepth &&
               russianRoulette == o.russianRoulette && lightSampler == o.lightSampler &&
               spectral == o.spectral && maxSpp == o.maxSpp && equal == o.equal;
    }
};

// Checks everything but the scene (which only loading can check); throws
// InputError naming the setting.
void validateViewSettings(const ViewSettings& settings);

// `settings` with the members a JSON object names replaced ("scene",
// "sampler", "compare", "seed", "width", "height", "max_depth",
// "russian_roulette", "light_sampler", "spectral", "max_spp", "equal",
// "exposure", "tone_map", "paused"), then
// validated. Throws InputError naming an unknown key, a value of the wrong
// type or one out of range.
ViewSettings applySettingsJson(ViewSettings settings, const nlohmann::json& changes);

// The JSON spellings of settings.
const char* toneMapName(ToneMap toneMap);
ToneMap parseToneMap(const std::string& name);  // throws InputError
const char* equalByName(EqualBy equal);         // "spp", "time"
// Throws InputError naming `what` (the option or setting).
EqualBy parseEqualBy(const std::string& name, const std::string& what);

}  // namespace pathlab::view
