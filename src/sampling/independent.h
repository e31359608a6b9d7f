// `independent`: uniform random numbers from PCG32, no correlation between
// dimensions or samples — the Monte Carlo baseline every other sampler is
// compared with. The PCG32 stream is chosen by hashing (pixel, seed) and the
// position in it by (sample index, dimension), so any sample can be drawn
// without drawing its predecessors.
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

    explicit IndependentSampler(const SamplerConfig& c) : spp_(c.samplesPerPixel), seed_(c.seed) {}

    int samplesPerPixel() const { return spp_; }
    void startPixelSample(Vec2i p, int index, int dim) {
        rng_.setSequence(hashValues(p.x, p.y, seed_), 0);
        rng_.advance(int64_t(index) * kStreamStride + dim);
    }
    float get1D() { return rng_.nextFloat(); }
    Vec2f get2D() {
        const float a = rng_.nextFloat();
        return {a, rng_.nextFloat()};
    }
    Vec2f getPixel2D() { return get2D(); }

  private:
    int spp_;
    uint64_t seed_;
    Pcg32 rng_;
};

}  // namespace pathlab
