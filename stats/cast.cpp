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
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 1024), [&](const auto& range) {
    CellCounters& counters = per_thread.local();
    for (std::size_t i = range.begin(); i < range.end(); ++i) {
      bool hit = false;
      CellCounters::Tally tally(counters);
      switch (walk) {
        case GridWalk::closest: {
          const auto h = grid.closest_hit(rays[i], tally);
          hit = h.has_value();
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

  // Predicted cells per ray from each ray's own length inside the grid box,
  // summed by the walks (WalkCounts::predicted_cells).
  m.cells_per_ray_predicted = rays.empty() ? 0.0 : m.counters.totals.predicted_cells() / double(rays.size());
  return m;
}

}  // namespace kappa
