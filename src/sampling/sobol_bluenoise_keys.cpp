#include "sampling/sobol_bluenoise_keys.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <mutex>
#include <stdexcept>
#include <string>
#include <tuple>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/hash.h"
#include "core/paths.h"
#include "core/rng.h"

namespace pathlab {
namespace {

constexpr char kMagic[8] = {'P', 'L', 'S', 'B', 'N', 'K', '0', '2'};
// Also the version of sobolBlueNoisePair: a tile arranged for another pair
// function holds the same pool and would pass every other check.
constexpr uint64_t kFormatVersion = 3;

// The tile's keys are the pool's, permuted, with offsets below 2^levels.
bool isArrangedPool(std::vector<SobolBlueNoiseKey> a, std::vector<SobolBlueNoiseKey> b,
                    int levels) {
    for (SobolBlueNoiseKey& k : a) {
        if (k.offset >> levels != 0) return false;
        k.offset = 0;
    }
    const auto less = [](const SobolBlueNoiseKey& u, const SobolBlueNoiseKey& v) {
        return std::tie(u.rank, u.scrambleX, u.scrambleY) <
               std::tie(v.rank, v.scrambleX, v.scrambleY);
    };
    std::sort(a.begin(), a.end(), less);
    std::sort(b.begin(), b.end(), less);
    return a == b;
}

std::shared_ptr<const SobolBlueNoiseKeys> readKeys(const std::filesystem::path& file,
                                                   const SobolBlueNoiseOptimizer& s) {
    std::ifstream in(file, std::ios::binary);
    char magic[8];
    int32_t size = 0;
    uint64_t fingerprint = 0;
    if (!in.read(magic, 8) || !std::equal(magic, magic + 8, kMagic) ||
        !in.read(reinterpret_cast<char*>(&size), sizeof size) || size != s.size ||
        !in.read(reinterpret_cast<char*>(&fingerprint), sizeof fingerprint) ||
        fingerprint != s.fingerprint())
        return nullptr;
    auto keys = std::make_shared<SobolBlueNoiseKeys>();
    keys->size = size;
    keys->key.resize(size_t(size) * size);
    for (SobolBlueNoiseKey& k : keys->key) {
        uint32_t words[4];
        if (!in.read(reinterpret_cast<char*>(words), sizeof words)) return nullptr;
        k = {words[0], words[1], words[2], words[3]};
    }
    if (in.peek() != std::char_traits<char>::eof()) return nullptr;
    if (!isArrangedPool(keys->key, sobolBlueNoiseKeyPool(s), s.levels)) return nullptr;
    return keys;
}

void writeKeys(const std::filesystem::path& file, const SobolBlueNoiseOptimizer& s,
               const SobolBlueNoiseKeys& keys) {
    std::string bytes(kMagic, 8);
    const int32_t size = keys.size;
    const uint64_t fingerprint = s.fingerprint();
    bytes.append(reinterpret_cast<const char*>(&size), sizeof size);
    bytes.append(reinterpret_cast<const char*>(&fingerprint), sizeof fingerprint);
    for (const SobolBlueNoiseKey& k : keys.key) {
        const uint32_t words[4] = {k.rank, k.scrambleX, k.scrambleY, k.offset};
        bytes.append(reinterpret_cast<const char*>(words), sizeof words);
    }
    std::error_code ec;
    std::filesystem::create_directories(file.parent_path(), ec);
    try {
        writeFileAtomic(file.string(), bytes);
    } catch (const InputError&) {
        // The cache is an optimisation: a read-only or full cache is fine.
    }
}

}  // namespace

uint64_t SobolBlueNoiseOptimizer::fingerprint() const {
    return hashValues(kFormatVersion, size, levels, integrands, passes, sweeps,
                      uint64_t(std::llround(sigma * 1e6)), swapRadius, seed);
}

std::vector<SobolBlueNoiseKey> sobolBlueNoiseKeyPool(const SobolBlueNoiseOptimizer& s) {
    std::vector<SobolBlueNoiseKey> pool(size_t(s.size) * s.size);
    for (size_t i = 0; i < pool.size(); ++i) {
        const uint64_t h = hashValues(s.seed, i, 0x6b6579u);
        pool[i] = {uint32_t(h), uint32_t(h >> 32), foldSeed(mixBits(h))};
    }
    return pool;
}

std::shared_ptr<const SobolBlueNoiseKeys> loadOrCreateSobolBlueNoiseKeys(
    const std::filesystem::path& file, const SobolBlueNoiseOptimizer& settings) {
    checkSobolBlueNoiseSettings(settings);
    if (auto keys = readKeys(file, settings)) return keys;
    auto keys = std::make_shared<const SobolBlueNoiseKeys>(optimizeSobolBlueNoiseKeys(settings));
    writeKeys(file, settings, *keys);
    return keys;
}

std::shared_ptr<const SobolBlueNoiseKeys> defaultSobolBlueNoiseKeys() {
    static std::shared_ptr<const SobolBlueNoiseKeys> keys;
    static std::once_flag once;
    std::call_once(once, [] {
        const SobolBlueNoiseOptimizer settings;
        keys = loadOrCreateSobolBlueNoiseKeys(
            cacheDirectory() /
                ("sobol-bluenoise-ranked-keys-" + std::to_string(settings.size) + ".bin"),
            settings);
    });
    return keys;
}

}  // namespace pathlab
