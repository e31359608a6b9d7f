// A position in a PCG32 stream laid out as consecutive blocks of kStride draws,
// one block per pixel sample: value `dim` of sample `index` is draw
// index·kStride + dim of the stream picked by a hashed key (pixel, seed, …).
//
// Samplers restart at every path vertex, and jumping from the stream's start
// each time costs O(log n) multiplies; the cursor instead keeps the current
// sample's block start, moves from one sample's block to the next with one
// precomputed affine jump, and computes each draw from the block start with a
// tabulated jump. The values are exactly those of the plain jump.
#pragma once

#include <array>

#include "core/rng.h"
#include "sampling/sampler.h"

namespace pathlab {

class PcgSampleCursor {
  public:
    // Draws reserved per sample: 2^16 is far beyond any path (7 per bounce).
    static constexpr int64_t kStride = 65536;

    void seek(uint64_t key, int index, int dim) {
        if (key != key_ || !started_) {
            key_ = key;
            started_ = true;
            streamStart_.setSequence(key, 0);
            index_ = -1;
            for (RecentSample& r : recent_) r.index = -1;
        }
        if (index != index_) startSample(index);
        position_ = dim;
    }
    // Draw position_ of the sample's block, from the block's start by a
    // tabulated jump: state_d = A_d·s + inc·B_d. No draw waits for the one
    // before it, as it would if the generator were stepped from draw to draw:
    // that chain of 64-bit multiplies lies on the path's critical path.
    float nextFloat() {
        const int64_t d = position_++;
        Pcg32 draw = sampleStart_;
        if (d < kTabulatedDraws)
            draw.advance(kDrawJumps[size_t(d)]);
        else
            draw.advance(d);
        return draw.nextFloat();
    }

  private:
    // Out of line: the renderer inlines seek into every path vertex, and this
    // part runs only when the sample changes.
    [[gnu::noinline]] void startSample(int index) {
        RecentSample& recent = recent_[size_t(index) % recent_.size()];
        if (recent.index == index) {
            sampleStart_ = recent.start;
        } else {
            if (index == index_ + 1 && index_ >= 0) {
                sampleStart_.advance(kSampleJump);
            } else {
                sampleStart_ = streamStart_;
                sampleStart_.advance(int64_t(index) * kStride);
            }
            recent = {index, sampleStart_};
        }
        index_ = index;
    }

    static constexpr Pcg32::Jump kSampleJump = Pcg32::jump(kStride);
    // The jumps to a block's first kTabulatedDraws draws (16 KB, computed at
    // compile time).
    static constexpr int64_t kTabulatedDraws = 1024;
    static constexpr std::array<Pcg32::Jump, kTabulatedDraws> kDrawJumps = [] {
        std::array<Pcg32::Jump, kTabulatedDraws> t{};
        for (size_t d = 0; d < t.size(); ++d) t[d] = Pcg32::jump(d);
        return t;
    }();

    // The block starts of the last kBatchSamples samples: the renderer traces
    // a batch's paths together, a bounce of each in turn, so the cursor
    // returns to the batch's first sample at every bounce.
    struct RecentSample {
        int index = -1;
        Pcg32 start;
    };
    std::array<RecentSample, kBatchSamples> recent_;
    uint64_t key_ = 0;
    bool started_ = false;
    int index_ = -1;
    int64_t position_ = 0;  // the next draw's offset in the current sample's block
    Pcg32 streamStart_, sampleStart_;
};

}  // namespace pathlab
