#include "query_clock.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

namespace kappa {

bool cpu_has_constant_tsc(const char* cpuinfo_text) {
  std::string text;
  if (cpuinfo_text) {
    text = cpuinfo_text;
  } else {
    std::ifstream in("/proc/cpuinfo");
    std::ostringstream ss;
    ss << in.rdbuf();
    text = ss.str();
  }
  // A flag is a whole word of a "flags" line.
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("flags", 0) != 0) continue;
    std::istringstream words(line);
    for (std::string w; words >> w;)
      if (w == "constant_tsc") return true;
  }
  return false;
}

std::uint64_t QueryClock::steady_ns() {
  return std::uint64_t(
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count());
}

QueryClock::QueryClock(bool tsc) : m_tsc(tsc) {
#if !(defined(__x86_64__) || defined(__i386__))
  m_tsc = false;
#endif
  if (m_tsc) {
    // The TSC's rate against steady_clock over five windows of 5 ms, the
    // median: a window in which the thread was preempted between its paired
    // reads cannot skew every time of the process.
    std::array<double, 5> rates;
    for (double& rate : rates) {
      const std::uint64_t t0 = steady_ns(), c0 = now();
      std::uint64_t t1 = t0;
      while (t1 - t0 < 5'000'000) t1 = steady_ns();
      const std::uint64_t c1 = now();
      rate = double(c1 - c0) / (double(t1 - t0) * 1e-9);
    }
    std::nth_element(rates.begin(), rates.begin() + 2, rates.end());
    m_ticks_per_second = rates[2];
  }
  // What timing an empty query costs: the median of many back-to-back reads.
  std::array<std::uint64_t, 1001> d;
  for (std::uint64_t& x : d) {
    const std::uint64_t a = now();
    x = now() - a;
  }
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  m_overhead_ticks = d[d.size() / 2];
  m_cap_ticks = std::uint64_t(kQueryCapSeconds * m_ticks_per_second);
}

const QueryClock& QueryClock::get() {
  static const QueryClock clock(cpu_has_constant_tsc());
  return clock;
}

}  // namespace kappa
