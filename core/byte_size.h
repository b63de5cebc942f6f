// Memory sizes in messages: bytes below a mebibyte, else MiB.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>

namespace kappa {

inline std::string byte_size(std::uint64_t bytes) {
  char buf[48];
  if (bytes < (std::uint64_t(1) << 20))
    std::snprintf(buf, sizeof buf, "%llu bytes", static_cast<unsigned long long>(bytes));
  else
    std::snprintf(buf, sizeof buf, "%.1f MiB", double(bytes) / double(std::uint64_t(1) << 20));
  return buf;
}

}  // namespace kappa
