// The machine's physical memory: what default budgets are fractions of and
// what no single buffer may exceed.
#pragma once

#include <unistd.h>

#include <cstdint>

namespace kappa {

/// Bytes of physical RAM, or 16 GiB where the system does not say.
inline std::uint64_t physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0) return std::uint64_t(16) << 30;
  return std::uint64_t(pages) * std::uint64_t(page);
}

}  // namespace kappa
