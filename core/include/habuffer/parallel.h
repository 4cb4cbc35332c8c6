// Fork-join over indices 0..n-1 on oneTBB, visible to ThreadSanitizer.
//
// Debian's libtbb is not instrumented, so ThreadSanitizer cannot see that a
// parallel_for's tasks start after the caller's writes and finish before the
// caller continues, and it reports those accesses as races. Under
// -fsanitize=thread the fork and the join are announced explicitly; in every
// other build the annotations compile to nothing.
#pragma once

#include <cstdint>

#include <tbb/parallel_for.h>

#if defined(__SANITIZE_THREAD__)
#include <sanitizer/tsan_interface.h>
#define HABUFFER_TSAN_RELEASE(p) __tsan_release(p)
#define HABUFFER_TSAN_ACQUIRE(p) __tsan_acquire(p)
#else
#define HABUFFER_TSAN_RELEASE(p) ((void)(p))
#define HABUFFER_TSAN_ACQUIRE(p) ((void)(p))
#endif

namespace habuffer {

// Calls body(i) for every i in [0, n), one task per index (static split), in
// the current task arena; returns when all have finished.
template <class Index, class Body>
void fork_join(Index n, Body&& body) {
  int sync = 0;  // only its address matters: the happens-before token
  HABUFFER_TSAN_RELEASE(&sync);
  tbb::parallel_for(
      Index{0}, n,
      [&](Index i) {
        HABUFFER_TSAN_ACQUIRE(&sync);
        body(i);
        HABUFFER_TSAN_RELEASE(&sync);
      },
      tbb::static_partitioner());
  HABUFFER_TSAN_ACQUIRE(&sync);
}

}  // namespace habuffer
