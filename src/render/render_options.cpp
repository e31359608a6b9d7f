#include "render/render_options.h"

#include <regex>

#include "core/error.h"
#include "core/image.h"
#include "core/seed.h"

namespace pathlab {
namespace {

// The renderer's limits (validateRenderSettings), checked here on the wide values.
constexpr int64_t kMaxSamplesPerPixel = int64_t(1) << 24;
constexpr int64_t kMaxDepth = 1024;

// A decimal count, saturated: "99999999999999999999" is simply very large.
int64_t parseCount(const std::string& digits) {
    int64_t v = 0;
    for (char c : digits) v = v > (INT64_MAX - 9) / 10 ? INT64_MAX : v * 10 + (c - '0');
    return v;
}

// Out-of-range values are refused here, before they are narrowed.
int checkedInt(int64_t v, int64_t lo, int64_t hi, const std::string& what) {
    if (v < lo || v > hi)
        throw InputError(what + " must be between " + std::to_string(lo) + " and " +
                         std::to_string(hi) + ", got " + std::to_string(v));
    return int(v);
}

}  // namespace

const RenderOptionNames& cliRenderOptionNames() {
    static const RenderOptionNames names{"--spp", "--max-depth", "--roulette-depth", "--seed",
                                         "--size"};
    return names;
}

Vec2i parseImageSize(const std::string& text, const std::string& option) {
    static const std::regex pattern(R"((\d+)x(\d+))");
    std::smatch m;
    if (!std::regex_match(text, m, pattern))
        throw InputError(option + " must look like WIDTHxHEIGHT (e.g. 512x512), got '" + text +
                         "'");
    const int64_t w = parseCount(m[1]), h = parseCount(m[2]);
    if (w < 1 || h < 1 || w > kMaxImageSide || h > kMaxImageSide)
        throw InputError(option + " must be between 1x1 and " + std::to_string(kMaxImageSide) +
                         "x" + std::to_string(kMaxImageSide) + ", got '" + text + "'");
    return {int(w), int(h)};
}

void applySceneDefaults(const RenderDefaults& d, RenderOptionValues& v, RenderSettings& s) {
    if (!d.sampler.empty() && !v.samplerGiven) s.sampler = d.sampler;
    if (d.samplesPerPixel > 0 && !v.sppGiven) v.spp = d.samplesPerPixel;
    if (d.hasSeed && !v.seedGiven) v.seed = std::to_string(d.seed);
    if (d.maxDepth >= 0 && !v.depthGiven) v.maxDepth = d.maxDepth;
}

void settleRenderSettings(const RenderOptionValues& v, const RenderOptionNames& names,
                          RenderSettings& s) {
    s.russianRoulette = v.russianRoulette;
    s.samplesPerPixel = checkedInt(v.spp, 1, kMaxSamplesPerPixel, names.spp);
    s.maxDepth = checkedInt(v.maxDepth, 0, kMaxDepth, names.maxDepth);
    s.rouletteDepth = checkedInt(v.rouletteDepth, 0, kMaxDepth, names.rouletteDepth);
    s.seed = parseSeed(v.seed, names.seed);
    if (!v.size.empty()) s.resolution = parseImageSize(v.size, names.size);
    validateRenderSettings(s);
}

}  // namespace pathlab
