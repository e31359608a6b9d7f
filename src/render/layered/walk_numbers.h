// The random numbers of a stochastic BSDF's random walk (the layered BSDF of
// layered_bsdf.h draws an unbounded, data-dependent count of them). A walk
// reads them one at a time from a WalkNumbers stream: in the renderer the
// first kWalkSamplerDimensions come from the sampler, at dimensions of the
// vertex's own layered block (docs/rendering.md, "Dimension layout"), and the
// rest from a PCG32 stream seeded by what the sampler gave; in tests and
// other callers without a sampler, from PCG32 seeded by a hash of the
// directions, as pbrt-v4's LayeredBxDF seeds its RNG.
#pragma once

#include <bit>
#include <cstdint>

#include "core/hash.h"
#include "core/math.h"
#include "core/rng.h"

namespace pathlab {

class WalkNumbers {
  public:
    virtual ~WalkNumbers() = default;
    // The next number, in [0, 1).
    virtual float next() = 0;
};

// Every number from PCG32.
class PcgWalkNumbers final : public WalkNumbers {
  public:
    explicit PcgWalkNumbers(uint64_t seed) : rng_(seed, mixBits(seed ^ 0x9e3779b97f4a7c15ULL)) {}
    float next() override { return rng_.nextFloat(); }

  private:
    Pcg32 rng_;
};

// pbrt-v4's seeding of a layered walk without a sampler: a hash of the
// directions it is asked about (and of c, a third number).
inline PcgWalkNumbers walkFromDirections(Vec3f a, Vec3f b, float c = 0) {
    return PcgWalkNumbers(hashValues(std::bit_cast<uint32_t>(a.x), std::bit_cast<uint32_t>(a.y),
                                     std::bit_cast<uint32_t>(a.z), std::bit_cast<uint32_t>(b.x),
                                     std::bit_cast<uint32_t>(b.y), std::bit_cast<uint32_t>(b.z),
                                     std::bit_cast<uint32_t>(c)));
}

// How many numbers of one walk come from the sampler.
inline constexpr int kWalkSamplerDimensions = 16;

// The first kWalkSamplerDimensions numbers from `draw(i)` (the sampler at the
// walk's i-th dimension), then PCG32 seeded by a hash of those numbers, so
// the continuation is a pure function of (pixel, index, dimension, seed) too.
template <typename Draw>
class SamplerWalkNumbers final : public WalkNumbers {
  public:
    explicit SamplerWalkNumbers(Draw draw) : draw_(draw) {}
    float next() override {
        if (count_ < kWalkSamplerDimensions) {
            const float u = draw_(count_++);
            hash_ = mixBits(hash_ ^ std::bit_cast<uint32_t>(u));
            return u;
        }
        if (count_++ == kWalkSamplerDimensions) rng_.setSequence(hash_, mixBits(hash_ + 1));
        return rng_.nextFloat();
    }

  private:
    Draw draw_;
    int count_ = 0;
    uint64_t hash_ = 0x6a09e667f3bcc909ULL;
    Pcg32 rng_;
};

}  // namespace pathlab
