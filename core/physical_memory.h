// The machine's physical memory: what default budgets are fractions of and
// what no single buffer may exceed.
#pragma once

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>

namespace kappa {

/// Bytes of physical RAM, or 16 GiB where the system does not say.
inline std::uint64_t physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0) return std::uint64_t(16) << 30;
  return std::uint64_t(pages) * std::uint64_t(page);
}

/// The memory this process may use: the physical memory, or less where a
/// limit on its address space or data (ulimit -v, -d) says so.
inline std::uint64_t usable_memory_bytes() {
  std::uint64_t usable = physical_memory_bytes();
  for (int resource : {RLIMIT_AS, RLIMIT_DATA}) {
    struct rlimit limit {};
    if (::getrlimit(resource, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
      usable = std::min<std::uint64_t>(usable, limit.rlim_cur);
  }
  return usable;
}

}  // namespace kappa
