// The RGB-to-spectrum table's cache file:
//   8 bytes magic "PLRGB2SP", int32 resolution, uint64 fingerprint,
//   float zNodes[n], float coefficients[3·n³·3], float worstDeltaE,
//   uint64 checksum (FNV-1a of every byte before it).
// The fingerprint hashes the format version and the CIE data the optimiser
// used, so new colour-matching or illuminant data make a new table. A file
// that is short, long, corrupt or of another fingerprint is rebuilt.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/hash.h"
#include "spectral/cie_data.h"
#include "spectral/rgb_spectrum_table.h"

namespace pathlab::spectral {
namespace {

constexpr char kMagic[8] = {'P', 'L', 'R', 'G', 'B', '2', 'S', 'P'};
// 2: fits with backtracking (version 1's tables had diverged nodes).
constexpr uint64_t kFormatVersion = 2;

uint64_t fnv1a(std::string_view bytes) {
    uint64_t h = 0xcbf29ce484222325ULL;
    for (unsigned char c : bytes) h = (h ^ c) * 0x100000001b3ULL;
    return h;
}

uint64_t fingerprint(int resolution) {
    uint64_t h = hashValues(kFormatVersion, resolution);
    auto mix = [&](const double* values, int count) {
        for (int i = 0; i < count; ++i) h = hashValues(h, std::bit_cast<uint64_t>(values[i]));
    };
    mix(cie_data::kCmfX, cie_data::kCmfCount);
    mix(cie_data::kCmfY, cie_data::kCmfCount);
    mix(cie_data::kCmfZ, cie_data::kCmfCount);
    for (int i = 0; i < cie_data::kIlluminantCount; ++i)
        if (std::string_view(cie_data::kIlluminants[i].name) == "stdillum-D65")
            mix(cie_data::kIlluminants[i].values, cie_data::kIlluminants[i].count);
    return h;
}

template <typename T>
void append(std::string& bytes, const T& value) {
    bytes.append(reinterpret_cast<const char*>(&value), sizeof value);
}
template <typename T>
bool take(std::string_view& bytes, T& value) {
    if (bytes.size() < sizeof value) return false;
    std::memcpy(&value, bytes.data(), sizeof value);
    bytes.remove_prefix(sizeof value);
    return true;
}

std::string serialise(const RgbToSpectrumTable& t) {
    std::string bytes(kMagic, sizeof kMagic);
    append(bytes, int32_t(t.resolution));
    append(bytes, fingerprint(t.resolution));
    for (float z : t.zNodes) append(bytes, z);
    for (float c : t.coefficients) append(bytes, c);
    append(bytes, t.worstDeltaE);
    append(bytes, fnv1a(bytes));
    return bytes;
}

std::shared_ptr<RgbToSpectrumTable> parse(std::string_view bytes, int resolution) {
    if (bytes.size() < sizeof kMagic + 8) return nullptr;
    uint64_t checksum = 0;
    std::memcpy(&checksum, bytes.data() + bytes.size() - 8, 8);
    if (checksum != fnv1a(bytes.substr(0, bytes.size() - 8))) return nullptr;
    if (std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) return nullptr;
    bytes.remove_prefix(sizeof kMagic);
    int32_t storedResolution = 0;
    uint64_t storedFingerprint = 0;
    if (!take(bytes, storedResolution) || storedResolution != resolution) return nullptr;
    if (!take(bytes, storedFingerprint) || storedFingerprint != fingerprint(resolution))
        return nullptr;
    auto t = std::make_shared<RgbToSpectrumTable>();
    t->resolution = resolution;
    t->zNodes.resize(size_t(resolution));
    t->coefficients.resize(size_t(3) * resolution * resolution * resolution * 3);
    for (float& z : t->zNodes)
        if (!take(bytes, z) || !std::isfinite(z)) return nullptr;
    for (float& c : t->coefficients)
        if (!take(bytes, c) || !std::isfinite(c)) return nullptr;
    if (!take(bytes, t->worstDeltaE) || bytes.size() != 8) return nullptr;
    return t;
}

}  // namespace

std::shared_ptr<const RgbToSpectrumTable> loadOrCreateRgbToSpectrumTable(
    const std::filesystem::path& file, int resolution) {
    {
        // Read whole (9 MB at n = 64: character by character, the reading was
        // most of a spectral render's start-up).
        std::ifstream in(file, std::ios::binary | std::ios::ate);
        if (in) {
            std::string bytes(size_t(std::max<std::streamoff>(in.tellg(), 0)), '\0');
            in.seekg(0);
            if (in.read(bytes.data(), std::streamsize(bytes.size())))
                if (auto t = parse(bytes, resolution)) return t;
        }
    }
    auto t = std::make_shared<const RgbToSpectrumTable>(makeRgbToSpectrumTable(resolution));
    std::error_code ec;
    std::filesystem::create_directories(file.parent_path(), ec);
    try {
        writeFileAtomic(file.string(), serialise(*t));
    } catch (const InputError&) {
        // The cache is an optimisation: a read-only or full cache is fine.
    }
    return t;
}

}  // namespace pathlab::spectral
