// Kappa's parallel loops. In every build but ThreadSanitizer's they are
// tbb::parallel_for itself. Under TSan they run on plain std::threads instead:
// Debian's libtbb is not built for TSan, so a task's spawn and the loop's join
// synchronise through atomics and futexes TSan cannot see, and TBB's header
// code inlined into Kappa (its partitioner's tree nodes, the join's wait
// counters, the task objects) is reported racing with that hidden code. With
// threads TSan sees every edge (thread start, thread join, the atomic chunk
// counter) and needs no suppression for Kappa's loops: what it reports is
// Kappa's own race. The loop bodies are the same code in both builds, and
// bodies never depend on how the range is split (images are bitwise the same
// whatever the thread count), so the TSan build checks the code that ships.
//
// The thread count is active_threads(): --threads and a bench arena bound
// these loops as they bound TBB's.
#pragma once

#include "core/thread_limit.h"

#include <tbb/blocked_range.h>
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

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>
#endif

namespace kappa {

// A library that runs Kappa's callbacks on its own TBB workers (Embree's BVH
// build calls the progress monitor there) synchronises with the caller inside
// libtbb, which TSan cannot see: the callback calls tbb_release() after it
// writes, and the caller tbb_acquire() when the library returns.
#ifdef KAPPA_TSAN
namespace detail {
inline char tbb_sync;
}
inline void tbb_acquire() { __tsan_acquire(&detail::tbb_sync); }
inline void tbb_release() { __tsan_release(&detail::tbb_sync); }
#else
inline void tbb_acquire() {}
inline void tbb_release() {}
#endif

#ifdef KAPPA_TSAN
namespace detail {

/// run_chunk(begin, end) over [0, n) in chunks of at least `grain` items,
/// taken in turn by active_threads() threads (the caller is one of them).
/// The first exception a chunk throws stops the others taking chunks and is
/// rethrown here after the join, as tbb::parallel_for rethrows it.
template <typename RunChunk>
void run_on_threads(std::uint64_t n, std::uint64_t grain, const RunChunk& run_chunk) {
  if (n == 0) return;
  const std::uint64_t threads = std::uint64_t(std::max(1, active_threads()));
  // Several chunks per thread so a slow chunk does not leave a thread idle.
  const std::uint64_t chunk = std::max<std::uint64_t>({grain, 1, n / (threads * 8)});
  std::atomic<std::uint64_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex error_mutex;
  const auto work = [&] {
    try {
      for (;;) {
        if (failed.load(std::memory_order_relaxed)) return;
        const std::uint64_t begin = next.fetch_add(chunk, std::memory_order_relaxed);
        if (begin >= n) return;
        run_chunk(begin, std::min(n, begin + chunk));
      }
    } catch (...) {
      const std::lock_guard lock(error_mutex);
      if (!error) error = std::current_exception();
      failed.store(true, std::memory_order_relaxed);
    }
  };
  std::vector<std::thread> helpers;
  const std::uint64_t wanted = std::min(threads, (n + chunk - 1) / chunk);
  for (std::uint64_t t = 1; t < wanted; ++t) helpers.emplace_back(work);
  work();
  for (std::thread& helper : helpers) helper.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace detail
#endif

/// body(i) for i in [first, last), as tbb::parallel_for.
template <typename Index, typename Body>
void parallel_for(Index first, Index last, const Body& body) {
#ifdef KAPPA_TSAN
  if (!(first < last)) return;
  detail::run_on_threads(std::uint64_t(last - first), 1, [&](std::uint64_t begin, std::uint64_t end) {
    for (std::uint64_t i = begin; i < end; ++i) body(Index(first + Index(i)));
  });
#else
  tbb::parallel_for(first, last, body);
#endif
}

/// body(subrange) over a tbb::blocked_range, as tbb::parallel_for.
template <typename Value, typename Body>
void parallel_for(const tbb::blocked_range<Value>& range, const Body& body) {
#ifdef KAPPA_TSAN
  const Value first = range.begin();
  detail::run_on_threads(std::uint64_t(range.size()), std::uint64_t(range.grainsize()),
                         [&](std::uint64_t begin, std::uint64_t end) {
                           body(tbb::blocked_range<Value>(Value(first + Value(begin)), Value(first + Value(end)),
                                                          range.grainsize()));
                         });
#else
  tbb::parallel_for(range, body);
#endif
}

}  // namespace kappa
