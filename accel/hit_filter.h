// The any-hit filter seam: a per-triangle "does this hit count" predicate that
// every exact accelerator asks at the same point of its triangle test, so that
// a cut-out (an alpha test) is one predicate and every accelerator still
// returns the same closest hit bitwise. A filter sees a candidate hit (the
// triangle, t and barycentrics the watertight test found) only once the test
// and, for a closest-hit query, the tie rule would keep it; a hit it refuses
// is as if the triangle were not there. Its verdict must depend on the hit
// alone (not on the order of calls), which is what makes the walks' orders,
// their mailboxes and their "exit beyond the hit" rule agree.
//
// NoHitFilter, the default, is compiled out: `active` is false and every
// call site tests it with `if constexpr`, so a scene without cut-outs runs
// the code it ran before the seam existed.
#pragma once

#include <concepts>

#include "accel/ray.h"

namespace kappa {

template <class F>
concept HitFilter = requires(const F& f, const Hit& h) {
  { F::active } -> std::convertible_to<bool>;
  { f.accepts(h) } -> std::convertible_to<bool>;
};

/// Every hit counts.
struct NoHitFilter {
  static constexpr bool active = false;
  constexpr bool accepts(const Hit&) const { return true; }
};

/// A filter behind a function pointer: what the Accelerator interface takes
/// (naive and Embree, reached through it), whatever filter the caller has.
struct FunctionHitFilter {
  static constexpr bool active = true;
  const void* context = nullptr;
  bool (*test)(const void* context, const Hit& candidate) = nullptr;
  bool accepts(const Hit& h) const { return test(context, h); }

  /// Wraps `filter`, which must outlive the wrapper.
  template <class F>
  static FunctionHitFilter of(const F& filter) {
    return {&filter, [](const void* c, const Hit& h) { return static_cast<const F*>(c)->accepts(h); }};
  }
};

/// Whether `candidate` counts under `filter` (always, for an inactive one).
template <HitFilter Filter>
[[gnu::always_inline]] inline bool filter_accepts(const Filter& filter, const Hit& candidate) {
  if constexpr (Filter::active) return filter.accepts(candidate);
  else return true;
}

}  // namespace kappa
