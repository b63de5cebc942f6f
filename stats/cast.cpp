#include "cast.h"

#include <cmath>

namespace kappa {

CastMeasurement finish_cast(const CellLayout& cells, CellCounters counters, const PerCellPlan& plan, double seconds) {
  CastMeasurement m;
  m.counters = std::move(counters);
  m.time_s = seconds;
  m.cell_sample = plan.every;
  m.stats_note = plan.note;
  m.theta = cells.occupancies();
  const ClassTotals& t = m.counters.totals;
  const std::uint64_t sampled = m.counters.per_cell_queries();
  if (plan.mode == PerCell::no) {
    m.collusion = collusion_sampled({}, m.theta, 0, t.rays, t.cells, t.refs);
  } else {
    const std::vector<std::uint64_t> visits = m.counters.visits();
    m.sample = collusion(visits, m.theta, sampled);
    m.collusion = sampled == t.rays ? m.sample : collusion_sampled(visits, m.theta, sampled, t.rays, t.cells, t.refs);
  }
  // Predicted cells per ray from each ray's own segment inside the box,
  // summed by the recorders (eq 24, predicted_cells_eq24).
  // Eq 24 needs one cell size: undefined (null) over cells of differing sizes (grid2's leaves).
  m.cells_per_ray_predicted = !cells.uniform_cell_size() ? NAN : t.rays == 0 ? 0.0 : t.predicted_cells() / double(t.rays);
  return m;
}

}  // namespace kappa
