// Integer hashing used to derive deterministic, independent seeds from
// (pixel, sample index, dimension, user seed) — so results never depend on
// which thread renders what.
#pragma once

#include <cstdint>
#include <cstring>

namespace pathlab {

// mixBits's steps before its last, for a uint64_t or a GCC vector of them:
// the lane kernels (sobol.cpp, halton_lanes_kernels.inc) hash with the same
// code, compiled there for their instruction set (a 64-bit lane multiply is
// one instruction with AVX-512DQ, three 32-bit ones with AVX2 alone). In
// place, so that no vector is passed by value outside those regions.
template <typename U>
[[gnu::always_inline]] constexpr void mixBitsMultiplySteps(U& v) {
    v ^= v >> 31;
    v *= 0x7fb5d329728ea185ULL;
    v ^= v >> 27;
    v *= 0x81dadef4bc2dd44dULL;
}

// 64-bit finaliser (Stafford's "Mix13" variant of MurmurHash3's fmix64).
constexpr uint64_t mixBits(uint64_t v) {
    mixBitsMultiplySteps(v);
    return v ^ (v >> 33);
}

// mixBits(v) >> 32 without mixBits's last step: v ^= v >> 33 leaves bits
// 32–63 as they are, since v >> 33 is below 2^31. (Owen's tree rotations use
// only the top half of each node's hash; the step saved is one of eight.)
constexpr uint32_t mixBitsHigh32(uint64_t v) {
    mixBitsMultiplySteps(v);
    return uint32_t(v >> 32);
}

// Hashes any number of integral arguments into 64 bits, order-sensitive.
template <typename... Args>
constexpr uint64_t hashValues(Args... args) {
    uint64_t h = 0x9e3779b97f4a7c15ULL;
    ((h = mixBits(h ^ (static_cast<uint64_t>(args) + 0x632be59bd9b4e019ULL))), ...);
    return h;
}

// 32-bit integer hash (Wellons' "lowbias32"), cheap enough for per-sample use.
constexpr uint32_t hash32(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

}  // namespace pathlab
