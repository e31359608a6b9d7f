#include "view/points_json.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>

#include "core/error.h"
#include "sampling/pixel_points.h"
#include "sampling/spectrum.h"

namespace pathlab::view {
namespace {

using nlohmann::json;

// The spectrum image shows frequencies up to this (a 129² grid).
constexpr int kMaxImageFrequency = 64;

// "A,B" of two non-negative integers below 10^7, else nullopt.
std::optional<Vec2i> parsePair(const std::string& text) {
    const size_t comma = text.find(',');
    if (comma == std::string::npos) return std::nullopt;
    const auto number = [](const char* first, const char* last) -> std::optional<int> {
        int v = 0;
        const auto [end, ec] = std::from_chars(first, last, v);
        if (first == last || last - first > 7 || ec != std::errc() || end != last || *first == '-')
            return std::nullopt;
        return v;
    };
    const char* s = text.data();
    const auto a = number(s, s + comma), b = number(s + comma + 1, s + text.size());
    if (!a || !b) return std::nullopt;
    return Vec2i{*a, *b};
}

Vec2i requirePair(const std::string& text, const char* name, const char* shape) {
    const std::optional<Vec2i> pair = parsePair(text);
    if (!pair)
        throw InputError(std::string(name) + " must look like " + shape +
                         " with non-negative integers, got '" + text + "'");
    return *pair;
}

int pointCount(const std::string& text, int fallback) {
    if (text.empty()) return std::clamp(fallback, 1, kMaxViewPoints);
    int v = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || end != text.data() + text.size() || v < 1 || v > kMaxViewPoints)
        throw InputError("count must be an integer between 1 and " +
                         std::to_string(kMaxViewPoints) + ", got '" + text + "'");
    return v;
}

// log10 of the central (2·kMaxImageFrequency + 1)² of the periodogram, to
// two decimals: the page maps it to grey (white noise is 0, blue noise's
// dark centre negative).
json spectrumImage(const std::vector<double>& power, int maxFrequency) {
    const int f = std::min(maxFrequency, kMaxImageFrequency), side = 2 * f + 1;
    const int full = 2 * maxFrequency + 1, offset = maxFrequency - f;
    json values = json::array();
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) {
            const double p = power[size_t(y + offset) * full + size_t(x + offset)];
            values.push_back(std::round(std::log10(std::max(p, 1e-6)) * 100) / 100);
        }
    return json{{"max_frequency", f}, {"size", side}, {"log10_power", values}};
}

}  // namespace

json pointsJson(const SessionStatus& status, const PointsQuery& q) {
    if (q.which != "a" && q.which != "b") throw InputError("which must be a or b");
    const std::string& sampler = q.which == "a" ? status.settings.sampler : status.settings.compare;
    if (sampler.empty()) throw InputError("which is b but there is no compare sampler");
    if (q.pixel.empty()) throw InputError("pixel is missing (pixel=X,Y)");
    const Vec2i pixel = requirePair(q.pixel, "pixel", "X,Y");
    if (pixel.x >= status.width || pixel.y >= status.height)
        throw InputError("pixel " + q.pixel + " is outside the " + std::to_string(status.width) +
                         "x" + std::to_string(status.height) + " image");
    const Vec2i dims = requirePair(q.dims, "dims", "I,J");
    if (dims.x == dims.y)
        throw InputError("dims must name two different dimensions, got '" + q.dims + "'");
    const int count = pointCount(q.count, q.which == "a" ? status.spp : status.sppB);

    const PixelPointsRequest request{sampler, count,
                                     dims.x,  dims.y,
                                     pixel,   {status.width, status.height},
                                     count,   status.settings.seed};
    const std::vector<Vec2f> points = pixelPoints(request);
    const int frequency = spectrumFrequency(points.size());
    const std::vector<double> power = powerSpectrum(points, frequency);
    json xy = json::array();
    for (const Vec2f& p : points) xy.push_back({p.x, p.y});
    return json{
        {"sampler", sampler},
        {"which", q.which},
        {"pixel", {pixel.x, pixel.y}},
        {"dims", {dims.x, dims.y}},
        {"count", count},
        {"seed", status.settings.seed},
        {"points", xy},
        {"spectrum", {{"max_frequency", frequency}, {"radial", radialAverage(power, frequency)}}},
        {"spectrum_image", spectrumImage(power, frequency)}};
}

}  // namespace pathlab::view
