// Happens-before edges for ThreadSanitizer that it cannot see by itself.
// oneTBB's scheduler lives in an uninstrumented shared library, so TSan misses
// what tbb::parallel_for guarantees: everything before the call happens before
// every task, and every task happens before the call returns. Without these
// edges it reports the caller's data, read by the tasks, as racy. They model
// exactly that guarantee and nothing more, so races between tasks are still
// reported. Compiled to nothing unless TSan is on.
#pragma once

#if defined(__SANITIZE_THREAD__)
#define PATHLAB_TSAN 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define PATHLAB_TSAN 1
#endif
#endif

#ifdef PATHLAB_TSAN
#include <sanitizer/tsan_interface.h>
#endif

namespace pathlab {

// Publishes this thread's prior writes to whoever acquires `token`.
inline void happensBefore([[maybe_unused]] const void* token) {
#ifdef PATHLAB_TSAN
    __tsan_release(const_cast<void*>(token));
#endif
}

// Makes writes published on `token` visible to this thread.
inline void happensAfter([[maybe_unused]] const void* token) {
#ifdef PATHLAB_TSAN
    __tsan_acquire(const_cast<void*>(token));
#endif
}

}  // namespace pathlab
