#include "report.h"

#include <cmath>

#include "cost_model.h"

namespace kappa {

nlohmann::ordered_json number_or_null(std::optional<double> v) {
  if (!v || !std::isfinite(*v)) return nullptr;
  return *v;
}

nlohmann::ordered_json grid_section(const UniformGrid& grid, std::span<const Triangle> triangles) {
  const GridInfo& g = grid.info();
  const double cells = double(g.resolution.cells());
  nlohmann::ordered_json j;
  j["res"] = {g.resolution.nx, g.resolution.ny, g.resolution.nz};
  j["N_c"] = g.resolution.cells();
  j["N"] = g.N;
  j["cell_size"] = {g.cell_size.x, g.cell_size.y, g.cell_size.z};
  j["build_s"] = g.build_s;
  j["bytes"] = g.bytes;
  j["theta_tot"] = g.theta_tot;
  j["theta_tot_eq19"] = number_or_null(theta_tot_eq19(triangles, g.cell_size));
  j["theta_tot_eq21"] = number_or_null(theta_tot_eq21(triangles, g.cell_size));
  j["theta_avg"] = double(g.theta_tot) / cells;
  j["max_multiplicity"] = g.max_occupancy;
  j["empty_fraction"] = double(g.empty_cells) / cells;
  j["degenerate"] = g.degenerate;
  return j;
}

nlohmann::ordered_json ray_class_section(const CastMeasurement& m, std::optional<double> p_tot_predicted) {
  return ray_class_section(ClassSummary{m.counters.totals, m.counters.per_cell_queries(), m.collusion,
                                        m.cells_per_ray_predicted, m.time_s},
                           p_tot_predicted);
}

nlohmann::ordered_json ray_class_section(const ClassSummary& m, std::optional<double> p_tot_predicted) {
  const ClassTotals& t = m.totals;
  const CollusionStats& c = m.collusion;
  const double rays = double(t.rays);
  auto per_ray = [&](double v) { return t.rays > 0 ? nlohmann::ordered_json(v / rays) : nlohmann::ordered_json(); };
  nlohmann::ordered_json j;
  j["count"] = t.rays;
  j["cells_per_ray"] = per_ray(double(t.cells));
  j["cells_per_ray_predicted"] = t.rays > 0 ? number_or_null(m.cells_per_ray_predicted) : nullptr;
  j["tests_per_ray"] = per_ray(double(t.tests));
  j["refs_per_ray"] = per_ray(double(t.refs));
  j["mailbox_skips_per_ray"] = per_ray(double(t.mailbox_skips));
  j["hit_fraction"] = per_ray(double(t.hits));
  j["p_tot"] = t.rays > 0 ? number_or_null(c.p_tot) : nullptr;
  if (p_tot_predicted) j["p_tot_predicted"] = number_or_null(p_tot_predicted);
  j["p_avg"] = t.rays > 0 ? number_or_null(c.p_avg) : nullptr;
  j["sigma_p"] = t.rays > 0 ? number_or_null(c.sigma_p) : nullptr;
  j["sigma_theta"] = number_or_null(c.sigma_theta);
  j["r"] = number_or_null(c.r);
  j["kappa"] = number_or_null(c.kappa);
  j["kappa_eq25"] = number_or_null(c.kappa_eq25);
  j["per_cell_rays"] = m.per_cell_rays;
  j["time_s"] = m.time_s;
  return j;
}

}  // namespace kappa
