// How the path tracer asks its visibility queries, chosen once per frame
// (integrator.cpp, through visit_accelerator): PlainQueries calls the
// accelerator as its concrete type (the grid directly, naive and Embree
// through the interface), nothing counted but the ray total;
// CountingQueries walks a cell-based accelerator with per-class counters;
// ClassQueries counts what applies to any accelerator.
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <optional>
#include <type_traits>

#include "accel/accel.h"
#include "accel/hit_filter.h"
#include "accel/recorder.h"
#include "core/hash.h"
#include "renderer/bsdf/lobe_sample.h"
#include "renderer/render/occluder_cache.h"
#include "renderer/render/sampling.h"
#include "stats/cost_model.h"
#include "stats/query_clock.h"
#include "stats/render_counters.h"

namespace kappa {

static_assert(bsdf::kLobes == kBounceLobes, "the report's lobes are the BSDF's, in its order");

/// Cumulative work of one thread's queries: what the cost AOVs difference.
struct QueryWork {
  std::uint64_t cells = 0, tests = 0;
};

/// A cut-out filter (renderer/texture/cutout_filter.h) whose alpha tests
/// are counted in a class's totals, each one a triangle test too: it changes
/// the cost the model predicts.
template <class F>
struct AlphaCounted {
  static constexpr bool active = true;
  const F& filter;
  ClassTotals& totals;
  bool accepts(const Hit& h) const {
    std::uint64_t lookups = 0;
    const bool accepted = filter.test(h, lookups);
    totals.alpha_tests += lookups;
    totals.tests += lookups;
    return accepted;
  }
};

/// `filter` counted into `totals` (an inactive filter is passed through).
template <HitFilter F>
auto counted_filter(const F& filter, ClassTotals& totals) {
  if constexpr (F::active) return AlphaCounted<F>{filter, totals};
  else return filter;
}

/// The closest hit of `accel` under `filter`: a cell walker's template walk,
/// or the interface's filtered query (naive, Embree).
template <class A, HitFilter F>
std::optional<Hit> filtered_closest(const A& accel, const Ray& r, const F& filter) {
  if constexpr (!F::active) return accel.closest_hit(r);
  else if constexpr (std::is_same_v<A, Accelerator>) return accel.closest_hit(r, FunctionHitFilter::of(filter));
  else {
    NoRecorder none;
    return accel.closest_hit(r, none, filter);
  }
}
template <class A, HitFilter F>
bool filtered_any(const A& accel, const Ray& r, const F& filter) {
  if constexpr (!F::active) return accel.any_hit(r);
  else if constexpr (std::is_same_v<A, Accelerator>) return accel.any_hit(r, FunctionHitFilter::of(filter));
  else {
    NoRecorder none;
    return accel.any_hit(r, none, filter);
  }
}

/// Every query takes an any-hit filter, NoHitFilter (compiled out) unless
/// the frame's scene has cut-outs. A shadow ray names its light (LightKey),
/// for the occluder cache where the accelerator has one (OccluderWalker) and
/// the frame uses it (`occluder_cache`, set once per frame).
template <class A>
struct PlainQueries {
  explicit PlainQueries(const A& a, bool use_occluder_cache = false) : accel(a), occluder_cache(use_occluder_cache) {}

  const A& accel;
  bool occluder_cache;
  std::uint64_t rays = 0;
  OccluderCache cache;

  QueryWork work() const { return {}; }
  void begin_path(std::uint64_t /*pixel*/, std::uint64_t /*sample*/) {}

  template <HitFilter F = NoHitFilter>
  std::optional<Hit> closest(const Ray& r, int /*depth*/, const F& filter = {}) {
    ++rays;
    return filtered_closest(accel, r, filter);
  }
  template <HitFilter F = NoHitFilter>
  std::optional<Hit> closest_by_lobe(const Ray& r, int depth, bsdf::Lobe /*lobe*/, const F& filter = {}) {
    return closest(r, depth, filter);
  }
  template <HitFilter F = NoHitFilter>
  bool shadow(const Ray& r, LightKey light, const F& filter = {}) {
    ++rays;
    if constexpr (OccluderWalker<A>) {
      if (occluder_cache) {
        const TriangleId last = cache.occluder(light);
        if (last != kNoTriangle && occludes(accel.triangles(), last, r, filter)) return true;
        NoRecorder none;
        const TriangleId id = accel.occluder_of(r, none, filter);
        cache.remember(light, id);
        return id != kNoTriangle;
      }
    }
    return filtered_any(accel, r, filter);
  }
};

/// Times every query of a class with the QueryClock (the TSC where it is
/// constant), less the clock's own cost, capped per query.
class QueryTimer {
 public:
  explicit QueryTimer(RenderCounters& counters) : m_counters(counters) {}

  /// Returns the ticks it added to class k's.
  template <typename F>
  std::uint64_t timed(RenderClass k, F&& query) {
    const std::uint64_t start = m_clock.now();
    query();
    bool capped = false;
    const std::uint64_t ticks = m_clock.elapsed(start, m_clock.now(), capped);
    m_counters.ticks[k] += ticks;
    m_counters.capped[k] += capped;
    return ticks;
  }

 private:
  RenderCounters& m_counters;
  const QueryClock& m_clock = QueryClock::get();
};

/// Statistics on with an accelerator other than the grid: per class what
/// applies to any accelerator, the rays, their hits and their sampled time.
class ClassQueries {
 public:
  ClassQueries(const Accelerator& accel, RenderCounters& counters) : m_accel(accel), m_counters(counters) {}

  std::uint64_t rays = 0;

  QueryWork work() const { return {}; }
  void begin_path(std::uint64_t /*pixel*/, std::uint64_t /*sample*/) {}

  template <HitFilter F = NoHitFilter>
  std::optional<Hit> closest(const Ray& r, int depth, const F& filter = {}) {
    const RenderClass k = class_of_depth(depth);
    const auto f = counted_filter(filter, m_counters.classes[k].totals);
    return counted<std::optional<Hit>>(k, [&] { return filtered_closest(m_accel, r, f); });
  }
  /// A bounce ray counted in its class and in its lobe's totals.
  template <HitFilter F = NoHitFilter>
  std::optional<Hit> closest_by_lobe(const Ray& r, int depth, bsdf::Lobe lobe, const F& filter = {}) {
    const RenderClass k = class_of_depth(depth);
    const auto f = counted_filter(filter, m_counters.classes[k].totals);
    return counted<std::optional<Hit>>(k, [&] { return filtered_closest(m_accel, r, f); },
                                       depth > 0 ? &m_counters.lobes[std::size_t(lobe)] : nullptr,
                                       std::size_t(lobe));
  }
  template <HitFilter F = NoHitFilter>
  bool shadow(const Ray& r, LightKey /*light*/, const F& filter = {}) {
    const auto f = counted_filter(filter, m_counters.classes[kShadow].totals);
    return counted<bool>(kShadow, [&] { return filtered_any(m_accel, r, f); });
  }

 private:
  template <typename Result, typename F>
  Result counted(RenderClass k, F&& query, CellCounters* lobe = nullptr, std::size_t lobe_index = 0) {
    ++rays;
    ClassTotals& t = m_counters.classes[k].totals;
    Result result{};
    ++t.rays;
    const std::uint64_t ticks = m_clock.timed(k, [&] { result = query(); });
    t.hits += bool(result);
    if (lobe) {
      ++lobe->totals.rays;
      lobe->totals.hits += bool(result);
      m_counters.lobe_ticks[lobe_index] += ticks;
    }
    return result;
  }

  const Accelerator& m_accel;
  RenderCounters& m_counters;
  QueryTimer m_clock{m_counters};
};

/// Which paths count per cell: every path, or 1 in `every` drawn by a hash
/// of (seed, pixel, sample), so the choice is the same whatever the thread
/// count. Per-class totals always count every ray.
struct CellSampling {
  std::uint64_t every = 1;
  std::uint64_t seed = 0;

  bool counts(std::uint64_t pixel, std::uint64_t sample) const {
    if (every <= 1) return true;
    return mix64(mix64(seed ^ 0x6A09E667F3BCC909ull) ^ mix64(pixel) ^ (sample * 0x9E3779B97F4A7C15ull)) % every == 0;
  }
};

/// Counts every query in its class's totals and, for the paths `sampling`
/// picks, per cell: into each thread's own arrays (SampledMode own, for
/// counting every path) or into arrays the threads share (shared, for
/// sampled paths). The mode is chosen once per frame.
template <class Walker, PerCell SampledMode>
class CountingQueries {
  static_assert(SampledMode != PerCell::no);

 public:
  /// Per-cell counts are kept if `counters` has per-cell arrays, for the
  /// paths `sampling` picks; shadow rays go through an occluder cache if
  /// `occluder_cache`.
  CountingQueries(const Walker& walker, RenderCounters& counters, CellSampling sampling = {},
                  bool occluder_cache = false)
      : m_walker(walker),
        m_counters(counters),
        m_sampling(sampling),
        m_per_cell(counters.classes[0].per_cell()),
        m_occluder_cache(occluder_cache) {}

  /// Chooses, once per path, whether its rays are counted per cell.
  void begin_path(std::uint64_t pixel, std::uint64_t sample) {
    m_path_per_cell = m_per_cell && m_sampling.counts(pixel, sample);
  }

  std::uint64_t rays = 0;

  /// The cells and triangle tests so far, the occluder cache's tests
  /// included (the cost AOVs: every test a pixel's rays made).
  QueryWork work() const {
    QueryWork w;
    for (const CellCounters& c : m_counters.classes) {
      w.cells += c.totals.cells;
      w.tests += c.totals.tests;
    }
    w.tests += m_counters.occluder_cache_tests;
    return w;
  }

  template <HitFilter F = NoHitFilter>
  std::optional<Hit> closest(const Ray& r, int depth, const F& filter = {}) {
    const RenderClass k = class_of_depth(depth);
    const auto f = counted_filter(filter, m_counters.classes[k].totals);
    return counted<std::optional<Hit>>(k, [&](auto& tally) { return m_walker.closest_hit(r, tally, f); });
  }
  /// A bounce ray walked once and counted twice: in its depth's class and
  /// in the lobe's that sampled it (frames of a scene with materials only).
  template <HitFilter F = NoHitFilter>
  std::optional<Hit> closest_by_lobe(const Ray& r, int depth, bsdf::Lobe lobe, const F& filter = {}) {
    if (depth == 0) return closest(r, depth, filter);
    const RenderClass k = class_of_depth(depth);
    const std::size_t l = std::size_t(lobe);
    CellCounters& c = m_counters.classes[k];
    CellCounters& b = m_counters.lobes[l];
    ++rays;
    ++c.totals.rays;
    ++b.totals.rays;
    std::optional<Hit> result;
    const auto f = counted_filter(filter, c.totals);
    const std::uint64_t ticks = m_clock.timed(k, [&] {
      if (m_path_per_cell && b.per_cell()) {
        result = walk_tee(c, b, r, f);
      } else {
        CellCounters::TeeTally<PerCell::no> tally(c, b, &m_recent);
        result = m_walker.closest_hit(r, tally, f);
      }
    });
    m_counters.lobe_ticks[l] += ticks;
    c.totals.hits += bool(result);
    b.totals.hits += bool(result);
    return result;
  }

  /// A shadow ray: the occluder cache's test first, where the frame uses
  /// it, counted apart (RenderCounters::occluder_cache_*); a ray it answers
  /// is no walk, so not in the class's rays. Otherwise the walk, counted in
  /// the shadow class, its occluder remembered.
  template <HitFilter F = NoHitFilter>
  bool shadow(const Ray& r, LightKey light, const F& filter = {}) {
    if (m_occluder_cache) {
      if (const TriangleId last = m_cache.occluder(light); last != kNoTriangle) {
        ++m_counters.occluder_cache_tests;
        if (occludes(m_walker.triangles(), last, r, filter)) {
          ++m_counters.occluder_cache_hits;
          ++rays;
          return true;
        }
      }
    }
    const auto f = counted_filter(filter, m_counters.classes[kShadow].totals);
    return counted<bool>(kShadow, [&](auto& tally) {
      const TriangleId id = m_walker.occluder_of(r, tally, f);
      if (m_occluder_cache) m_cache.remember(light, id);
      return id != kNoTriangle;
    });
  }

 private:
  /// One query of class k: walked with the tally this path was given (per
  /// cell or totals only), timed by sampling, counted in the class totals.
  template <typename Result, typename Walk>
  Result counted(RenderClass k, Walk&& walk) {
    ++rays;
    CellCounters& c = m_counters.classes[k];
    Result result{};
    ++c.totals.rays;
    m_clock.timed(k, [&] {
      if (m_path_per_cell) {
        result = walk_per_cell<Result>(c, m_recent, walk);
      } else {
        CellCounters::TotalsTally tally(c, &m_recent);
        result = walk(tally);
      }
    });
    c.totals.hits += bool(result);
    return result;
  }

  /// The rare per-cell walk (sampled paths), kept out of line so that the
  /// common totals-only walk gets the compiler's inlining.
  template <typename Result, typename Walk>
  [[gnu::noinline]] static Result walk_per_cell(CellCounters& c, RecentCells& recent, Walk& walk) {
    CellCounters::BasicTally<SampledMode> tally(c, &recent);
    return walk(tally);
  }

  template <HitFilter F>
  [[gnu::noinline]] std::optional<Hit> walk_tee(CellCounters& c, CellCounters& b, const Ray& r, const F& filter) {
    CellCounters::TeeTally<SampledMode> tally(c, b, &m_recent);
    return m_walker.closest_hit(r, tally, filter);
  }

  const Walker& m_walker;
  RenderCounters& m_counters;
  QueryTimer m_clock{m_counters};
  CellSampling m_sampling;
  bool m_per_cell;
  bool m_path_per_cell = false;
  bool m_occluder_cache;
  OccluderCache m_cache;
  /// The cells this tile's walks entered lately (stats/recent_cells.h): one
  /// table per tile's queries in a pass, so coherence is counted the same
  /// for any thread count.
  RecentCells m_recent;
};

}  // namespace kappa
