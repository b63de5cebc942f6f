// Kappa's parallel loops: tbb::parallel_for, and in a ThreadSanitizer build
// the happens-before edges TBB provides that TSan cannot see. Debian's libtbb
// is not built for TSan: a task's spawn and the loop's join synchronise
// through atomics and futexes inside the library, so without these edges every
// loop whose body reads what the caller wrote before it (or whose caller reads
// what the bodies wrote) is reported as a race. In other builds the wrappers
// are tbb::parallel_for itself.
//
// The edges go through one sync object: the caller releases it before the
// loop, each body acquires it on entry and releases it on exit, and the caller
// acquires it after the join. Bodies that run at the same time still race in
// TSan's eyes (each acquired before the other released); one body that ends
// before another starts on another thread is ordered after it, which hides a
// race between them that timing alone avoided.
#pragma once

#include <tbb/parallel_for.h>

#if defined(__SANITIZE_THREAD__)
#define KAPPA_TSAN 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define KAPPA_TSAN 1
#endif
#endif

#ifdef KAPPA_TSAN
extern "C" void __tsan_acquire(void* addr);
extern "C" void __tsan_release(void* addr);
#endif

namespace kappa {

#ifdef KAPPA_TSAN
namespace detail {
inline char tbb_sync;
}
/// What TBB's join (or a library's own TBB loop ending) makes visible.
inline void tbb_acquire() { __tsan_acquire(&detail::tbb_sync); }
/// What a task (or a library's callback on a TBB worker) has written.
inline void tbb_release() { __tsan_release(&detail::tbb_sync); }
#else
inline void tbb_acquire() {}
inline void tbb_release() {}
#endif

/// body(i) for i in [first, last), as tbb::parallel_for.
template <typename Index, typename Body>
void parallel_for(Index first, Index last, const Body& body) {
#ifdef KAPPA_TSAN
  tbb_release();
  tbb::parallel_for(first, last, [&](Index i) {
    tbb_acquire();
    body(i);
    tbb_release();
  });
  tbb_acquire();
#else
  tbb::parallel_for(first, last, body);
#endif
}

/// body(subrange) over a tbb::blocked_range, as tbb::parallel_for.
template <typename Range, typename Body>
void parallel_for(const Range& range, const Body& body) {
#ifdef KAPPA_TSAN
  tbb_release();
  tbb::parallel_for(range, [&](const Range& sub) {
    tbb_acquire();
    body(sub);
    tbb_release();
  });
  tbb_acquire();
#else
  tbb::parallel_for(range, body);
#endif
}

}  // namespace kappa
