// Compiling a region of a file for AVX2, to be chosen at run time on the
// processors that have it. Each such file compiles the same code twice — for
// the x86-64 baseline and inside PATHLAB_AVX2_BEGIN … PATHLAB_AVX2_END — and
// dispatches on cpuHasAvx2(). Not with target_clones: its ifunc resolvers run
// before ThreadSanitizer's runtime is up and crash the instrumented build.
#pragma once

// GCC and Clang spell "compile this region for AVX2" differently. AVX2 alone,
// without FMA, so that no multiply-add is contracted and rounding stays that of
// the baseline code.
#if defined(__clang__)
#define PATHLAB_AVX2_BEGIN \
    _Pragma("clang attribute push(__attribute__((target(\"avx2\"))), apply_to = function)")
#define PATHLAB_AVX2_END _Pragma("clang attribute pop")
#else
#define PATHLAB_AVX2_BEGIN _Pragma("GCC push_options") _Pragma("GCC target(\"avx2\")")
#define PATHLAB_AVX2_END _Pragma("GCC pop_options")
#endif

namespace pathlab {

inline bool cpuHasAvx2() {
    static const bool avx2 = __builtin_cpu_supports("avx2");
    return avx2;
}

}  // namespace pathlab
