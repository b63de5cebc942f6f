// A progress line on stderr for a terminal: the phase ("reading dragon.obj",
// "grid 64x64x64: filling cells", "rendering"), a bar when the size is known,
// the time and an ETA. A new phase is drawn when it begins; then its own
// thread redraws every 250 ms from the TaskProgress the workers bump, so the
// workers never wait for the terminal.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <thread>

#include "core/task_progress.h"

namespace kappa {

class ProgressBar {
 public:
  /// Draws nothing unless `enabled` (stderr a terminal and not --quiet).
  explicit ProgressBar(bool enabled);
  /// Erases the line unless finish() kept it: a load or build leaves no
  /// trace, and an error message starts on a clean line.
  ~ProgressBar();

  /// What the workers report to; null when nothing is drawn, so they skip it.
  TaskProgress* task() { return m_enabled ? &m_task : nullptr; }
  void update(std::size_t done, std::size_t total) { m_task.set(done, total); }
  /// Draws the final state and ends the line.
  void finish();

 private:
  void stop();
  void draw(const TaskProgress::Snapshot& state, bool final_line);

  bool m_enabled;
  TaskProgress m_task;
  std::mutex m_mutex;
  std::condition_variable m_wake;
  bool m_stop = false;
  std::thread m_thread;
  std::uint64_t m_drawn_generation = ~std::uint64_t(0);
  double m_phase_start = 0;
};

/// Whether to draw progress: on a terminal, unless --quiet.
bool progress_wanted(bool quiet);

/// f(TaskProgress*) under a progress line that is erased when f returns or
/// throws: for loading and building, which leave no trace on the terminal.
template <typename F>
auto with_progress(bool enabled, F&& f) {
  ProgressBar bar(enabled);
  return f(bar.task());
}

}  // namespace kappa
