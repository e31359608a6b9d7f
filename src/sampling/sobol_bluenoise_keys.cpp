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

constexpr char kMagic[8] = {'P', 'L', 'S', 'B', 'N', 'K', '0', '1'};
// Also the version of sobolBlueNoisePair: a tile arranged for another pair
// function holds the same pool and would pass every other check.
constexpr uint64_t kFormatVersion = 2;

// A test integrand: the indicator of the half-plane n·(x, y) < c, whose edge
// runs through a random point of the square at a random angle, seen through a
// random digital shift (the sampler shifts every point by the seed's shift,
// so the keys are arranged for steps under any shift).
struct Step {
    float nx, ny, c;
    uint64_t shift;
    float operator()(uint64_t xy) const {
        xy ^= shift;
        const float x = fixedPointToFloat(uint32_t(xy)), y = fixedPointToFloat(uint32_t(xy >> 32));
        return nx * x + ny * y < c ? 1.0f : 0.0f;
    }
};

std::vector<Step> testSteps(int count, uint64_t seed) {
    Pcg32 rng(hashValues(seed, 0x73746570u), 0);
    std::vector<Step> steps(static_cast<size_t>(count));
    for (size_t j = 0; j < steps.size(); ++j) {
        Step& s = steps[j];
        const double angle = 2 * M_PI * rng.nextFloat();
        const float px = rng.nextFloat(), py = rng.nextFloat();
        s.nx = float(std::cos(angle)), s.ny = float(std::sin(angle));
        s.c = s.nx * px + s.ny * py;
        s.shift = j % 2 ? uint64_t(rng.nextUInt()) << 32 | rng.nextUInt() : 0;
    }
    return steps;
}

// Row k of the result: key k's estimates of every step from its first 2^l
// points, l = 0…levels (block l, `steps` values), centred on the pool's mean
// and each block scaled to unit mean square over the pool.
std::vector<float> errorVectors(const std::vector<SobolBlueNoiseKey>& keys,
                                const std::vector<Step>& steps, int levels) {
    const size_t t = steps.size(), dims = t * size_t(levels + 1), n = keys.size();
    std::vector<float> e(n * dims);
    std::vector<float> count(t);
    for (size_t k = 0; k < n; ++k) {
        std::fill(count.begin(), count.end(), 0.0f);
        for (uint32_t i = 0, level = 0; i < (1u << levels); ++i) {
            const uint64_t xy = sobolBlueNoisePair(keys[k], i);
            for (size_t j = 0; j < t; ++j) count[j] += steps[j](xy);
            if (((i + 1) & i) == 0) {  // i + 1 = 2^level points so far
                for (size_t j = 0; j < t; ++j)
                    e[k * dims + level * t + j] = count[j] / float(i + 1);
                ++level;
            }
        }
    }
    for (size_t c = 0; c < dims; ++c) {
        double mean = 0;
        for (size_t k = 0; k < n; ++k) mean += e[k * dims + c];
        mean /= double(n);
        for (size_t k = 0; k < n; ++k) e[k * dims + c] -= float(mean);
    }
    for (int level = 0; level <= levels; ++level) {
        double squares = 0;
        for (size_t k = 0; k < n; ++k)
            for (size_t j = 0; j < t; ++j)
                squares += double(e[k * dims + level * t + j]) * e[k * dims + level * t + j];
        const double rms = std::sqrt(squares / double(n));
        if (rms == 0) continue;
        for (size_t k = 0; k < n; ++k)
            for (size_t j = 0; j < t; ++j) e[k * dims + level * t + j] /= float(rms);
    }
    return e;
}

// The tile's arrangement of error vectors, the low-pass field F and the swaps.
class Arrangement {
  public:
    Arrangement(const SobolBlueNoiseOptimizer& s, std::vector<SobolBlueNoiseKey> keys,
                std::vector<float> errors)
        : size_(s.size),
          dims_(errors.size() / keys.size()),
          radius_(std::max(1, int(std::ceil(3 * s.sigma)))),
          keys_(std::move(keys)),
          e_(std::move(errors)),
          field_(e_.size(), 0.0f) {
        const int side = 2 * radius_ + 1;
        weight_.resize(size_t(side) * side);
        for (int dy = -radius_; dy <= radius_; ++dy)
            for (int dx = -radius_; dx <= radius_; ++dx)
                weight_[size_t(dy + radius_) * side + (dx + radius_)] =
                    dx == 0 && dy == 0
                        ? 0.0f
                        : float(std::exp(-(dx * dx + dy * dy) / (2 * s.sigma * s.sigma)));
        for (int p = 0; p < size_ * size_; ++p) addToNeighbours(p, &e_[size_t(p) * dims_], 1.0f);
    }

    // Proposes swapping pixel a with b; keeps the swap if it lowers the energy.
    bool trySwap(int a, int b) {
        float* ea = row(e_, a);
        float* eb = row(e_, b);
        const float* fa = row(field_, a);
        const float* fb = row(field_, b);
        const float w = weight(a, b);
        float gain = 0, norm = 0;
        for (size_t c = 0; c < dims_; ++c) {
            const float d = eb[c] - ea[c];
            gain += d * (fa[c] - fb[c]);
            norm += d * d;
        }
        if (gain - w * norm >= 0) return false;
        std::vector<float>& d = scratch_;
        d.resize(dims_);
        for (size_t c = 0; c < dims_; ++c) d[c] = eb[c] - ea[c];
        addToNeighbours(a, d.data(), 1.0f);
        addToNeighbours(b, d.data(), -1.0f);
        std::swap_ranges(ea, ea + dims_, eb);
        std::swap(keys_[size_t(a)], keys_[size_t(b)]);
        return true;
    }

    std::vector<SobolBlueNoiseKey> takeKeys() { return std::move(keys_); }

  private:
    float* row(std::vector<float>& v, int p) { return &v[size_t(p) * dims_]; }
    int wrap(int v) const { return v & (size_ - 1); }
    // w(a − b) on the torus, 0 outside the kernel's window.
    float weight(int a, int b) const {
        int dx = wrap(b % size_ - a % size_), dy = wrap(b / size_ - a / size_);
        if (dx > size_ / 2) dx -= size_;
        if (dy > size_ / 2) dy -= size_;
        if (std::abs(dx) > radius_ || std::abs(dy) > radius_) return 0.0f;
        return weight_[size_t(dy + radius_) * (2 * radius_ + 1) + (dx + radius_)];
    }
    // F_q += sign · w(q − p) · v for every q in p's window.
    void addToNeighbours(int p, const float* v, float sign) {
        const int px = p % size_, py = p / size_, side = 2 * radius_ + 1;
        for (int dy = -radius_; dy <= radius_; ++dy)
            for (int dx = -radius_; dx <= radius_; ++dx) {
                const float w = sign * weight_[size_t(dy + radius_) * side + (dx + radius_)];
                if (w == 0) continue;
                float* f = row(field_, wrap(py + dy) * size_ + wrap(px + dx));
                for (size_t c = 0; c < dims_; ++c) f[c] += w * v[c];
            }
    }

    int size_;
    size_t dims_;
    int radius_;
    std::vector<SobolBlueNoiseKey> keys_;
    std::vector<float> e_, field_, weight_, scratch_;
};

void checkSettings(const SobolBlueNoiseOptimizer& s) {
    if (s.size < 8 || (s.size & (s.size - 1)) != 0)
        throw std::invalid_argument("sobol-bluenoise tile size must be a power of two ≥ 8");
    if (s.levels < 0 || s.levels > 12 || s.integrands < 1 || s.passes < 0 || !(s.sigma > 0) ||
        s.swapRadius < 1 || 2 * std::max(s.swapRadius, int(std::ceil(3 * s.sigma))) >= s.size)
        throw std::invalid_argument("sobol-bluenoise optimiser settings out of range");
}

bool sameMultiset(std::vector<SobolBlueNoiseKey> a, std::vector<SobolBlueNoiseKey> b) {
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
        uint32_t words[3];
        if (!in.read(reinterpret_cast<char*>(words), sizeof words)) return nullptr;
        k = {words[0], words[1], words[2]};
    }
    if (in.peek() != std::char_traits<char>::eof()) return nullptr;
    if (!sameMultiset(keys->key, sobolBlueNoiseKeyPool(s))) return nullptr;
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
        const uint32_t words[3] = {k.rank, k.scrambleX, k.scrambleY};
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
    return hashValues(kFormatVersion, size, levels, integrands, passes,
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

SobolBlueNoiseKeys optimizeSobolBlueNoiseKeys(const SobolBlueNoiseOptimizer& s) {
    checkSettings(s);
    std::vector<SobolBlueNoiseKey> pool = sobolBlueNoiseKeyPool(s);
    std::vector<float> errors = errorVectors(pool, testSteps(s.integrands, s.seed), s.levels);
    Arrangement arrangement(s, std::move(pool), std::move(errors));
    // Proposals visit random pixels with random partners nearby: a fixed
    // stream, so the tile is a function of the settings alone.
    Pcg32 rng(hashValues(s.seed, 0x73776170u), 0);
    const int n = s.size * s.size, span = 2 * s.swapRadius + 1;
    for (int64_t proposal = 0; proposal < int64_t(s.passes) * n; ++proposal) {
        const int a = int(rng.nextUInt(uint32_t(n)));
        const int dx = int(rng.nextUInt(uint32_t(span))) - s.swapRadius;
        const int dy = int(rng.nextUInt(uint32_t(span))) - s.swapRadius;
        if (dx == 0 && dy == 0) continue;
        const int bx = (a % s.size + dx) & (s.size - 1), by = (a / s.size + dy) & (s.size - 1);
        arrangement.trySwap(a, by * s.size + bx);
    }
    SobolBlueNoiseKeys keys;
    keys.size = s.size;
    keys.key = arrangement.takeKeys();
    return keys;
}

std::shared_ptr<const SobolBlueNoiseKeys> loadOrCreateSobolBlueNoiseKeys(
    const std::filesystem::path& file, const SobolBlueNoiseOptimizer& settings) {
    checkSettings(settings);
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
            cacheDirectory() / ("sobol-bluenoise-keys-" + std::to_string(settings.size) + ".bin"),
            settings);
    });
    return keys;
}

}  // namespace pathlab
