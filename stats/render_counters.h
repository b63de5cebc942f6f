// The ray classes of a path-traced frame and their counters.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "counters.h"

namespace kappa {

/// camera, shadow (next-event estimation), bounce1, bounce2, bounce3+.
inline constexpr std::size_t kRenderClasses = 5;
inline constexpr std::array<const char*, kRenderClasses> kRenderClassNames = {"camera", "shadow", "bounce1", "bounce2",
                                                                              "bounce3+"};
enum RenderClass : std::size_t { kCamera = 0, kShadow = 1, kBounce1 = 2, kBounce2 = 3, kBounce3Plus = 4 };

/// The class of a closest-hit query at path depth `depth` (0 = camera ray).
inline RenderClass class_of_depth(int depth) {
  return depth == 0 ? kCamera : depth == 1 ? kBounce1 : depth == 2 ? kBounce2 : kBounce3Plus;
}

/// Bounce rays (bounce1, bounce2, bounce3+) are counted a second time by the
/// lobe of the BSDF that sampled them (renderer/bsdf/lobe_sample.h, the same
/// order): the report's rays.bounce_by_lobe. Glossy and specular bounces are
/// more coherent than diffuse ones, which is what their kappa measures.
inline constexpr std::size_t kBounceLobes = 4;
inline constexpr std::array<const char*, kBounceLobes> kBounceLobeNames = {"diffuse", "glossy", "specular",
                                                                           "transmission"};

/// Every set of counters a frame keeps per cell: the classes, then the lobes.
inline constexpr std::size_t kCountedSets = kRenderClasses + kBounceLobes;

/// Per-cell arrays of each class and lobe, shared by every thread's counters.
using SharedCellArrays = std::array<std::shared_ptr<CellArrays>, kCountedSets>;

/// Per-cell arrays for every class (and, if `lobes`, every lobe) of a grid
/// of `cells` cells, to share.
inline SharedCellArrays make_shared_cell_arrays(std::size_t cells, bool lobes = false) {
  SharedCellArrays a;
  for (std::size_t k = 0; k < (lobes ? kCountedSets : kRenderClasses); ++k) a[k] = std::make_shared<CellArrays>(cells);
  return a;
}

/// One thread's counters for a frame.
struct RenderCounters {
  /// Per-cell arrays of this thread's own over `cells` cells of size
  /// `cell_size` (or totals only, if `per_cell` is false). The lobes are
  /// counted (`lobes`) only where the scene has other than Lambertian
  /// surfaces: on a Lambertian scene every bounce is diffuse, and the report
  /// reads the diffuse lobe off the bounce classes.
  RenderCounters(std::uint64_t cells, const Vec3d& cell_size, bool per_cell, bool lobes = false)
      : classes{CellCounters(cells, cell_size, per_cell), CellCounters(cells, cell_size, per_cell),
                CellCounters(cells, cell_size, per_cell), CellCounters(cells, cell_size, per_cell),
                CellCounters(cells, cell_size, per_cell)},
        lobes{CellCounters(cells, cell_size, per_cell && lobes), CellCounters(cells, cell_size, per_cell && lobes),
              CellCounters(cells, cell_size, per_cell && lobes), CellCounters(cells, cell_size, per_cell && lobes)},
        lobes_counted(lobes) {}
  /// Per-cell counts into `shared`, with every other thread (the lobes too
  /// if `shared` has their arrays).
  RenderCounters(const SharedCellArrays& shared, const Vec3d& cell_size)
      : classes{CellCounters(shared[0], cell_size), CellCounters(shared[1], cell_size),
                CellCounters(shared[2], cell_size), CellCounters(shared[3], cell_size),
                CellCounters(shared[4], cell_size)},
        lobes{CellCounters(shared[5], cell_size), CellCounters(shared[6], cell_size),
              CellCounters(shared[7], cell_size), CellCounters(shared[8], cell_size)},
        lobes_counted(shared[5] != nullptr) {}
  /// Totals only, for an accelerator without cells.
  RenderCounters() : RenderCounters(0, Vec3d{}, false) {}

  std::array<CellCounters, kRenderClasses> classes;
  /// Traversal time of every query of a class, in QueryClock ticks (each
  /// query capped), and how many queries were capped.
  std::array<std::uint64_t, kRenderClasses> ticks{};
  std::array<std::uint64_t, kRenderClasses> capped{};
  /// The bounce rays again, by the lobe that sampled them, and their time.
  std::array<CellCounters, kBounceLobes> lobes;
  std::array<std::uint64_t, kBounceLobes> lobe_ticks{};
  /// The lobes were counted (else every bounce was diffuse, in `classes`).
  bool lobes_counted = false;
  /// The occluder cache's counts (renderer/render/occluder_cache.h), kept
  /// apart from the shadow class's walks, whose rays, cells and tests stay
  /// the paper's quantities: shadow rays for whose light a triangle was
  /// remembered (each one triangle test), and those it occluded, answered
  /// without a walk.
  std::uint64_t occluder_cache_tests = 0, occluder_cache_hits = 0;

  /// Every count of every class and lobe in one order (CellCounters::flatten),
  /// and back: the ranks of one frame sum theirs (kappa-mpi).
  std::vector<std::uint64_t> flatten() const {
    std::vector<std::uint64_t> out;
    for (const CellCounters& c : classes) c.flatten(out);
    for (const CellCounters& c : lobes) c.flatten(out);
    out.insert(out.end(), ticks.begin(), ticks.end());
    out.insert(out.end(), capped.begin(), capped.end());
    out.insert(out.end(), lobe_ticks.begin(), lobe_ticks.end());
    out.push_back(occluder_cache_tests);
    out.push_back(occluder_cache_hits);
    return out;
  }
  void assign(const std::vector<std::uint64_t>& flat) {
    const std::uint64_t* in = flat.data();
    for (CellCounters& c : classes) c.assign(in);
    for (CellCounters& c : lobes) c.assign(in);
    for (auto* a : {ticks.data(), capped.data()})
      for (std::size_t k = 0; k < kRenderClasses; ++k) a[k] = *in++;
    for (std::size_t k = 0; k < kBounceLobes; ++k) lobe_ticks[k] = *in++;
    occluder_cache_tests = *in++;
    occluder_cache_hits = *in++;
  }

  void merge(const RenderCounters& o) {
    for (std::size_t k = 0; k < kRenderClasses; ++k) {
      classes[k].merge(o.classes[k]);
      ticks[k] += o.ticks[k];
      capped[k] += o.capped[k];
    }
    lobes_counted = lobes_counted || o.lobes_counted;
    occluder_cache_tests += o.occluder_cache_tests;
    occluder_cache_hits += o.occluder_cache_hits;
    for (std::size_t k = 0; k < kBounceLobes; ++k) {
      lobes[k].merge(o.lobes[k]);
      lobe_ticks[k] += o.lobe_ticks[k];
    }
  }
};

}  // namespace kappa
