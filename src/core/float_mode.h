// Flush-to-zero and denormals-are-zero for the calling thread, while in scope.
//
// Embree asks for both modes in every thread that traces rays: its start-up
// check (device config "verbose=1") warns that without them "this can have a
// severe performance impact", as denormal operands in traversal arithmetic
// take slow microcode paths. Set at the start of each rendering task and
// restored after it, the mode holds for every pixel whichever thread renders
// it, so images still do not depend on the thread count.
#pragma once

#if defined(__SSE__) || defined(__x86_64__)
#include <xmmintrin.h>
#define PATHLAB_HAS_MXCSR 1
#endif

namespace pathlab {

class ScopedFlushDenormals {
  public:
#ifdef PATHLAB_HAS_MXCSR
    ScopedFlushDenormals() : saved_(_mm_getcsr()) {
        _mm_setcsr(saved_ | kFlushToZero | kDenormalsAreZero);
    }
    ~ScopedFlushDenormals() {
        _mm_setcsr(saved_);
    }
#endif
    ScopedFlushDenormals(const ScopedFlushDenormals&) = delete;
    ScopedFlushDenormals& operator=(const ScopedFlushDenormals&) = delete;

  private:
#ifdef PATHLAB_HAS_MXCSR
    static constexpr unsigned kFlushToZero = 0x8000;       // MXCSR bit 15
    static constexpr unsigned kDenormalsAreZero = 0x0040;  // MXCSR bit 6
    unsigned saved_;
#endif
};

}  // namespace pathlab
