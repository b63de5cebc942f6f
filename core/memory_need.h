// What the process is allocating for, so that running out of memory is one
// line naming what needed it and how much ("out of memory while reading
// 'big.obj' (2.0 GiB)"), exit 2, instead of a bare "out of memory". Set
// around loading, parsing and building, never on a hot path.
#pragma once

#include <cstdint>
#include <string>

namespace kappa {

/// While one lives, it is what the process is allocating for; nested ones
/// stack (the innermost is named).
class MemoryNeed {
 public:
  /// `what` as "reading 'x.obj'"; `bytes` about what it needs (0: unknown).
  MemoryNeed(std::string what, std::uint64_t bytes);
  ~MemoryNeed();
  MemoryNeed(const MemoryNeed&) = delete;
  MemoryNeed& operator=(const MemoryNeed&) = delete;

 private:
  int m_exceptions;  ///< exceptions in flight when made: more at destruction means unwinding
};

/// The message for running out of memory: what was being done when the
/// allocation failed (the need the exception unwound through first), what
/// it needed, and what this process may use.
std::string out_of_memory_message();

}  // namespace kappa
