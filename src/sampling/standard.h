// `standard`: the presentation's "Standard Sampler" — C++'s minimal-standard
// LCG (Lewis, Goodman & Miller 1969; Park & Miller 1988, "Random Number
// Generators: Good Ones Are Hard to Find"), x_{n+1} = 16807 x_n mod (2^31 − 1),
// through std::uniform_real_distribution<float>(0,1).
//
// The presentation draws from one static engine shared by all pixels, which
// makes the image depend on thread scheduling. Here the engine is re-seeded for
// every (pixel, sample index, seed) from a hash, and advanced by the dimension,
// so results are deterministic; each float costs exactly one engine step
// (generate_canonical needs ceil(24 / log2(2^31 − 2)) = 1 call).
#pragma once

#include <array>
#include <random>

#include "core/hash.h"
#include "sampling/sampler.h"

namespace pathlab {

using MinimalStandardEngine = std::linear_congruential_engine<uint32_t, 16807, 0, 2147483647>;

class StandardSampler {
  public:
    explicit StandardSampler(const SamplerConfig& c) : spp_(c.samplesPerPixel), seed_(c.seed) {}

    int samplesPerPixel() const { return spp_; }
    void startPixelSample(Vec2i p, int index, int dim) {
        // The same pixel sample a little further on (the next path vertex):
        // step from where the engine is instead of re-seeding.
        if (p.x == pixel_.x && p.y == pixel_.y && index == index_ && dim >= position_) {
            engine_.discard(static_cast<unsigned long long>(dim - position_));
            position_ = dim;
            return;
        }
        reseed(p, index, dim);
    }
    float get1D() {
        // The presentation clamps every value to [0, 1 − ε]; generate_canonical
        // can round up to exactly 1 for floats.
        ++position_;
        const float v = distribution_(engine_);
        return v < kOneMinusEpsilon ? v : kOneMinusEpsilon;
    }
    Vec2f get2D() {
        const float a = get1D();
        return {a, get1D()};
    }
    Vec2f getPixel2D() { return get2D(); }

    // Lane draws (sampler.h): each lane's engine output at dimension d is its
    // seed state times 16807^(d+1) mod (2^31 − 1), so every lane's values
    // come from one multiply each instead of re-seeding one engine and
    // stepping it lane after lane (a chain of dependent multiplies), reduced
    // by the Mersenne fold (mersenneMod) and turned into the distribution's
    // float by canonicalFloat — the same values (tested). They leave the
    // per-sample engine and its position as they were (they read only the
    // seed states), so startPixelSample's step-on path stays valid; they used
    // to re-seed the engine at the last lane, a modulo per call that the
    // profile-guided build compiled as a division.
    void get1DLanes(Vec2i p, const int* indices, int count, int dim, float* out) {
        uint64_t states[kCameraPacketSamples];
        for (int j = 0; j < count; ++j) states[j] = seedState(p, indices[j]);
        const uint64_t power = multiplierPower(dim + 1);
        for (int j = 0; j < count; ++j) out[j] = laneValue(states[j], power);
    }
    void get2DLanes(Vec2i p, const int* indices, int count, int dim, Vec2f* out) {
        uint64_t states[kCameraPacketSamples];
        for (int j = 0; j < count; ++j) states[j] = seedState(p, indices[j]);
        const uint64_t powerX = multiplierPower(dim + 1), powerY = multiplierPower(dim + 2);
        for (int j = 0; j < count; ++j)
            out[j] = {laneValue(states[j], powerX), laneValue(states[j], powerY)};
    }
    void getPixel2DLanes(Vec2i p, const int* indices, int count, Vec2f* out) {
        get2DLanes(p, indices, count, dims::kPixel, out);
    }

    // x mod (2^31 − 2), the number of valid states, without a division: the
    // profile-guided build compiled `%` by this constant on a path it deems
    // cold (a sample's first draw) as a 64-bit division. 2^31 − 2 =
    // 2·(2^30 − 1), so x mod it is 2·(⌊x/2⌋ mod (2^30 − 1)) + (x mod 2), and
    // modulo the Mersenne number 2^30 − 1 a number is congruent to the sum
    // of its 30-bit chunks (2^30 ≡ 1): two folds take ⌊x/2⌋ < 2^63 to at
    // most 2^30 + 8, and one subtraction below 2^30 − 1.
    static uint64_t moduloStateCount(uint64_t x) {
        constexpr uint64_t kChunk = (uint64_t(1) << 30) - 1;
        uint64_t y = x >> 1;
        y = (y & kChunk) + (y >> 30);  // < 2^30 + 2^33
        y = (y & kChunk) + (y >> 30);  // ≤ 2^30 − 1 + 9
        if (y >= kChunk) y -= kChunk;
        return 2 * y + (x & 1);
    }

    // What distribution_ makes of the engine output x, clamped as get1D
    // clamps it: libstdc++'s generate_canonical takes one engine call and
    // divides float(x − min) by float(max − min + 1) = float(2^31 − 2) =
    // 2^31 exactly, so the value is float(x − 1)·2^-31; the rare ≥ 1 it
    // replaces by nextafter(1, 0), which is kOneMinusEpsilon, the clamp's
    // value too. Checked against the distribution itself (tested), so a
    // standard library that computed it otherwise would fail the tests.
    static float canonicalFloat(uint32_t x) {
        const float v = static_cast<float>(x - 1) * 0x1p-31f;
        return v < kOneMinusEpsilon ? v : kOneMinusEpsilon;
    }

  private:
    // x mod (2^31 − 1) for x < 2^62 that is not a multiple of it (a product
    // of a state and a power of 16807, both in [1, 2^31 − 2], never is): as
    // 2^31 ≡ 1, x ≡ (x mod 2^31) + ⌊x / 2^31⌋, which is below 2^32 and is
    // reduced by one subtraction at most. Shifts and adds where `%` is a
    // multiply-high sequence.
    static uint32_t mersenneMod(uint64_t x) {
        const uint64_t folded = (x & kModulus) + (x >> 31);
        return static_cast<uint32_t>(folded >= kModulus ? folded - kModulus : folded);
    }

    // The value whose engine state is a seed state times `power` (16807^(d+1)
    // for dimension d).
    static float laneValue(uint64_t state, uint64_t power) {
        return canonicalFloat(mersenneMod(state * power));
    }
    // The engine at dimension `dim` of the sample, seeded afresh.
    void reseed(Vec2i p, int index, int dim) {
        pixel_ = p, index_ = index, position_ = dim;
        engine_.seed(stateAt(seedState(p, index), dim));
    }
    // The engine's state `dim` steps on from a sample's seed state x:
    // x·16807^dim mod (2^31 − 1), one multiply instead of `dim` steps.
    static uint32_t stateAt(uint64_t seed, int dim) {
        return mersenneMod(seed * multiplierPower(dim));
    }

    // A valid state is in [1, 2^31 − 2]; the hash picks one uniformly. The
    // last kBatchSamples samples' states are kept: the renderer returns to
    // each sample of a batch at every bounce.
    uint64_t seedState(Vec2i p, int index) {
        RecentSample& recent = recent_[size_t(index) % recent_.size()];
        if (recent.index != index || recent.pixel.x != p.x || recent.pixel.y != p.y)
            recent = {p, index, 1 + moduloStateCount(hashValues(p.x, p.y, index, seed_))};
        return recent.state;
    }
    struct RecentSample {
        Vec2i pixel{-1, -1};
        int index = -1;
        uint64_t state = 0;
    };
    std::array<RecentSample, kBatchSamples> recent_;

    static constexpr uint64_t kModulus = 2147483647, kMultiplier = 16807;
    // 16807^n mod (2^31 − 1): tabulated for the first 1024 dimensions (4 KB,
    // at compile time), by squaring beyond.
    static constexpr int kTabulatedPowers = 1024;
    static constexpr uint64_t powerBySquaring(uint64_t n) {
        uint64_t result = 1, base = kMultiplier;
        for (; n > 0; n >>= 1, base = base * base % kModulus)
            if (n & 1) result = result * base % kModulus;
        return result;
    }
    static constexpr std::array<uint32_t, kTabulatedPowers> kPowers = [] {
        std::array<uint32_t, kTabulatedPowers> t{};
        uint64_t power = 1;
        for (auto& entry : t) entry = uint32_t(power), power = power * kMultiplier % kModulus;
        return t;
    }();
    static uint64_t multiplierPower(int n) {
        return n < kTabulatedPowers ? kPowers[size_t(n)] : powerBySquaring(uint64_t(n));
    }

    int spp_;
    uint64_t seed_;
    Vec2i pixel_{-1, -1};
    int index_ = -1;
    int position_ = 0;  // engine steps since the sample's seeding
    MinimalStandardEngine engine_;
    std::uniform_real_distribution<float> distribution_{0.0f, 1.0f};
};

}  // namespace pathlab
