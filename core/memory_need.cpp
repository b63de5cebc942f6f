#include "core/memory_need.h"

#include <exception>
#include <mutex>
#include <vector>

#include "core/byte_size.h"
#include "core/physical_memory.h"

namespace kappa {
namespace {

struct Need {
  std::string what;
  std::uint64_t bytes;
};

std::mutex g_mutex;
Need g_unwound;  ///< the innermost need an exception unwound through
std::vector<Need>& needs() {
  static std::vector<Need> stack;
  return stack;
}

}  // namespace

MemoryNeed::MemoryNeed(std::string what, std::uint64_t bytes) : m_exceptions(std::uncaught_exceptions()) {
  std::lock_guard<std::mutex> lock(g_mutex);
  g_unwound = {};  // a failure already handled (an exception caught) is not this task's
  needs().reserve(16);  // so that a push while memory is short does not throw
  needs().push_back({std::move(what), bytes});
}

MemoryNeed::~MemoryNeed() {
  std::lock_guard<std::mutex> lock(g_mutex);
  if (needs().empty()) return;
  // Unwinding: remembered (moved, no allocation) for the message.
  if (std::uncaught_exceptions() > m_exceptions && g_unwound.what.empty()) g_unwound = std::move(needs().back());
  needs().pop_back();
}

std::string out_of_memory_message() {
  std::string what = "out of memory";
  {
    std::lock_guard<std::mutex> lock(g_mutex);
    const Need* failed = !g_unwound.what.empty() ? &g_unwound : !needs().empty() ? &needs().back() : nullptr;
    if (failed) {
      const Need& need = *failed;
      what += " while " + need.what;
      if (need.bytes > 0) what += ", which needs about " + byte_size(need.bytes);
    }
  }
  return what + " (this process may use " + byte_size(usable_memory_bytes()) + ")";
}

}  // namespace kappa
