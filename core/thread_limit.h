// --threads, applied once: a command opens one ThreadLimit before it loads
// and builds, so the grid's parallel build, casts and the render all run with
// at most that many TBB workers. Nothing below a command sets a limit of its
// own; what sizes per-thread memory asks active_threads(). Here, in the
// lowest library, because every parallel loop (accel, stats, renderer) reads it.
#pragma once

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstddef>
#include <optional>

namespace kappa {

class ThreadLimit {
 public:
  /// `threads` > 0 limits TBB to that many workers until the scope ends; 0
  /// leaves every core.
  explicit ThreadLimit(int threads) {
    if (threads > 0) m_control.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  }

 private:
  std::optional<tbb::global_control> m_control;
};

/// How many threads a parallel loop started here can run at once: the
/// innermost limit in force, within the current arena's concurrency.
inline int active_threads() {
  const std::size_t limit = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  return int(std::min<std::size_t>(limit, std::size_t(tbb::this_task_arena::max_concurrency())));
}

}  // namespace kappa
