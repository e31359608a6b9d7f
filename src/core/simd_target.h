// Compiling a region of a file for AVX2 (or AVX-512), to be chosen at run time
// on the processors that have it. Each such file has a baseline x86-64 version
// of its kernels (the same code, or a scalar loop) and the SIMD ones inside
// PATHLAB_AVX2_BEGIN … PATHLAB_AVX2_END (or the AVX-512 pair), and dispatches
// on cpuHasAvx2() or bestSimdLevel(). Not with target_clones: its ifunc
// resolvers run before ThreadSanitizer's runtime is up and crash the
// instrumented build.
#pragma once

// GCC and Clang spell "compile this region for AVX2" differently. AVX2 alone,
// without FMA, so that no multiply-add is contracted and rounding stays that of
// the baseline code. The AVX-512 regions have FMA (every AVX-512 processor
// does) and may contract: in their users every multiply followed by an add is
// exact integer arithmetic in doubles, where a fused multiply-add rounds
// nothing, and halton_lanes.cpp's quotients are shown exact with it.
#if defined(__clang__)
#define PATHLAB_AVX2_BEGIN \
    _Pragma("clang attribute push(__attribute__((target(\"avx2\"))), apply_to = function)")
#define PATHLAB_AVX2_END _Pragma("clang attribute pop")
// clang-format off
#define PATHLAB_AVX512_BEGIN _Pragma("clang attribute push(__attribute__((target(\"avx2,fma,avx512f,avx512dq,avx512vl\"))), apply_to = function)")
// clang-format on
#define PATHLAB_AVX512_END _Pragma("clang attribute pop")
// clang-format off
#define PATHLAB_AVX512_VBMI_BEGIN _Pragma("clang attribute push(__attribute__((target(\"avx2,fma,avx512f,avx512dq,avx512vl,avx512bw,avx512vbmi\"))), apply_to = function)")
// clang-format on
#define PATHLAB_AVX512_VBMI_END _Pragma("clang attribute pop")
#else
#define PATHLAB_AVX2_BEGIN _Pragma("GCC push_options") _Pragma("GCC target(\"avx2\")")
#define PATHLAB_AVX2_END _Pragma("GCC pop_options")
#define PATHLAB_AVX512_BEGIN \
    _Pragma("GCC push_options") _Pragma("GCC target(\"avx2,fma,avx512f,avx512dq,avx512vl\")")
#define PATHLAB_AVX512_END _Pragma("GCC pop_options")
#define PATHLAB_AVX512_VBMI_BEGIN \
    _Pragma("GCC push_options")   \
        _Pragma("GCC target(\"avx2,fma,avx512f,avx512dq,avx512vl,avx512bw,avx512vbmi\")")
#define PATHLAB_AVX512_VBMI_END _Pragma("GCC pop_options")
#endif

namespace pathlab {

inline bool cpuHasAvx2() {
    static const bool avx2 = __builtin_cpu_supports("avx2");
    return avx2;
}

// The instruction sets a kernel may be compiled for, in order; Avx512 means
// AVX-512 F, DQ and VL, with AVX2; Avx512Vbmi adds BW and VBMI, whose byte
// permutes look up a table of up to 128 bytes held in two registers (Ice Lake,
// Zen 4 and later).
enum class SimdLevel { Baseline, Avx2, Avx512, Avx512Vbmi };

// The processor's level, asked once (bestSimdLevel), out of line: the lane
// draws ask bestSimdLevel on every call, and as a call of its own (two per
// draw) it was 0.5% of a halton-owen frame; inlined, it is a load and a branch.
[[gnu::cold, gnu::noinline]] inline SimdLevel detectSimdLevel() {
    if (!cpuHasAvx2()) return SimdLevel::Baseline;
    if (!__builtin_cpu_supports("avx512f") || !__builtin_cpu_supports("avx512dq") ||
        !__builtin_cpu_supports("avx512vl"))
        return SimdLevel::Avx2;
    return __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512vbmi")
               ? SimdLevel::Avx512Vbmi
               : SimdLevel::Avx512;
}

[[gnu::always_inline]] inline SimdLevel bestSimdLevel() {
    static const SimdLevel level = detectSimdLevel();
    return level;
}

// The best level the processor has, capped by `limit` (tests cap it to run
// each version of a kernel).
inline SimdLevel simdLevelUpTo(SimdLevel limit) {
    const SimdLevel best = bestSimdLevel();
    return limit < best ? limit : best;
}

}  // namespace pathlab
