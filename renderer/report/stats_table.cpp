#include "renderer/report/stats_table.h"

#include <cstdio>

namespace kappa {
namespace {

/// `v` formatted with `fmt`, or "-" when it is null (undefined) or absent.
std::string number(const nlohmann::ordered_json& v, const char* fmt) {
  if (!v.is_number()) return "-";
  char buf[48];
  std::snprintf(buf, sizeof buf, fmt, v.get<double>());
  return buf;
}

std::string row(const char* fmt, auto... columns) {
  char buf[256];
  std::snprintf(buf, sizeof buf, fmt, columns...);
  return buf;
}

/// The predicted cells per ray: eq 22 for uniform lines (the whole chord),
/// eq 24 from each ray's own length otherwise.
const nlohmann::ordered_json& predicted_cells(const nlohmann::ordered_json& c) {
  return c.contains("p_tot_predicted") ? c["p_tot_predicted"] : c["cells_per_ray_predicted"];
}

/// The bounce rays by lobe, as rows "by LOBE" under the classes, for the
/// lobes that sampled any ray.
template <class Row>
void for_each_lobe(const nlohmann::ordered_json& report, Row&& row_of) {
  if (!report["rays"].contains("bounce_by_lobe")) return;
  for (const auto& [lobe, c] : report["rays"]["bounce_by_lobe"].items())
    if (c["count"].is_number() && c["count"].template get<double>() > 0) row_of("by " + lobe, c);
}

}  // namespace

std::string stats_table(const nlohmann::ordered_json& report) {
  std::string out;
  if (!report.contains("rays") || report["rays"].empty()) return out;
  if (report.contains("cost") && report["cost"].is_object() && report["cost"]["eq10"].is_object()) {
    const auto& c = report["cost"];
    const auto& e = c["eq10"];
    out += row("cost (thread-seconds of traversal): measured %.3f s; eq 10 %.3f s (error %s; T0 %.1f ns, Ts %.1f ns, "
               "Th %.1f ns); extended %.3f s (error %s)\n",
               c["measured_s"].get<double>(), e["predicted_s"].get<double>(),
               number(e["relative_error"], "%+.3f").c_str(), e["T0_ns"].get<double>(), e["Ts_ns"].get<double>(),
               e["Th_ns"].get<double>(), c["extended"]["predicted_s"].get<double>(),
               number(c["extended"]["relative_error"], "%+.3f").c_str());
  }
  const bool grid_counts = report["rays"].begin()->contains("cells_per_ray");
  if (!grid_counts) {  // another accelerator: what applies to any
    const auto any_row = [&](const std::string& name, const nlohmann::ordered_json& c) {
      out += row("%-9s %11s %12s %10s\n", name.c_str(), c["count"].dump().c_str(),
                 number(c["hit_fraction"], "%.3f").c_str(), number(c["time_s"], "%.3f").c_str());
    };
    out += row("%-9s %11s %12s %10s\n", "class", "rays", "hit fraction", "time (s)");
    for (const auto& [name, c] : report["rays"].items())
      if (name != "bounce_by_lobe") any_row(name, c);
    for_each_lobe(report, [&](const std::string& name, const nlohmann::ordered_json& c) { any_row(name, c); });
    return out;
  }
  static const char* kRow = "%-9s %11s %10s %20s %10s %10s %14s %7s %8s %11s\n";
  out += row(kRow, "class", "rays", "cells/ray", "predicted cells/ray", "tests/ray", "refs/ray", "p_tot (cells)", "r",
             "kappa", "kappa eq 25");
  const auto grid_row = [&](const std::string& name, const nlohmann::ordered_json& c) {
    out += row(kRow, name.c_str(), c["count"].dump().c_str(),
               number(c["cells_per_ray"], "%.2f").c_str(), number(predicted_cells(c), "%.2f").c_str(),
               number(c["tests_per_ray"], "%.2f").c_str(), number(c["refs_per_ray"], "%.2f").c_str(),
               number(c["p_tot"], "%.2f").c_str(), number(c["r"], "%.3f").c_str(), number(c["kappa"], "%.3f").c_str(),
               number(c["kappa_eq25"], "%.3f").c_str());
  };
  for (const auto& [name, c] : report["rays"].items())
    if (name != "bounce_by_lobe") grid_row(name, c);
  for_each_lobe(report, grid_row);
  return out;
}

std::string grid_occupancy_line(const nlohmann::ordered_json& grid) {
  if (grid.contains("levels"))  // grid2: its top grid and leaves (no eq 19 over cells of differing sizes)
    return row("grid2 top %s x %s x %s (%s cells refined): N_c %s leaves in %zu levels, N %s, theta_tot %s, empty %s\n",
               grid["top_res"][0].dump().c_str(), grid["top_res"][1].dump().c_str(), grid["top_res"][2].dump().c_str(),
               grid["refined"].dump().c_str(), grid["N_c"].dump().c_str(), grid["levels"].size(), grid["N"].dump().c_str(),
               grid["theta_tot"].dump().c_str(), number(grid["empty_fraction"], "%.3f").c_str());
  return row("grid %s x %s x %s: N_c %s, N %s, theta_tot %s (eq19 %s, eq21 %s), empty %s\n",
             grid["res"][0].dump().c_str(), grid["res"][1].dump().c_str(), grid["res"][2].dump().c_str(),
             grid["N_c"].dump().c_str(), grid["N"].dump().c_str(), grid["theta_tot"].dump().c_str(),
             number(grid["theta_tot_eq19"], "%.0f").c_str(), number(grid["theta_tot_eq21"], "%.0f").c_str(),
             number(grid["empty_fraction"], "%.3f").c_str());
}

}  // namespace kappa
