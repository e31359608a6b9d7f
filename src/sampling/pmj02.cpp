#include "sampling/pmj02.h"

#include <algorithm>

#include "core/rng.h"

namespace pathlab {

Pmj02Tables::Pmj02Tables(int log2Size_, uint64_t seed) : log2Size(log2Size_) {
    const uint32_t size = uint32_t(1) << log2Size;
    const uint32_t* matrices = sobolMatrices();
    points.resize(size_t(2) * kInstances * size);
    for (int k = 0; k < kInstances; ++k) {
        // The random choices of one instance: a nested-scramble seed per axis.
        Pcg32 rng(hashValues(seed, k, 0x706d6a30u), 0);
        const uint32_t sx = rng.nextUInt(), sy = rng.nextUInt();
        for (uint32_t i = 0; i < size; ++i) {
            uint32_t* p = points.data() + 2 * ((size_t(k) << log2Size) + i);
            p[0] = owenScramble(sobolBits(matrices, i, 0), sx);
            p[1] = owenScramble(sobolBits(matrices, i, 1), sy);
        }
    }
}

Pmj02Sampler::Pmj02Sampler(const SamplerConfig& c) : spp_(c.samplesPerPixel), seed_(c.seed) {
    const int log2Size = std::min(24, log2Ceil(uint64_t(std::max(1, c.samplesPerPixel))));
    tables_ = std::make_shared<const Pmj02Tables>(log2Size, c.seed);
    log2Size_ = log2Size;
}

}  // namespace pathlab
