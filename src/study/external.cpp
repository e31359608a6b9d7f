#include "study/external.h"

#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <tuple>

#include "core/error.h"

namespace pathlab {
namespace {
namespace fs = std::filesystem;

constexpr const char* kPlaceholders[] = {"{sampler}", "{spp}", "{seed}"};

size_t occurrences(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
    return n;
}

// The pattern as a regular expression over a file's whole path: literal text
// escaped, {sampler} a path component's characters, {spp} and {seed} digits.
// Also returns, in `order`, which placeholder each capture group is.
std::regex patternRegex(const std::string& pattern, std::vector<std::string>& order) {
    std::string re;
    for (size_t i = 0; i < pattern.size();) {
        bool placeholder = false;
        for (const char* p : kPlaceholders) {
            if (pattern.compare(i, std::strlen(p), p) != 0) continue;
            re += std::string(p) == "{sampler}" ? "([^/]+)" : "([0-9]+)";
            order.emplace_back(p);
            i += std::strlen(p);
            placeholder = true;
            break;
        }
        if (placeholder) continue;
        const char c = pattern[i++];
        if (std::strchr("\\^$.|?*+()[]{}", c)) re += '\\';
        re += c;
    }
    return std::regex(re, std::regex::ECMAScript);
}

// The deepest directory of the pattern before its first placeholder.
fs::path searchRoot(const std::string& pattern) {
    const size_t first = pattern.find('{');
    return fs::path(pattern.substr(0, pattern.rfind('/', first) + 1));
}

int parseCount(const std::string& digits, const std::string& file) {
    if (digits.size() > 9) throw InputError("'" + file + "': number '" + digits + "' is too large");
    return std::stoi(digits);
}

using CellIndex = std::tuple<std::string, int, int>;  // sampler, spp, seed

std::map<CellIndex, double> readTimes(const ExternalSpec& spec) {
    std::map<CellIndex, double> times;
    std::ifstream in(spec.times);
    if (!in)
        throw InputError(spec.origin + " names times file '" + spec.times +
                         "', which cannot be read");
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.empty() || line.rfind("sampler,", 0) == 0) continue;  // the header
        std::stringstream fields(line);
        std::string sampler, spp, seed, seconds;
        std::getline(fields, sampler, ',');
        std::getline(fields, spp, ',');
        std::getline(fields, seed, ',');
        std::getline(fields, seconds);
        try {
            size_t a = 0, b = 0, c = 0;
            const int sppValue = std::stoi(spp, &a), seedValue = std::stoi(seed, &b);
            const double s = std::stod(seconds, &c);
            if (a != spp.size() || b != seed.size() || c != seconds.size() || !(s >= 0))
                throw std::invalid_argument("trailing text");
            times[{sampler, sppValue, seedValue}] = s;
        } catch (const std::exception&) {
            throw InputError(spec.times + ":" + std::to_string(n) +
                             ": expected sampler,spp,seed,seconds, got '" + line + "'");
        }
    }
    return times;
}

// The width and height a PNG's IHDR chunk gives (the first chunk, at byte 16).
Vec2i pngSize(const std::string& path) {
    unsigned char head[24] = {};
    std::ifstream in(path, std::ios::binary);
    const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (!in.read(reinterpret_cast<char*>(head), sizeof head) ||
        std::memcmp(head, signature, 8) != 0 || std::memcmp(head + 12, "IHDR", 4) != 0)
        throw InputError("cannot read PNG '" + path + "': not a PNG file");
    const auto be32 = [&](int at) {
        return int(head[at]) << 24 | int(head[at + 1]) << 16 | int(head[at + 2]) << 8 |
               int(head[at + 3]);
    };
    return {be32(16), be32(20)};
}

Vec2i storedImageSize(const std::string& path) {
    switch (imageFormatFromPath(path)) {
        case ImageFormat::Exr:
            try {
                const Imath::Box2i window = Imf::InputFile(path.c_str()).header().dataWindow();
                return {window.max.x - window.min.x + 1, window.max.y - window.min.y + 1};
            } catch (const std::exception& e) {
                throw InputError("cannot read EXR '" + path + "': " + e.what());
            }
        case ImageFormat::Png:
            return pngSize(path);
        case ImageFormat::Pfm:
            break;
    }
    const Image image = readImage(path);
    return {image.width, image.height};
}

}  // namespace

void checkExternalImageSizes(const ExternalRenders& renders, Vec2i size) {
    for (const ExternalImage& image : renders.images) {
        const Vec2i stored = storedImageSize(image.path);
        if (stored.x != size.x || stored.y != size.y)
            throw InputError("'" + image.path + "' is " + std::to_string(stored.x) + "x" +
                             std::to_string(stored.y) + ", the study's images of scene '" +
                             renders.spec->scene + "' are " + std::to_string(size.x) + "x" +
                             std::to_string(size.y));
    }
}

std::string externalSamplerName(const ExternalSpec& spec, const std::string& sampler) {
    return spec.name + ":" + sampler;
}

std::string externalImagePath(const std::string& pattern, const std::string& sampler, int spp,
                              int seed) {
    std::string out = pattern;
    const std::pair<const char*, std::string> values[] = {
        {"{sampler}", sampler}, {"{spp}", std::to_string(spp)}, {"{seed}", std::to_string(seed)}};
    for (const auto& [key, value] : values)
        if (const size_t p = out.find(key); p != std::string::npos)
            out.replace(p, std::strlen(key), value);
    return out;
}

ExternalRenders findExternalImages(const ExternalSpec& spec) {
    const std::string key = spec.origin + ".images";
    for (const char* p : kPlaceholders)
        if (occurrences(spec.images, p) != 1)
            throw InputError(key + " must hold each of {sampler}, {spp} and {seed} once, got '" +
                             spec.images + "'");
    std::vector<std::string> order;
    const std::regex re = patternRegex(spec.images, order);
    std::map<CellIndex, std::string> found;
    std::error_code ec;
    const fs::path root = searchRoot(spec.images);
    if (fs::is_directory(root, ec))
        for (auto it = fs::recursive_directory_iterator(root, ec);
             !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
            if (!it->is_regular_file(ec)) continue;
            const std::string file = it->path().generic_string();
            std::smatch m;
            if (!std::regex_match(file, m, re)) continue;
            std::string sampler;
            int spp = 0, seed = 0;
            for (size_t g = 0; g < order.size(); ++g) {
                if (order[g] == "{sampler}") sampler = m[g + 1];
                if (order[g] == "{spp}") spp = parseCount(m[g + 1], file);
                if (order[g] == "{seed}") seed = parseCount(m[g + 1], file);
            }
            if (spp < 1) throw InputError("'" + file + "': an image of 0 spp (" + key + ")");
            const auto [at, added] = found.try_emplace({sampler, spp, seed}, file);
            if (!added)
                throw InputError("'" + file + "' and '" + at->second + "' are both the image of " +
                                 sampler + " at " + std::to_string(spp) + " spp seed " +
                                 std::to_string(seed));
        }
    if (found.empty()) throw InputError(key + " matches no file: '" + spec.images + "'");
    std::set<std::string> samplers;
    std::set<int> spps, seeds;
    for (const auto& [index, file] : found) {
        samplers.insert(std::get<0>(index));
        spps.insert(std::get<1>(index));
        seeds.insert(std::get<2>(index));
    }
    const std::map<CellIndex, double> times =
        spec.times.empty() ? std::map<CellIndex, double>{} : readTimes(spec);
    ExternalRenders out{&spec, {}};
    for (int seed : seeds)
        for (int spp : spps)
            for (const std::string& sampler : samplers) {
                const auto file = found.find({sampler, spp, seed});
                const std::string cell =
                    sampler + " at " + std::to_string(spp) + " spp seed " + std::to_string(seed);
                if (file == found.end())
                    throw InputError("missing image '" +
                                     externalImagePath(spec.images, sampler, spp, seed) +
                                     "': " + key + " has " + cell + "'s neighbours but not it");
                double seconds = 0;
                if (!spec.times.empty()) {
                    const auto t = times.find({sampler, spp, seed});
                    if (t == times.end())
                        throw InputError("'" + spec.times + "' has no row for " + cell);
                    seconds = t->second;
                }
                out.images.push_back({sampler, spp, seed, file->second, seconds});
            }
    return out;
}

}  // namespace pathlab
