// Per-cell 64-bit counters that cost 4 bytes of memory traffic each.
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "zeroed_array.h"

namespace kappa {

/// 64-bit counters stored as 32-bit low words and, apart, the
/// carries into the high words: the high words' pages are never touched
/// unless a count passes 2^32, so a cell costs 4 bytes of memory traffic
/// instead of 8.
class SplitCounts {
 public:
  /// Memory per counter: a low word and its carry word.
  static constexpr std::size_t kBytesPerCount = 2 * sizeof(std::uint32_t);

  SplitCounts() = default;
  explicit SplitCounts(std::size_t n) : m_lo(n), m_hi(n) {}
  void increment(std::size_t i) {
    if (++m_lo[i] == 0) ++m_hi[i];
  }
  /// increment() on an array that other threads increment at the same time:
  /// relaxed atomics, since only the sums matter and they are read after the
  /// threads have joined. The thread that wraps a low word adds its carry.
  void increment_shared(std::size_t i) {
    if (std::atomic_ref<std::uint32_t>(m_lo[i]).fetch_add(1, std::memory_order_relaxed) == 0xFFFFFFFFu)
      std::atomic_ref<std::uint32_t>(m_hi[i]).fetch_add(1, std::memory_order_relaxed);
  }
  std::uint64_t at(std::size_t i) const { return (std::uint64_t(m_hi[i]) << 32) | m_lo[i]; }
  void add(std::size_t i, std::uint64_t v) {
    const std::uint64_t sum = at(i) + v;
    m_lo[i] = std::uint32_t(sum);
    m_hi[i] = std::uint32_t(sum >> 32);
  }
  void set(std::size_t i, std::uint64_t v) {
    m_lo[i] = std::uint32_t(v);
    m_hi[i] = std::uint32_t(v >> 32);
  }
  std::size_t size() const { return m_lo.size(); }
  std::vector<std::uint64_t> all() const {
    std::vector<std::uint64_t> v(size());
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = at(i);
    return v;
  }

 private:
  ZeroedArray<std::uint32_t> m_lo, m_hi;
};

}  // namespace kappa
