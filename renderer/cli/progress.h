// A progress bar with ETA on stderr, redrawn by its own thread a few times a
// second so that render threads only bump an atomic counter per tile.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <thread>

namespace kappa {

class ProgressBar {
 public:
  explicit ProgressBar(bool enabled);
  ~ProgressBar();

  void update(std::size_t done, std::size_t total) {
    m_done.store(done, std::memory_order_relaxed);
    m_total.store(total, std::memory_order_relaxed);
  }
  /// Draws the final state and ends the line.
  void finish();

 private:
  void draw(bool final_line) const;

  bool m_enabled;
  std::atomic<std::size_t> m_done{0}, m_total{0};
  std::mutex m_mutex;
  std::condition_variable m_wake;
  bool m_stop = false;
  std::thread m_thread;
  double m_start = 0;
};

}  // namespace kappa
