// `independent`: uniform random numbers from PCG32, no correlation between
// dimensions or samples — the Monte Carlo baseline every other sampler is
// compared with. The PCG32 stream is chosen by hashing (pixel, seed) and the
// position in it by (sample index, dimension), so any sample can be drawn
// without drawing its predecessors.
//
// Positioning is the hot part: a path restarts the sampler at every vertex.
// Jumping from the stream's start costs O(log n) multiplies each time, so the
// sampler remembers where it is and steps forward when the next request lies
// ahead in the same sample (the usual case), and moves from one sample's start
// to the next with one precomputed affine jump. The values are exactly those of
// the plain jump.
#pragma once

#include "core/hash.h"
#include "core/rng.h"
#include "sampling/sampler.h"

namespace pathlab {

class IndependentSampler {
  public:
    // Dimensions reserved per sample within one pixel's stream: 2^16 is far
    // beyond any path (7 per bounce), so samples never overlap.
    static constexpr int64_t kStreamStride = 65536;
    // A forward gap up to this many draws is stepped rather than jumped.
    static constexpr int kMaxStep = 16;
    static constexpr Pcg32::Jump kSampleJump = Pcg32::jump(kStreamStride);

    explicit IndependentSampler(const SamplerConfig& c) : spp_(c.samplesPerPixel), seed_(c.seed) {}

    int samplesPerPixel() const { return spp_; }
    void startPixelSample(Vec2i p, int index, int dim) {
        if (p.x != pixel_.x || p.y != pixel_.y) {
            pixel_ = p;
            pixelStart_.setSequence(hashValues(p.x, p.y, seed_), 0);
            index_ = -1;
        }
        if (index != index_) {
            if (index == index_ + 1 && index_ >= 0) {
                sampleStart_.advance(kSampleJump);
            } else {
                sampleStart_ = pixelStart_;
                sampleStart_.advance(int64_t(index) * kStreamStride);
            }
            index_ = index;
            rng_ = sampleStart_;
            position_ = 0;
        }
        if (dim >= position_ && dim - position_ <= kMaxStep) {
            for (; position_ < dim; ++position_) rng_.nextUInt();
        } else {
            rng_ = sampleStart_;
            rng_.advance(dim);
            position_ = dim;
        }
    }
    float get1D() {
        ++position_;
        return rng_.nextFloat();
    }
    Vec2f get2D() {
        position_ += 2;
        const float a = rng_.nextFloat();
        return {a, rng_.nextFloat()};
    }
    Vec2f getPixel2D() { return get2D(); }

  private:
    int spp_;
    uint64_t seed_;
    Vec2i pixel_{-1, -1};
    int index_ = -1;
    int position_ = 0;  // draws since the current sample's start
    Pcg32 pixelStart_, sampleStart_, rng_;
};

}  // namespace pathlab
