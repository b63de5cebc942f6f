// The per-frame JSON report's sections built from measurements (keys are
// documented in stats/README.md and fixed: other tools read them).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>

#include "accel/grid.h"
#include "cast.h"

namespace kappa {

inline constexpr int kReportSchemaVersion = 1;

/// A double, or null when it is undefined or not finite (never NaN in JSON).
nlohmann::ordered_json number_or_null(std::optional<double> v);

/// The "grid" section: resolution, sizes, occupancy measured and predicted (eqs 19, 21).
nlohmann::ordered_json grid_section(const UniformGrid& grid, std::span<const Triangle> triangles);

/// What one entry of the "rays" section reports about a class of rays.
struct ClassSummary {
  ClassTotals totals;
  std::uint64_t per_cell_rays = 0;  ///< rays counted per cell (all of them unless sampled)
  CollusionStats collusion;
  double cells_per_ray_predicted = 0;
  double time_s = 0;
};

/// One entry of the "rays" section. `p_tot_predicted` is given for uniform
/// lines only (eq 22).
nlohmann::ordered_json ray_class_section(const ClassSummary& m, std::optional<double> p_tot_predicted);
/// The same from a cast with counters.
nlohmann::ordered_json ray_class_section(const CastMeasurement& m, std::optional<double> p_tot_predicted);

}  // namespace kappa
