// How the path tracer asks its visibility queries, chosen once per frame:
// PlainQueries calls the accelerator (a virtual call, nothing counted but
// the ray total); CountingQueries walks the grid with per-class counters.
#pragma once

#include <chrono>
#include <cmath>
#include <optional>

#include "accel/accel.h"
#include "accel/grid_traverse.h"
#include "stats/cost_model.h"
#include "stats/render_counters.h"

namespace kappa {

/// Cumulative work of one thread's queries: what the cost AOVs difference.
struct QueryWork {
  std::uint64_t cells = 0, tests = 0;
};

struct PlainQueries {
  const Accelerator& accel;
  std::uint64_t rays = 0;

  QueryWork work() const { return {}; }

  std::optional<Hit> closest(const Ray& r, int /*depth*/) {
    ++rays;
    return accel.closest_hit(r);
  }
  bool shadow(const Ray& r) {
    ++rays;
    return accel.any_hit(r);
  }
};

class CountingQueries {
 public:
  CountingQueries(const UniformGrid& grid, RenderCounters& counters) : m_grid(grid), m_counters(counters) {}

  std::uint64_t rays = 0;

  QueryWork work() const {
    QueryWork w;
    for (const CellCounters& c : m_counters.classes) {
      w.cells += c.totals.cells;
      w.tests += c.totals.tests;
    }
    return w;
  }

  std::optional<Hit> closest(const Ray& r, int depth) {
    ++rays;
    const RenderClass k = class_of_depth(depth);
    CellCounters& c = m_counters.classes[k];
    std::optional<Hit> hit;
    timed(k, [&] {
      CellCounters::Tally tally(c);
      hit = m_grid.closest_hit(r, tally);
    });
    ++c.totals.rays;
    c.totals.hits += hit.has_value();
    predict(k, r, hit ? hit->t : r.tmax);
    return hit;
  }

  bool shadow(const Ray& r) {
    ++rays;
    CellCounters& c = m_counters.classes[kShadow];
    bool occluded = false;
    timed(kShadow, [&] {
      CellCounters::Tally tally(c);
      occluded = m_grid.any_hit(r, tally);
    });
    ++c.totals.rays;
    c.totals.hits += occluded;
    predict(kShadow, r, r.tmax);  // where an any-hit walk stopped is not known: an upper bound
    return occluded;
  }

 private:
  /// Times every 64th query of a class with the clock and counts it 64
  /// times: no clock read per query.
  template <typename F>
  void timed(RenderClass k, F&& query) {
    if ((m_counters.queries[k]++ & 63) != 0) {
      query();
      return;
    }
    const auto start = std::chrono::steady_clock::now();
    query();
    m_counters.sampled_seconds[k] += 64.0 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  /// Predicted cells for the part of the ray inside the grid, up to `end`.
  void predict(RenderClass k, const Ray& r, float end) {
    const GridInfo& g = m_grid.info();
    // The same early-outs as the walk: these rays visit no cell.
    if (!is_finite(r.o) || !is_finite(r.d) || r.d == Vec3f{0, 0, 0} || !(r.tmin <= end)) return;
    double t0 = r.tmin, t1 = end;
    for (int a = 0; a < 3; ++a) {
      const double d = r.d[a], o = r.o[a];
      if (d == 0) {
        if (o < g.lo[a] || o > g.hi[a]) return;
        continue;
      }
      double tn = (g.lo[a] - o) / d, tf = (g.hi[a] - o) / d;
      if (tn > tf) std::swap(tn, tf);
      t0 = std::max(t0, tn);
      t1 = std::min(t1, tf);
    }
    if (!(t1 > t0)) return;
    const double cells = cells_for_segment(Vec3d(r.d) * (t1 - t0), g.cell_size);
    if (!std::isfinite(cells)) return;
    m_counters.predicted_fixed[k] += std::uint64_t(std::llround(cells * 1024.0));
  }

  const UniformGrid& m_grid;
  RenderCounters& m_counters;
};

}  // namespace kappa
