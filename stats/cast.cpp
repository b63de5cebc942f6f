#include "cast.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cmath>
#include <optional>

#include "accel/grid_traverse.h"
#include "cost_model.h"

namespace kappa {

std::vector<std::uint32_t> occupancies(const UniformGrid& grid) {
  std::vector<std::uint32_t> theta(grid.info().resolution.cells());
  for (std::uint64_t c = 0; c < theta.size(); ++c) theta[c] = std::uint32_t(grid.cell(c).size());
  return theta;
}

CastMeasurement cast_with_counters(const UniformGrid& grid, std::span<const Ray> rays, GridWalk walk, int threads) {
  std::optional<tbb::global_control> limit;
  if (threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(threads));

  const auto start = std::chrono::steady_clock::now();
  const GridResolution res = grid.info().resolution;
  tbb::enumerable_thread_specific<CellCounters> per_thread([res] { return CellCounters(res); });
  // Where each ray's walk ended: its closest hit, else its tmax.
  std::vector<float> end_t(rays.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 1024), [&](const auto& range) {
    CellCounters& counters = per_thread.local();
    for (std::size_t i = range.begin(); i < range.end(); ++i) {
      bool hit = false;
      end_t[i] = rays[i].tmax;
      CellCounters::Tally tally(counters);
      switch (walk) {
        case GridWalk::closest: {
          const auto h = grid.closest_hit(rays[i], tally);
          hit = h.has_value();
          if (h) end_t[i] = h->t;
          break;
        }
        case GridWalk::any: hit = grid.any_hit(rays[i], tally); break;
        case GridWalk::whole: hit = grid.walk_whole(rays[i], tally).has_value(); break;
      }
      ++counters.totals.rays;
      counters.totals.hits += hit;
    }
  });
  CastMeasurement m;
  m.counters = CellCounters(res);
  per_thread.combine_each([&](const CellCounters& c) { m.counters.merge(c); });
  m.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  m.theta = occupancies(grid);
  m.collusion = collusion(m.counters.visits(), m.theta, m.counters.totals.rays);

  // Predicted cells per ray from each ray's own length inside the grid box
  // (serial: a double sum in a fixed order).
  const GridInfo& g = grid.info();
  double predicted = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const Ray& r = rays[i];
    const Vec3d o(r.o), d(r.d);
    // The same early-outs as the walk: these rays visit no cell.
    if (!is_finite(r.o) || !is_finite(r.d) || r.d == Vec3f{0, 0, 0} || !(r.tmin <= end_t[i])) continue;
    double t0 = r.tmin, t1 = end_t[i];
    bool outside = false;
    for (int a = 0; a < 3; ++a) {
      if (d[a] == 0) {
        outside |= o[a] < g.lo[a] || o[a] > g.hi[a];
        continue;
      }
      double tn = (g.lo[a] - o[a]) / d[a], tf = (g.hi[a] - o[a]) / d[a];
      if (tn > tf) std::swap(tn, tf);
      t0 = std::max(t0, tn);
      t1 = std::min(t1, tf);
    }
    // Any-hit walks may stop before tmax at an unknown point: their
    // prediction uses the whole segment, an upper bound.
    if (!outside && t1 > t0) predicted += cells_for_segment(d * (t1 - t0), g.cell_size);
  }
  m.cells_per_ray_predicted = rays.empty() ? 0.0 : predicted / double(rays.size());
  return m;
}

}  // namespace kappa
