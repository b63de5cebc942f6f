#include "core/check.h"

#include <cstdio>
#include <cstdlib>

namespace kappa::detail {

void check_failed(const char* file, int line, const char* condition) {
  std::fprintf(stderr, "kappa: internal error: check failed at %s:%d: %s\n", file, line, condition);
  std::fflush(stderr);
  std::abort();
}

void check_op_failed(const char* file, int line, const char* a_text, const char* op, const char* b_text,
                     const std::string& a_value, const std::string& b_value) {
  std::fprintf(stderr, "kappa: internal error: check failed at %s:%d: %s %s %s with %s = %s, %s = %s\n", file, line,
               a_text, op, b_text, a_text, a_value.c_str(), b_text, b_value.c_str());
  std::fflush(stderr);
  std::abort();
}

}  // namespace kappa::detail
