// Invariant checks, after pbrt-v4's util/check.h: KAPPA_CHECK* is on in every
// build and belongs where a broken invariant would otherwise corrupt memory
// or a number silently, never inside the per-ray loop; KAPPA_DCHECK* costs
// nothing in Release and is on in Debug builds and with -DKAPPA_DCHECKS=1 (the
// sanitizer build). A failed check prints the condition and, for the _OP
// forms, both operands' values, then aborts: an internal error, not the
// user's (their input is refused with InputError instead).
#pragma once

#include <sstream>
#include <string>

namespace kappa::detail {

[[noreturn]] void check_failed(const char* file, int line, const char* condition);
[[noreturn]] void check_op_failed(const char* file, int line, const char* a_text, const char* op, const char* b_text,
                                  const std::string& a_value, const std::string& b_value);

template <class T>
std::string check_operand(const T& v) {
  std::ostringstream s;
  if constexpr (requires { s << v; }) s << v;
  else s << "(unprintable)";
  return s.str();
}

}  // namespace kappa::detail

#define KAPPA_CHECK(condition) \
  ((condition) ? (void)0 : ::kappa::detail::check_failed(__FILE__, __LINE__, #condition))

#define KAPPA_CHECK_OP(a, op, b)                                                                                 \
  do {                                                                                                           \
    const auto& kappa_check_a = (a);                                                                             \
    const auto& kappa_check_b = (b);                                                                             \
    if (!(kappa_check_a op kappa_check_b))                                                                       \
      ::kappa::detail::check_op_failed(__FILE__, __LINE__, #a, #op, #b, ::kappa::detail::check_operand(kappa_check_a), \
                                       ::kappa::detail::check_operand(kappa_check_b));                           \
  } while (false)

#define KAPPA_CHECK_EQ(a, b) KAPPA_CHECK_OP(a, ==, b)
#define KAPPA_CHECK_NE(a, b) KAPPA_CHECK_OP(a, !=, b)
#define KAPPA_CHECK_LT(a, b) KAPPA_CHECK_OP(a, <, b)
#define KAPPA_CHECK_LE(a, b) KAPPA_CHECK_OP(a, <=, b)
#define KAPPA_CHECK_GT(a, b) KAPPA_CHECK_OP(a, >, b)
#define KAPPA_CHECK_GE(a, b) KAPPA_CHECK_OP(a, >=, b)
/// A branch that cannot be reached.
#define KAPPA_UNREACHABLE() ::kappa::detail::check_failed(__FILE__, __LINE__, "unreachable code reached")

#if !defined(NDEBUG) || (defined(KAPPA_DCHECKS) && KAPPA_DCHECKS)
#define KAPPA_DCHECK(condition) KAPPA_CHECK(condition)
#define KAPPA_DCHECK_EQ(a, b) KAPPA_CHECK_EQ(a, b)
#define KAPPA_DCHECK_NE(a, b) KAPPA_CHECK_NE(a, b)
#define KAPPA_DCHECK_LT(a, b) KAPPA_CHECK_LT(a, b)
#define KAPPA_DCHECK_LE(a, b) KAPPA_CHECK_LE(a, b)
#define KAPPA_DCHECK_GT(a, b) KAPPA_CHECK_GT(a, b)
#define KAPPA_DCHECK_GE(a, b) KAPPA_CHECK_GE(a, b)
#else
// Not evaluated, but still compiled: a DCHECK cannot rot in Release.
#define KAPPA_DCHECK(condition) ((void)sizeof(!(condition)))
#define KAPPA_DCHECK_OP_OFF(a, b) ((void)sizeof((a) == (b)))
#define KAPPA_DCHECK_EQ(a, b) KAPPA_DCHECK_OP_OFF(a, b)
#define KAPPA_DCHECK_NE(a, b) KAPPA_DCHECK_OP_OFF(a, b)
#define KAPPA_DCHECK_LT(a, b) ((void)sizeof((a) < (b)))
#define KAPPA_DCHECK_LE(a, b) ((void)sizeof((a) <= (b)))
#define KAPPA_DCHECK_GT(a, b) ((void)sizeof((a) > (b)))
#define KAPPA_DCHECK_GE(a, b) ((void)sizeof((a) >= (b)))
#endif
