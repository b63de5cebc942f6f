// The one dispatch point: an Accelerator turned into the concrete type its
// frame is instantiated for, once per frame (never per ray). The grid gets
// its own type, so its per-ray loop calls UniformGrid directly (no virtual
// call) and statistics instantiate its walk with their recorders; naive and
// Embree share one instantiation through the interface. Adding an
// accelerator touches the factory (factory.cpp), its AccelKind and this switch.
#pragma once

#include <concepts>
#include <utility>

#include "accel.h"
#include "grid.h"
#include "grid2.h"
#include "grid2_traverse.h"
#include "grid_traverse.h"  // the walks' templates, for code that instantiates them with a recorder
#include "recorder.h"

namespace kappa {

/// An accelerator whose walks take a recorder (accel/recorder.h) and whose
/// cells a CellLayout describes: what statistics count per cell.
template <class A>
concept CellWalker = requires(const A& a, const Ray& r, NoRecorder& rec) {
  { a.closest_hit(r, rec) };
  { a.any_hit(r, rec) };
  { a.walk_whole(r, rec) };
  { a.cells() } -> std::convertible_to<const CellLayout*>;
};

/// Calls f with `accel` as its concrete type where one is instantiated (the
/// grids), else as `const Accelerator&`; returns what f returns.
template <class F>
decltype(auto) visit_accelerator(const Accelerator& accel, F&& f) {
  switch (accel.kind()) {
    case AccelKind::grid:
      // kind() is grid only for a UniformGrid: the cast is checked by construction.
      return std::forward<F>(f)(static_cast<const UniformGrid&>(accel));
    case AccelKind::grid2:
      return std::forward<F>(f)(static_cast<const NestedGrid&>(accel));
    case AccelKind::naive:
    case AccelKind::embree:
      break;
  }
  return std::forward<F>(f)(accel);
}

}  // namespace kappa
