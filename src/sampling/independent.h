// `independent`: uniform random numbers from PCG32, no correlation between
// dimensions or samples — the Monte Carlo baseline every other sampler is
// compared with. The PCG32 stream is chosen by hashing (pixel, seed) and the
// position in it by (sample index, dimension), so any sample can be drawn
// without drawing its predecessors (pcg_cursor.h keeps that cheap).
#pragma once

#include "core/hash.h"
#include "sampling/pcg_cursor.h"
#include "sampling/sampler.h"

namespace pathlab {

class IndependentSampler {
  public:
    static constexpr int64_t kStreamStride = PcgSampleCursor::kStride;

    explicit IndependentSampler(const SamplerConfig& c) : spp_(c.samplesPerPixel), seed_(c.seed) {}

    int samplesPerPixel() const { return spp_; }
    void startPixelSample(Vec2i p, int index, int dim) {
        if (p.x != pixel_.x || p.y != pixel_.y) pixel_ = p, key_ = hashValues(p.x, p.y, seed_);
        cursor_.seek(key_, index, dim);
    }
    float get1D() { return cursor_.nextFloat(); }
    Vec2f get2D() {
        const float a = cursor_.nextFloat();
        return {a, cursor_.nextFloat()};
    }
    Vec2f getPixel2D() { return get2D(); }

  private:
    int spp_;
    uint64_t seed_;
    Vec2i pixel_{-1, -1};
    uint64_t key_ = 0;
    PcgSampleCursor cursor_;
};

}  // namespace pathlab
