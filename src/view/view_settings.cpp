#include "view/view_settings.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/image.h"
#include "core/seed.h"
#include "sampling/registry.h"
#include "scene/light_selection.h"

namespace pathlab::view {
namespace {

using nlohmann::json;

std::string stringOf(const json& value, const std::string& key) {
    if (!value.is_string()) throw InputError("setting '" + key + "' must be a string");
    return value.get<std::string>();
}

int64_t integerOf(const json& value, const std::string& key) {
    if (!value.is_number_integer())
        throw InputError("setting '" + key + "' must be an integer, got " + value.dump());
    return value.get<int64_t>();
}

bool boolOf(const json& value, const std::string& key) {
    if (!value.is_boolean()) throw InputError("setting '" + key + "' must be true or false");
    return value.get<bool>();
}

int inRange(int64_t v, int64_t lo, int64_t hi, const std::string& key) {
    if (v < lo || v > hi)
        throw InputError("setting '" + key + "' must be between " + std::to_string(lo) + " and " +
                         std::to_string(hi) + ", got " + std::to_string(v));
    return int(v);
}

void applyOne(ViewSettings& s, const std::string& key, const json& v) {
    if (key == "scene") {
        s.scene = stringOf(v, key);
    } else if (key == "sampler") {
        s.sampler = stringOf(v, key);
    } else if (key == "compare") {
        s.compare = v.is_null() ? "" : stringOf(v, key);
    } else if (key == "seed") {
        // JSON numbers lose integers above 2^53: large seeds come as strings.
        s.seed = v.is_string() ? parseSeed(v.get<std::string>(), "setting 'seed'")
                               : uint64_t(inRange(integerOf(v, key), 0, INT32_MAX, key));
    } else if (key == "width") {
        s.size.x = inRange(integerOf(v, key), 1, kMaxImageSide, key);
    } else if (key == "height") {
        s.size.y = inRange(integerOf(v, key), 1, kMaxImageSide, key);
    } else if (key == "max_depth") {
        s.maxDepth = inRange(integerOf(v, key), 0, 1024, key);
    } else if (key == "russian_roulette") {
        s.russianRoulette = boolOf(v, key);
    } else if (key == "light_sampler") {
        s.lightSampler = v.is_null() ? "" : stringOf(v, key);
    } else if (key == "spectral") {
        s.spectral = boolOf(v, key);
    } else if (key == "max_spp") {
        s.maxSpp = inRange(integerOf(v, key), 1, 1 << 24, key);
    } else if (key == "equal") {
        s.equal = parseEqualBy(stringOf(v, key), "setting 'equal'");
    } else if (key == "exposure") {
        if (!v.is_number() || !std::isfinite(v.get<double>()) || std::abs(v.get<double>()) > 64)
            throw InputError("setting 'exposure' must be a number of stops from -64 to 64");
        s.exposure = v.get<float>();
    } else if (key == "tone_map") {
        s.toneMap = parseToneMap(stringOf(v, key));
    } else if (key == "paused") {
        s.paused = boolOf(v, key);
    } else {
        throw InputError("unknown setting '" + key + "'");
    }
}

}  // namespace

void validateViewSettings(const ViewSettings& s) {
    samplerInfo(s.sampler);  // throws InputError for an unknown name
    if (!s.compare.empty()) samplerInfo(s.compare);
    if (!s.lightSampler.empty()) parseLightSelection(s.lightSampler, "setting 'light_sampler'");
    if ((s.size.x == 0) != (s.size.y == 0))
        throw InputError("image size needs both a width and a height");
}

ViewSettings applySettingsJson(ViewSettings settings, const json& changes) {
    if (!changes.is_object()) throw InputError("settings must be a JSON object");
    for (const auto& [key, value] : changes.items()) applyOne(settings, key, value);
    validateViewSettings(settings);
    return settings;
}

const char* toneMapName(ToneMap toneMap) {
    switch (toneMap) {
        case ToneMap::Linear:
            return "linear";
        case ToneMap::Srgb:
            return "srgb";
        case ToneMap::Aces:
            return "aces";
    }
    return "srgb";
}

ToneMap parseToneMap(const std::string& name) {
    for (ToneMap t : {ToneMap::Linear, ToneMap::Srgb, ToneMap::Aces})
        if (name == toneMapName(t)) return t;
    throw InputError("unknown tone map '" + name + "' (linear, srgb, aces)");
}

const char* equalByName(EqualBy equal) {
    return equal == EqualBy::Time ? "time" : "spp";
}

EqualBy parseEqualBy(const std::string& name, const std::string& what) {
    for (EqualBy e : {EqualBy::Spp, EqualBy::Time})
        if (name == equalByName(e)) return e;
    throw InputError(what + " must be spp or time, got '" + name + "'");
}

}  // namespace pathlab::view
