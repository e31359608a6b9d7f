// Integer hashing used to derive deterministic, independent seeds from
// (pixel, sample index, dimension, user seed) — so results never depend on
// which thread renders what.
#pragma once

#include <cstdint>
#include <cstring>

namespace pathlab {

// 64-bit finaliser (Stafford's "Mix13" variant of MurmurHash3's fmix64).
constexpr uint64_t mixBits(uint64_t v) {
    v ^= v >> 31;
    v *= 0x7fb5d329728ea185ULL;
    v ^= v >> 27;
    v *= 0x81dadef4bc2dd44dULL;
    v ^= v >> 33;
    return v;
}

// mixBits(v) >> 32 without mixBits's last step: v ^= v >> 33 leaves bits
// 32–63 as they are, since v >> 33 is below 2^31. (Owen's tree rotations use
// only the top half of each node's hash; the step saved is one of eight.)
constexpr uint32_t mixBitsHigh32(uint64_t v) {
    v ^= v >> 31;
    v *= 0x7fb5d329728ea185ULL;
    v ^= v >> 27;
    v *= 0x81dadef4bc2dd44dULL;
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
