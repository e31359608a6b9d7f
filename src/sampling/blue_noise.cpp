#include "sampling/blue_noise.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <stdexcept>

#include "core/paths.h"
#include "core/rng.h"

namespace pathlab {
namespace {

// The energy field of a binary pattern: Σ over its ones of a toroidal Gaussian.
class EnergyField {
  public:
    EnergyField(int size, double sigma)
        : size_(size), kernel_(size_t(size) * size), energy_(kernel_.size()) {
        for (int dy = 0; dy < size; ++dy)
            for (int dx = 0; dx < size; ++dx) {
                const int ty = std::min(dy, size - dy), tx = std::min(dx, size - dx);
                kernel_[size_t(dy) * size + dx] =
                    static_cast<float>(std::exp(-(tx * tx + ty * ty) / (2 * sigma * sigma)));
            }
    }
    // Adds (sign = +1) or removes (−1) the splat of a one at pixel i.
    void splat(int i, float sign) {
        const int ix = i % size_, iy = i / size_;
        for (int y = 0; y < size_; ++y) {
            const int ky = y >= iy ? y - iy : y - iy + size_;
            const float* k = &kernel_[size_t(ky) * size_];
            float* e = &energy_[size_t(y) * size_];
            for (int x = 0; x < ix; ++x) e[x] += sign * k[x - ix + size_];
            for (int x = ix; x < size_; ++x) e[x] += sign * k[x - ix];
        }
    }
    // The tightest cluster (max energy among ones) or largest void (min among zeros).
    // The caller guarantees at least one pixel has `value`.
    int extreme(const std::vector<uint8_t>& bits, uint8_t value, bool largest) const {
        size_t best = 0;
        bool found = false;
        float bestEnergy = 0;
        for (size_t i = 0; i < energy_.size(); ++i) {
            if (bits[i] != value) continue;
            const float e = energy_[i];
            if (!found || (largest ? e > bestEnergy : e < bestEnergy)) {
                best = i, bestEnergy = e, found = true;
            }
        }
        return static_cast<int>(best);
    }

  private:
    int size_;
    std::vector<float> kernel_;
    std::vector<float> energy_;
};

constexpr char kMagic[8] = {'P', 'L', 'B', 'N', 'V', 'C', '0', '1'};

}  // namespace

void BlueNoiseTexture::computeValues() {
    const double n = double(size) * double(size);
    fixedPoint.resize(rank.size());
    for (size_t i = 0; i < rank.size(); ++i)
        fixedPoint[i] = static_cast<uint32_t>(std::ldexp((rank[i] + 0.5) / n, 32));
}

BlueNoiseTexture generateBlueNoiseTexture(int size, uint64_t seed, double sigma) {
    if (size < 4) throw std::invalid_argument("blue-noise texture size must be at least 4");
    const int n = size * size;
    BlueNoiseTexture texture;
    texture.size = size;
    texture.rank.assign(size_t(n), 0);

    // Initial binary pattern: ~10% random ones (Ulichney's "prototype"), then
    // relaxed by moving the tightest cluster into the largest void until the
    // move is a no-op.
    std::vector<uint8_t> initial(size_t(n), 0);
    EnergyField initialEnergy(size, sigma);
    Pcg32 rng(hashValues(seed, 0x766163u), 0);
    const int ones = std::max(1, n / 10);
    for (int placed = 0; placed < ones;) {
        const int i = int(rng.nextUInt(uint32_t(n)));
        if (initial[i]) continue;
        initial[i] = 1;
        initialEnergy.splat(i, +1);
        ++placed;
    }
    for (int iteration = 0; iteration < 4 * n; ++iteration) {
        const int cluster = initialEnergy.extreme(initial, 1, true);
        initial[cluster] = 0;
        initialEnergy.splat(cluster, -1);
        const int voidIndex = initialEnergy.extreme(initial, 0, false);
        initial[voidIndex] = 1;
        initialEnergy.splat(voidIndex, +1);
        if (voidIndex == cluster) break;
    }

    // Phase 1: rank the prototype's ones by removing tightest clusters.
    {
        std::vector<uint8_t> bits = initial;
        EnergyField energy = initialEnergy;
        for (int rank = ones - 1; rank >= 0; --rank) {
            const int cluster = energy.extreme(bits, 1, true);
            bits[cluster] = 0;
            energy.splat(cluster, -1);
            texture.rank[cluster] = uint32_t(rank);
        }
    }
    // Phases 2 and 3: fill the largest void until full. (Ulichney's phase 3
    // picks the tightest cluster of zeros; with a fixed kernel that is the
    // same pixel as the largest void of ones.)
    std::vector<uint8_t>& bits = initial;
    EnergyField& energy = initialEnergy;
    for (int rank = ones; rank < n; ++rank) {
        const int voidIndex = energy.extreme(bits, 0, false);
        bits[voidIndex] = 1;
        energy.splat(voidIndex, +1);
        texture.rank[voidIndex] = uint32_t(rank);
    }
    texture.computeValues();
    return texture;
}

std::shared_ptr<const BlueNoiseTexture> loadOrCreateBlueNoiseTexture(
    const std::filesystem::path& file, int size, uint64_t seed) {
    const size_t n = size_t(size) * size;
    // Read and validate: magic, size, seed, and the ranks a permutation.
    {
        std::ifstream in(file, std::ios::binary);
        char magic[8];
        int32_t storedSize = 0;
        uint64_t storedSeed = 0;
        if (in.read(magic, 8) && std::equal(magic, magic + 8, kMagic) &&
            in.read(reinterpret_cast<char*>(&storedSize), sizeof storedSize) &&
            storedSize == size &&
            in.read(reinterpret_cast<char*>(&storedSeed), sizeof storedSeed) &&
            storedSeed == seed) {
            auto texture = std::make_shared<BlueNoiseTexture>();
            texture->size = size;
            texture->rank.resize(n);
            if (in.read(reinterpret_cast<char*>(texture->rank.data()), std::streamsize(n * 4))) {
                std::vector<uint8_t> seen(n, 0);
                bool valid = true;
                for (uint32_t r : texture->rank) {
                    if (r >= n || seen[r]) {
                        valid = false;
                        break;
                    }
                    seen[r] = 1;
                }
                if (valid) {
                    texture->computeValues();
                    return texture;
                }
            }
        }
    }
    auto texture = std::make_shared<BlueNoiseTexture>(generateBlueNoiseTexture(size, seed));
    // Atomic write: a unique temporary beside the target, renamed over it. A
    // concurrent process doing the same writes identical bytes.
    std::error_code ec;
    std::filesystem::create_directories(file.parent_path(), ec);
    const std::filesystem::path tmp =
        file.string() + ".tmp." + std::to_string(::getpid()) + "." +
        std::to_string(hashValues(reinterpret_cast<uintptr_t>(texture.get())) & 0xffffff);
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        const int32_t storedSize = size;
        out.write(kMagic, 8);
        out.write(reinterpret_cast<const char*>(&storedSize), sizeof storedSize);
        out.write(reinterpret_cast<const char*>(&seed), sizeof seed);
        out.write(reinterpret_cast<const char*>(texture->rank.data()), std::streamsize(n * 4));
        out.close();
        if (!out) {
            std::filesystem::remove(tmp, ec);
            return texture;  // the cache is an optimisation; a read-only cache is fine
        }
    }
    std::filesystem::rename(tmp, file, ec);
    if (ec) std::filesystem::remove(tmp, ec);
    return texture;
}

std::shared_ptr<const BlueNoiseTexture> defaultBlueNoiseTexture() {
    static std::shared_ptr<const BlueNoiseTexture> texture;
    static std::once_flag once;
    std::call_once(once, [] {
        texture = loadOrCreateBlueNoiseTexture(
            cacheDirectory() / ("blue-noise-vc-" + std::to_string(kBlueNoiseTextureSize) + ".bin"),
            kBlueNoiseTextureSize, 0x7061746862ULL);
    });
    return texture;
}

}  // namespace pathlab
