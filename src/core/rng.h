// PCG32 (O'Neill 2014, "PCG: A Family of Simple Fast Space-Efficient
// Statistically Good Algorithms for Random Number Generation"): 64-bit LCG state,
// XSH-RR output. Used by the independent sampler and for seeded permutations.
#pragma once

#include <cstdint>

#include "core/math.h"

namespace pathlab {

class Pcg32 {
  public:
    static constexpr uint64_t kDefaultState = 0x853c49e6748fea9bULL;
    static constexpr uint64_t kDefaultStream = 0xda3e39cb94b95bdbULL;
    static constexpr uint64_t kMultiplier = 0x5851f42d4c957f2dULL;

    Pcg32() = default;
    Pcg32(uint64_t sequenceIndex, uint64_t offset) { setSequence(sequenceIndex, offset); }

    // Selects one of 2^63 streams and a starting offset within it.
    void setSequence(uint64_t sequenceIndex, uint64_t offset) {
        state_ = 0u;
        inc_ = (sequenceIndex << 1u) | 1u;
        nextUInt();
        state_ += offset;
        nextUInt();
    }

    uint32_t nextUInt() {
        const uint64_t old = state_;
        state_ = old * kMultiplier + inc_;
        const auto xorShifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
        const auto rot = static_cast<uint32_t>(old >> 59u);
        return (xorShifted >> rot) | (xorShifted << ((~rot + 1u) & 31));
    }

    // Uniform in [0, bound) without modulo bias (Lemire's rejection is overkill here;
    // the classic threshold method keeps the stream position deterministic per call count).
    uint32_t nextUInt(uint32_t bound) {
        const uint32_t threshold = (~bound + 1u) % bound;
        for (;;) {
            const uint32_t r = nextUInt();
            if (r >= threshold) return r % bound;
        }
    }

    // Uniform float in [0,1): 24 random mantissa bits... via multiply by 2^-32,
    // clamped so rounding can never produce 1.
    float nextFloat() {
        const float v = static_cast<float>(nextUInt()) * 0x1p-32f;
        return v < kOneMinusEpsilon ? v : kOneMinusEpsilon;
    }

    // A jump by a fixed number of steps, precomputed: the LCG advanced by delta
    // is state ↦ multiplier·state + increment·offsetFactor, and both factors
    // depend only on delta (the increment enters linearly).
    struct Jump {
        uint64_t multiplier, offsetFactor;
    };
    static constexpr Jump jump(uint64_t delta) {
        uint64_t curMult = kMultiplier, curPlus = 1u, accMult = 1u, accPlus = 0u;
        for (; delta > 0; delta /= 2) {
            if (delta & 1) {
                accMult *= curMult;
                accPlus = accPlus * curMult + curPlus;
            }
            curPlus = (curMult + 1) * curPlus;
            curMult *= curMult;
        }
        return {accMult, accPlus};
    }
    void advance(const Jump& j) { state_ = j.multiplier * state_ + inc_ * j.offsetFactor; }

    // Jumps the generator by delta steps in O(log delta) (Brown 1994, "Random
    // Number Generation with Arbitrary Strides").
    void advance(int64_t idelta) {
        uint64_t curMult = kMultiplier, curPlus = inc_, accMult = 1u, accPlus = 0u;
        auto delta = static_cast<uint64_t>(idelta);
        while (delta > 0) {
            if (delta & 1) {
                accMult *= curMult;
                accPlus = accPlus * curMult + curPlus;
            }
            curPlus = (curMult + 1) * curPlus;
            curMult *= curMult;
            delta /= 2;
        }
        state_ = accMult * state_ + accPlus;
    }

  private:
    uint64_t state_ = kDefaultState;
    uint64_t inc_ = kDefaultStream;
};

}  // namespace pathlab
