// The optimiser that arranges `sobol-bluenoise`'s key tile: a permutation of
// the pool for the full 2^L-point sets, then one ranking bit per level below
// (sobol_bluenoise_keys.h gives the energy and the two steps).
#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "core/hash.h"
#include "core/rng.h"
#include "sampling/sobol_bluenoise_keys.h"

namespace pathlab {
namespace {

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

// The error of a 2^m-point (0,m,2)-net is that of the Walsh functions it
// does not integrate exactly; for a smooth integrand the largest Walsh
// coefficients are those of the Rademacher products r_kx(x) r_ky(y) (r_k the
// sign of the k-th binary digit, r_0 = 1), and the net integrates those with
// kx + ky ≤ m exactly. So each level's probes are the products with
// kx + ky = m + 1 and m + 2, besides the steps (edges). A digital shift only
// flips the sign of a Walsh function, the same in every pixel: the spectrum
// of its error image does not depend on the seed's shift.
struct Probe {
    Step step{};
    int kx = -1, ky = 0;  // kx ≥ 0: the product r_kx(x) r_ky(y); else the step
    static float rademacher(uint32_t v, int k) {
        return k == 0 || ((v >> (32 - k)) & 1) == 0 ? 1.0f : -1.0f;
    }
    float operator()(uint64_t xy) const {
        if (kx < 0) return step(xy);
        return rademacher(uint32_t(xy), kx) * rademacher(uint32_t(xy >> 32), ky);
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

// The first ranked index of the 2^level-point block a key's first 2^level
// samples come from, with `flip` XORed onto the offset.
uint32_t blockStart(const SobolBlueNoiseKey& key, int level, uint32_t flip) {
    return (owenScramble(0, key.rank) ^ key.offset ^ flip) & ~((uint32_t(1) << level) - 1);
}

// The probes of one level: the steps and the Rademacher products (integral
// 0), each scaled to unit mean square error over the tile so that every
// probe counts the same.
struct LevelProbes {
    std::vector<Probe> probe;
    std::vector<float> integral, scale;
};

// A key's errors on every probe from its first 2^level samples (with `flip`
// XORed onto its offset).
void keyErrors(const SobolBlueNoiseKey& key, const LevelProbes& p, int level, uint32_t flip,
               float* out) {
    const uint32_t count = uint32_t(1) << level, start = blockStart(key, level, flip);
    const size_t t = p.probe.size();
    std::fill(out, out + t, 0.0f);
    for (uint32_t i = 0; i < count; ++i) {
        const uint64_t xy = sobolBlueNoiseRankedPair(key, start | i);
        for (size_t j = 0; j < t; ++j) out[j] += p.probe[j](xy);
    }
    for (size_t j = 0; j < t; ++j) out[j] = (out[j] / float(count) - p.integral[j]) * p.scale[j];
}

// Row k: keyErrors of key k.
std::vector<float> levelErrors(const std::vector<SobolBlueNoiseKey>& keys, const LevelProbes& p,
                               int level, uint32_t flip) {
    std::vector<float> e(keys.size() * p.probe.size());
    for (size_t k = 0; k < keys.size(); ++k)
        keyErrors(keys[k], p, level, flip, &e[k * p.probe.size()]);
    return e;
}

// The probes of `level`, scaled for the keys' current errors.
LevelProbes levelProbes(const std::vector<SobolBlueNoiseKey>& keys, const std::vector<Step>& steps,
                        const std::vector<float>& stepIntegral, int level) {
    LevelProbes p;
    for (size_t j = 0; j < steps.size(); ++j)
        p.probe.push_back({steps[j]}), p.integral.push_back(stepIntegral[j]);
    for (int order = level + 1; order <= level + 2; ++order)
        for (int kx = 0; kx <= order; ++kx)
            if (kx <= 31 && order - kx <= 31)
                p.probe.push_back({Step{}, kx, order - kx}), p.integral.push_back(0.0f);
    const size_t t = p.probe.size();
    p.scale.assign(t, 1.0f);
    const std::vector<float> e = levelErrors(keys, p, level, 0);
    for (size_t j = 0; j < t; ++j) {
        double squares = 0;
        for (size_t k = 0; k < keys.size(); ++k) squares += double(e[k * t + j]) * e[k * t + j];
        if (squares > 0) p.scale[j] = float(1 / std::sqrt(squares / double(keys.size())));
    }
    return p;
}

// Each step's integral, to the precision of every key's 2^levels points.
std::vector<float> stepIntegrals(const std::vector<SobolBlueNoiseKey>& keys,
                                 const std::vector<Step>& steps, int levels) {
    LevelProbes p;
    for (const Step& step : steps) p.probe.push_back({step});
    p.integral.assign(steps.size(), 0.0f);
    p.scale.assign(steps.size(), 1.0f);
    const std::vector<float> estimates = levelErrors(keys, p, levels, 0);
    std::vector<float> integral(steps.size(), 0.0f);
    for (size_t j = 0; j < steps.size(); ++j) {
        double sum = 0;
        for (size_t k = 0; k < keys.size(); ++k) sum += estimates[k * steps.size() + j];
        integral[j] = float(sum / double(keys.size()));
    }
    return integral;
}

// The tile's error vectors e_p and the low-pass field F_p = Σ_{q≠p} w(p−q) e_q.
class ErrorField {
  public:
    ErrorField(int size, double sigma, std::vector<float> errors)
        : size_(size),
          dims_(errors.size() / (size_t(size) * size)),
          radius_(std::max(1, int(std::ceil(3 * sigma)))),
          e_(std::move(errors)),
          field_(e_.size(), 0.0f) {
        const int side = 2 * radius_ + 1;
        weight_.resize(size_t(side) * side);
        for (int dy = -radius_; dy <= radius_; ++dy)
            for (int dx = -radius_; dx <= radius_; ++dx)
                weight_[size_t(dy + radius_) * side + (dx + radius_)] =
                    dx == 0 && dy == 0
                        ? 0.0f
                        : float(std::exp(-(dx * dx + dy * dy) / (2 * sigma * sigma)));
        for (int p = 0; p < size_ * size_; ++p) addToNeighbours(p, row(e_, p), 1.0f);
    }

    // Whether swapping the errors of pixels a and b lowers the energy; if
    // so, swaps them.
    bool trySwap(int a, int b) {
        float* ea = row(e_, a);
        float* eb = row(e_, b);
        const float* fa = row(field_, a);
        const float* fb = row(field_, b);
        float gain = 0, norm = 0;
        for (size_t c = 0; c < dims_; ++c) {
            const float d = eb[c] - ea[c];
            gain += d * (fa[c] - fb[c]);
            norm += d * d;
        }
        if (gain - weight(a, b) * norm >= 0) return false;
        scratch_.resize(dims_);
        for (size_t c = 0; c < dims_; ++c) scratch_[c] = eb[c] - ea[c];
        addToNeighbours(a, scratch_.data(), 1.0f);
        addToNeighbours(b, scratch_.data(), -1.0f);
        std::swap_ranges(ea, ea + dims_, eb);
        return true;
    }

    // Whether replacing pixel p's error by `candidate` lowers the energy, its
    // own term w(0)|e_p|² = |e_p|² included; if so, replaces it.
    bool tryReplace(int p, const float* candidate) {
        float* ep = row(e_, p);
        const float* fp = row(field_, p);
        float change = 0;
        for (size_t c = 0; c < dims_; ++c)
            change +=
                2 * (candidate[c] - ep[c]) * fp[c] + candidate[c] * candidate[c] - ep[c] * ep[c];
        if (change >= 0) return false;
        scratch_.resize(dims_);
        for (size_t c = 0; c < dims_; ++c) scratch_[c] = candidate[c] - ep[c];
        addToNeighbours(p, scratch_.data(), 1.0f);
        std::copy(candidate, candidate + dims_, ep);
        return true;
    }

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
    std::vector<float> e_, field_, weight_, scratch_;
};

// Step 1: permutes the keys so that the errors of their 2^levels-point sets
// are blue. Proposals visit random pixels with random partners nearby: a
// fixed stream, so the tile is a function of the settings alone.
void arrangeFullSets(const SobolBlueNoiseOptimizer& s, std::vector<SobolBlueNoiseKey>& keys,
                     const LevelProbes& probes) {
    ErrorField field(s.size, s.sigma, levelErrors(keys, probes, s.levels, 0));
    Pcg32 rng(hashValues(s.seed, 0x73776170u), 0);
    const int n = s.size * s.size, span = 2 * s.swapRadius + 1;
    for (int64_t proposal = 0; proposal < int64_t(s.passes) * n; ++proposal) {
        const int a = int(rng.nextUInt(uint32_t(n)));
        const int dx = int(rng.nextUInt(uint32_t(span))) - s.swapRadius;
        const int dy = int(rng.nextUInt(uint32_t(span))) - s.swapRadius;
        if (dx == 0 && dy == 0) continue;
        const int bx = (a % s.size + dx) & (s.size - 1), by = (a / s.size + dy) & (s.size - 1);
        const int b = by * s.size + bx;
        if (field.trySwap(a, b)) std::swap(keys[size_t(a)], keys[size_t(b)]);
    }
}

// Step 2 at one level: bit `level` of each offset, chosen pixel by pixel in
// a seeded order, `sweeps` times over the tile.
void rankLevel(const SobolBlueNoiseOptimizer& s, std::vector<SobolBlueNoiseKey>& keys,
               const LevelProbes& probes, int level) {
    const uint32_t bit = uint32_t(1) << level;
    std::vector<float> other = levelErrors(keys, probes, level, bit);
    ErrorField field(s.size, s.sigma, levelErrors(keys, probes, level, 0));
    const size_t t = probes.probe.size();
    std::vector<int> order(keys.size());
    std::iota(order.begin(), order.end(), 0);
    Pcg32 rng(hashValues(s.seed, 0x72616e6bu, level), 0);
    for (int sweep = 0; sweep < s.sweeps; ++sweep) {
        for (size_t i = order.size(); i > 1; --i)  // Fisher–Yates, seeded
            std::swap(order[i - 1], order[rng.nextUInt(uint32_t(i))]);
        for (const int p : order) {
            float* candidate = &other[size_t(p) * t];
            if (!field.tryReplace(p, candidate)) continue;
            keys[size_t(p)].offset ^= bit;
            // The half just left is now the alternative.
            keyErrors(keys[size_t(p)], probes, level, bit, candidate);
        }
    }
}

}  // namespace

void checkSobolBlueNoiseSettings(const SobolBlueNoiseOptimizer& s) {
    if (s.size < 8 || (s.size & (s.size - 1)) != 0)
        throw std::invalid_argument("sobol-bluenoise tile size must be a power of two ≥ 8");
    if (s.levels < 0 || s.levels > 12 || s.integrands < 1 || s.passes < 0 || s.sweeps < 0 ||
        !(s.sigma > 0) || s.swapRadius < 1 ||
        2 * std::max(s.swapRadius, int(std::ceil(3 * s.sigma))) >= s.size)
        throw std::invalid_argument("sobol-bluenoise optimiser settings out of range");
}

SobolBlueNoiseKeys optimizeSobolBlueNoiseKeys(const SobolBlueNoiseOptimizer& s) {
    checkSobolBlueNoiseSettings(s);
    std::vector<SobolBlueNoiseKey> keys = sobolBlueNoiseKeyPool(s);
    const std::vector<Step> steps = testSteps(s.integrands, s.seed);
    const std::vector<float> integral = stepIntegrals(keys, steps, s.levels);
    arrangeFullSets(s, keys, levelProbes(keys, steps, integral, s.levels));
    for (int level = s.levels - 1; level >= 0; --level)
        rankLevel(s, keys, levelProbes(keys, steps, integral, level), level);
    SobolBlueNoiseKeys tile;
    tile.size = s.size;
    tile.key = std::move(keys);
    return tile;
}

}  // namespace pathlab
