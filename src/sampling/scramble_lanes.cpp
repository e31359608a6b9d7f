#include "sampling/scramble_lanes.h"

#include "sampling/lowdiscrepancy.h"
#include "sampling/sampler.h"

namespace pathlab {

// Every function is compiled twice, for the x86-64 baseline and for AVX2, and
// the processor's best is chosen at run time (as diffuse_batch.cpp does; not
// with target_clones, whose ifunc resolvers run before ThreadSanitizer's
// runtime is up and crash the instrumented build). Integer operations and an
// exact int-to-float conversion: the same bits from both.
namespace baseline {
#include "sampling/scramble_lanes_kernels.inc"
}  // namespace baseline

#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx2"))), apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx2")
#endif
namespace avx2 {
#include "sampling/scramble_lanes_kernels.inc"
}  // namespace avx2
#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC pop_options
#endif

namespace {
bool hasAvx2() {
    static const bool avx2 = __builtin_cpu_supports("avx2");
    return avx2;
}
}  // namespace

void owenSobolLanes1D(const uint32_t* index, uint32_t indexSeed, uint32_t valueSeed, float* x) {
    if (hasAvx2()) return avx2::owenSobol1D(index, indexSeed, valueSeed, x);
    baseline::owenSobol1D(index, indexSeed, valueSeed, x);
}

void owenSobolLanes2D(const uint32_t* index, uint32_t indexSeed, uint32_t xSeed, uint32_t ySeed,
                      float* x, float* y) {
    if (hasAvx2()) return avx2::owenSobol2D(index, indexSeed, xSeed, ySeed, x, y);
    baseline::owenSobol2D(index, indexSeed, xSeed, ySeed, x, y);
}

}  // namespace pathlab
