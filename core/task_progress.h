// How far a long task (loading a mesh, building an accelerator, rendering)
// has got, for a display thread to poll. The workers only add to an atomic,
// once per chunk of work, so reporting costs nothing measurable; naming a
// new phase takes a lock and tells the observer (the display draws it at
// once, so even a phase of a millisecond is seen), a few times per run.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>

namespace kappa {

class TaskProgress {
 public:
  struct Snapshot {
    std::string phase;
    std::uint64_t done = 0, total = 0;  ///< total 0: size unknown
    std::uint64_t generation = 0;       ///< bumped by every begin()
  };

  /// Called by begin() with the new phase, on the caller's thread; set it
  /// before the work starts.
  void set_observer(std::function<void(const Snapshot&)> observer) { m_observer = std::move(observer); }

  /// Starts a phase of `total` units of work (0 if unknown).
  void begin(std::string phase, std::uint64_t total) {
    {
      std::lock_guard lock(m_mutex);
      m_phase = std::move(phase);
      m_done.store(0, std::memory_order_relaxed);
      m_total.store(total, std::memory_order_relaxed);
      ++m_generation;
    }
    if (m_observer) m_observer(snapshot());
  }
  /// Renames the current phase (a render's passes: "12 spp, relMSE 0.02")
  /// without starting a new one: its clock and ETA go on.
  void rename(std::string phase) {
    std::lock_guard lock(m_mutex);
    m_phase = std::move(phase);
  }
  /// Counts `units` more done; any thread.
  void advance(std::uint64_t units) { m_done.fetch_add(units, std::memory_order_relaxed); }
  /// Sets the state outright (for work that reports absolute progress).
  void set(std::uint64_t done, std::uint64_t total) {
    m_done.store(done, std::memory_order_relaxed);
    m_total.store(total, std::memory_order_relaxed);
  }

  Snapshot snapshot() const {
    std::lock_guard lock(m_mutex);
    return {m_phase, m_done.load(std::memory_order_relaxed), m_total.load(std::memory_order_relaxed), m_generation};
  }

 private:
  mutable std::mutex m_mutex;
  std::string m_phase;
  std::uint64_t m_generation = 0;
  std::atomic<std::uint64_t> m_done{0}, m_total{0};
  std::function<void(const Snapshot&)> m_observer;
};

/// The calls the loaders and builders make, for an optional display.
inline void begin_phase(TaskProgress* progress, std::string phase, std::uint64_t total) {
  if (progress) progress->begin(std::move(phase), total);
}
inline void advance(TaskProgress* progress, std::uint64_t units) {
  if (progress) progress->advance(units);
}

}  // namespace kappa
