#include "report.h"

#include <cmath>

#include "accel/cell_layout.h"
#include "cost_model.h"

namespace kappa {

nlohmann::ordered_json number_or_null(std::optional<double> v) {
  if (!v || !std::isfinite(*v)) return nullptr;
  return *v;
}

nlohmann::ordered_json accel_section(const Accelerator& accel, std::span<const Triangle> triangles) {
  nlohmann::ordered_json own = accel.report_section();
  const CellLayout* cells = accel.cells();
  const std::optional<Vec3d> size = cells ? cells->uniform_cell_size() : std::nullopt;
  if (!own.is_object() || !size || !own.contains("theta_tot")) return own;
  nlohmann::ordered_json j;
  for (const auto& [key, value] : own.items()) {
    j[key] = value;
    if (key == "theta_tot") {
      j["theta_tot_eq19"] = number_or_null(theta_tot_eq19(triangles, *size));
      j["theta_tot_eq21"] = number_or_null(theta_tot_eq21(triangles, *size));
    }
  }
  return j;
}

nlohmann::ordered_json ray_class_section(const CastMeasurement& m, std::optional<double> p_tot_predicted) {
  return ray_class_section(ClassSummary{m.counters.totals, m.counters.per_cell_queries(), m.collusion, m.sample,
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
  j["occupied_cells_per_ray"] = per_ray(double(t.occupied_cells));
  j["tests_per_ray"] = per_ray(double(t.tests));
  j["refs_per_ray"] = per_ray(double(t.refs));
  j["mailbox_skips_per_ray"] = per_ray(double(t.mailbox_skips));
  j["hit_fraction"] = per_ray(double(t.hits));
  j["alpha_tests"] = t.alpha_tests;  // cut-out lookups (also in tests_per_ray)
  j["p_tot"] = t.rays > 0 ? number_or_null(c.p_tot) : nullptr;
  if (p_tot_predicted) j["p_tot_predicted"] = number_or_null(p_tot_predicted);
  j["p_avg"] = t.rays > 0 ? number_or_null(c.p_avg) : nullptr;
  j["sigma_p"] = t.rays > 0 ? number_or_null(c.sigma_p) : nullptr;
  j["sigma_theta"] = number_or_null(c.sigma_theta);
  j["r"] = number_or_null(c.r);
  j["kappa"] = number_or_null(c.kappa);
  j["kappa_eq25"] = number_or_null(c.kappa_eq25);
  j["per_cell_rays"] = m.per_cell_rays;
  // The sample alone (every ray when none was left out): inside it,
  // 1 + (sigma_p / p_avg)(sigma_theta / theta_avg) r is kappa_eq25.
  const CollusionStats& s = m.sample;
  j["sample"] = s.N_r == 0 ? nlohmann::ordered_json()
                           : nlohmann::ordered_json{{"N_s", s.N_r},
                                                    {"p_avg", number_or_null(s.p_avg)},
                                                    {"sigma_p", number_or_null(s.sigma_p)},
                                                    {"r", number_or_null(s.r)},
                                                    {"kappa_eq25", number_or_null(s.kappa_eq25)}};
  j["time_s"] = m.time_s;
  return j;
}

void add_level_figures(nlohmann::ordered_json& section, const ClassTotals& totals,
                       const std::vector<CellLayout::Level>& levels) {
  if (levels.empty()) return;  // one level: the grid's
  section["levels"] = level_sections(totals, levels);
  section["descents_per_ray"] =
      totals.rays > 0 ? nlohmann::ordered_json(double(totals.descents) / double(totals.rays)) : nlohmann::ordered_json();
}

nlohmann::ordered_json level_sections(const ClassTotals& t, const std::vector<CellLayout::Level>& levels) {
  if (levels.size() < 2) return nullptr;
  const double rays = double(t.rays);
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const CellLayout::Level& level : levels) {
    const int k = level.level;
    if (k < 0 || k >= kMaxCellLevels) continue;
    const double cells = double(t.level_cells[k]);
    nlohmann::ordered_json j;
    j["level"] = k;
    j["N_c"] = level.N_c;
    j["cells_per_ray"] = t.rays > 0 ? nlohmann::ordered_json(cells / rays) : nullptr;
    j["tests_per_ray"] = t.rays > 0 ? nlohmann::ordered_json(double(t.level_tests[k]) / rays) : nullptr;
    j["p_tot"] = j["cells_per_ray"];  // sum_i p_i over the level's leaves = its mean leaves per ray (eq 6)
    // Eq 8 over the level's leaves: N_cL refs_L / (cells_L theta_totL); undefined without triangles or visits.
    std::optional<double> kappa;
    if (cells > 0 && level.theta_tot > 0)
      kappa = double(level.N_c) * double(t.level_refs[k]) / (cells * double(level.theta_tot));
    j["kappa"] = number_or_null(kappa);
    out.push_back(std::move(j));
  }
  return out;
}

}  // namespace kappa
