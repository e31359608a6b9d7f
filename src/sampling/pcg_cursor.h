// A position in a PCG32 stream laid out as consecutive blocks of kStride draws,
// one block per pixel sample: value `dim` of sample `index` is draw
// index·kStride + dim of the stream picked by a hashed key (pixel, seed, …).
//
// Samplers restart at every path vertex, and jumping from the stream's start
// each time costs O(log n) multiplies; the cursor instead remembers where it is
// and steps forward when the request lies a little ahead in the same sample
// (the usual case), and moves from one sample's block to the next with one
// precomputed affine jump. The values are exactly those of the plain jump.
#pragma once

#include "core/rng.h"

namespace pathlab {

class PcgSampleCursor {
  public:
    // Draws reserved per sample: 2^16 is far beyond any path (7 per bounce).
    static constexpr int64_t kStride = 65536;
    // A forward gap up to this many draws is stepped rather than jumped.
    static constexpr int kMaxStep = 16;

    void seek(uint64_t key, int index, int dim) {
        if (key != key_ || !started_) {
            key_ = key;
            started_ = true;
            streamStart_.setSequence(key, 0);
            index_ = -1;
        }
        if (index != index_) {
            if (index == index_ + 1 && index_ >= 0) {
                sampleStart_.advance(kSampleJump);
            } else {
                sampleStart_ = streamStart_;
                sampleStart_.advance(int64_t(index) * kStride);
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
    float nextFloat() {
        ++position_;
        return rng_.nextFloat();
    }

  private:
    static constexpr Pcg32::Jump kSampleJump = Pcg32::jump(kStride);
    uint64_t key_ = 0;
    bool started_ = false;
    int index_ = -1;
    int position_ = 0;  // draws since the current sample's start
    Pcg32 streamStart_, sampleStart_, rng_;
};

}  // namespace pathlab
