// The per-frame JSON report's sections built from measurements (keys are
// documented in stats/README.md and fixed: other tools read them).
#pragma once

#include <nlohmann/json.hpp>

#include "accel/cell_layout.h"
#include <optional>
#include <span>
#include <string>

#include "accel/accel.h"
#include "accel/cell_layout.h"
#include "cast.h"

namespace kappa {

/// Bumped once by each change of the report's keys (changelog: stats/README.md).
inline constexpr int kReportSchemaVersion = 17;

/// A double, or null when it is undefined or not finite (never NaN in JSON).
nlohmann::ordered_json number_or_null(std::optional<double> v);

/// The accelerator's own section (Accelerator::report_section, e.g. the
/// grid's resolution, sizes and occupancy), with the model's Theta_tot by eqs
/// 19 and 21 after theta_tot when its cells have one size; null for an
/// accelerator without a section.
nlohmann::ordered_json accel_section(const Accelerator& accel, std::span<const Triangle> triangles);

/// What one entry of the "rays" section reports about a class of rays.
struct ClassSummary {
  ClassTotals totals;
  std::uint64_t per_cell_rays = 0;  ///< rays counted per cell (all of them unless sampled)
  CollusionStats collusion;
  CollusionStats sample;  ///< the per-cell sample alone; sample.N_r = 0 without one
  double cells_per_ray_predicted = 0;
  double time_s = 0;
};

/// One entry of the "rays" section. `p_tot_predicted` is given for uniform
/// lines only (eq 22).
nlohmann::ordered_json ray_class_section(const ClassSummary& m, std::optional<double> p_tot_predicted);
/// The same from a cast with counters.
nlohmann::ordered_json ray_class_section(const CastMeasurement& m, std::optional<double> p_tot_predicted);

/// A ray class's figures per level of a structure of several (grid2,
/// CellLayout::levels): [{level, N_c, cells_per_ray, tests_per_ray, p_tot,
/// kappa}], exact from the totals: eq 8 restricted to level L is
/// N_cL * refs_L / (cells_L * theta_totL), null where theta_totL is 0. Null
/// for a structure of one level.
nlohmann::ordered_json level_sections(const ClassTotals& totals, const std::vector<CellLayout::Level>& levels);

/// Adds to a ray class's section what a structure that has levels has
/// (grid2; nothing for the uniform grid): `levels` (level_sections) and
/// `descents_per_ray`, the sub-grids its rays entered (the model's T_descend
/// term, stats/time_model.h).
void add_level_figures(nlohmann::ordered_json& section, const ClassTotals& totals,
                       const std::vector<CellLayout::Level>& levels);

}  // namespace kappa
