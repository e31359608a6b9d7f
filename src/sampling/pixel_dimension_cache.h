// Values that depend on the pixel and the dimension only — a permutation's or a
// scramble's seed — kept for the pixel's other samples. The first kDimensions
// dimensions are kept (a depth-8 path draws 58); deeper ones are computed each
// time. clear() when the pixel changes.
#pragma once

#include <cstdint>

namespace pathlab {

template <class T, int kDimensions = 64>
class PixelDimensionCache {
    static_assert(kDimensions <= 64, "one valid bit per dimension in a uint64_t");

  public:
    void clear() { valid_ = 0; }
    // The value of dimension d: compute() the first time for this pixel.
    template <class Compute>
    [[gnu::always_inline]] T get(int d, Compute compute) {
        if (unsigned(d) >= unsigned(kDimensions)) return compute();
        if (!((valid_ >> d) & 1)) values_[d] = compute(), valid_ |= uint64_t(1) << d;
        return values_[d];
    }

  private:
    uint64_t valid_ = 0;  // bit d: values_[d] is the current pixel's
    T values_[kDimensions]{};
};

}  // namespace pathlab
