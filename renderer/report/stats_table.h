// The per-class statistics table `kappa render` and `kappa cast` print on
// stdout, made from the report's "rays" section (so what is printed is what
// the JSON holds), with the units in the column heads.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace kappa {

/// One row per class of rays in report["rays"]. Classes walked through the
/// grid get its counts: rays, cells per ray (measured, and predicted by eq 22
/// for uniform lines or eq 24 otherwise), tests and references per ray, p_tot,
/// r, kappa (eq 8) and kappa by eq 25; other accelerators' classes get rays,
/// hit fraction and time. A value the report holds as null prints as "-".
/// Preceded by eq 10's line when report["cost"] holds a prediction.
std::string stats_table(const nlohmann::ordered_json& report);

/// The grid's occupancy from report["grid"], measured beside eqs 19 and 21
/// (grid2's from report["grid2"], its top grid and leaves):
/// the line `kappa cast` prints above its table.
std::string grid_occupancy_line(const nlohmann::ordered_json& grid);

}  // namespace kappa
