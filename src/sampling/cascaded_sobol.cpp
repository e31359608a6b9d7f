#include "sampling/cascaded_sobol.h"

namespace pathlab {

float CascadedSobolSampler::definition(Vec2i pixel, uint64_t seed, int spp, uint32_t index,
                                       int dim) {
    const uint64_t pixelHash = hashValues(pixel.x, pixel.y, seed);
    const uint32_t mask = indexMask(spp);
    // Sobol' dimension 1 from its generator matrix's columns (Joe–Kuo), not
    // from the superset transform the draws use.
    const uint32_t* column = sobolMatrices() + kSobolMatrixColumns;
    uint32_t x = owenScramble(reverseBits32(index), seedOf(pixelHash, 0));
    for (int j = 0; j < dim; ++j) {
        // The m-bit index a whose van der Corput value is x's top m bits.
        uint32_t a = reverseBits32(x) & mask, sobol1 = 0;
        for (; a != 0; a &= a - 1) sobol1 ^= column[__builtin_ctz(a)];
        x = owenScramble(sobol1, seedOf(pixelHash, j + 1));
    }
    return fixedPointToFloat(x);
}

}  // namespace pathlab
