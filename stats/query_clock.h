// The clock that times each visibility query when statistics are on: the
// CPU's time-stamp counter where it ticks at a constant rate (rdtsc costs a
// few nanoseconds, against tens for a steady_clock read through the vDSO),
// steady_clock where /proc/cpuinfo lacks constant_tsc. Every query is timed
// (sampling one in 64 let a single descheduled or page-faulting query move a
// class 30x between identical runs); a query is capped at kQueryCap, which no
// walk of a valid scene approaches, and the capped ones are counted.
#pragma once

#include <cstdint>

#if defined(__x86_64__) || defined(__i386__)
#include <x86intrin.h>
#endif

namespace kappa {

class QueryClock {
 public:
  /// One query longer than this was interrupted (descheduled, a page fault):
  /// it counts as this long, and as capped.
  static constexpr double kQueryCapSeconds = 100e-6;

  /// The process's clock, set up (and its tick rate measured, about 25 ms) on
  /// first use: call it before anything timed.
  static const QueryClock& get();

  /// Ticks: TSC cycles, or steady_clock nanoseconds.
  std::uint64_t now() const {
#if defined(__x86_64__) || defined(__i386__)
    if (m_tsc) return __rdtsc();
#endif
    return steady_ns();
  }
  /// The ticks a query took, less the clock's own cost, and whether it was
  /// capped. An end before the start (a thread moved between CPUs whose
  /// counters differ) is no time at all, and counts as capped: untrusted.
  std::uint64_t elapsed(std::uint64_t start, std::uint64_t end, bool& capped) const {
    if (end < start) {
      capped = true;
      return 0;
    }
    const std::uint64_t d = end - start > m_overhead_ticks ? end - start - m_overhead_ticks : 0;
    capped = d > m_cap_ticks;
    return capped ? m_cap_ticks : d;
  }
  double seconds(std::uint64_t ticks) const { return double(ticks) / m_ticks_per_second; }
  double ticks_per_second() const { return m_ticks_per_second; }
  double overhead_seconds() const { return seconds(m_overhead_ticks); }
  /// "tsc" or "steady_clock", for the report.
  const char* source() const { return m_tsc ? "tsc" : "steady_clock"; }

  /// A clock on steady_clock (tsc false) or the TSC; public for tests.
  explicit QueryClock(bool tsc);

 private:
  static std::uint64_t steady_ns();

  bool m_tsc;
  double m_ticks_per_second = 1e9;
  std::uint64_t m_overhead_ticks = 0;
  std::uint64_t m_cap_ticks = 0;
};

/// Whether /proc/cpuinfo (or the text given) lists constant_tsc.
bool cpu_has_constant_tsc(const char* cpuinfo_text = nullptr);

}  // namespace kappa
