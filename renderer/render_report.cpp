#include "render_report.h"

#include <cstdio>

#include "accel/grid.h"
#include "stats/cast.h"
#include "stats/report.h"
#include "version.h"

namespace kappa {
namespace {

/// One class's measurement in the shape the report's sections take.
CastMeasurement measurement(const CellCounters& counters, const std::vector<std::uint32_t>& theta,
                            std::uint64_t predicted_fixed, double seconds) {
  CastMeasurement m;
  m.counters = counters;
  m.theta = theta;
  const std::uint64_t rays = counters.totals.rays;
  if (counters.per_cell()) {
    m.collusion = collusion(counters.visits(), theta, rays);
  } else {  // totals only: Theta's moments as usual, what needs p_i undefined
    m.collusion = collusion(std::vector<std::uint64_t>(theta.size(), 0), theta, 0);
    m.collusion.N_r = rays;
    m.collusion.p_tot = rays > 0 ? double(counters.totals.cells) / double(rays) : 0.0;
    m.collusion.p_avg = theta.empty() ? 0.0 : m.collusion.p_tot / double(theta.size());
    m.collusion.sigma_p = std::numeric_limits<double>::quiet_NaN();  // becomes null
  }
  m.cells_per_ray_predicted = rays > 0 ? double(predicted_fixed) / 1024.0 / double(rays) : 0.0;
  m.time_s = seconds;
  return m;
}

std::string cell(const nlohmann::ordered_json& v, const char* fmt) {
  if (!v.is_number()) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, fmt, v.get<double>());
  return buf;
}

}  // namespace

nlohmann::ordered_json render_report(const Scene& scene, const Accelerator& accel, const FrameFacts& frame,
                                     const RenderResult& result, const std::optional<Calibration>& calibration) {
  nlohmann::ordered_json j;
  j["schema_version"] = kReportSchemaVersion;
  j["kappa_version"] = version_string();
  j["scene"] = scene.source.string();
  j["accel"] = std::string(accel.name());
  j["render"] = {{"width", frame.width},
                 {"height", frame.height},
                 {"spp", frame.spp},
                 {"threads", frame.threads},
                 {"seed", frame.seed},
                 {"time_s", result.seconds},
                 {"rays", result.rays},
                 {"mrays_per_s", result.seconds > 0 ? double(result.rays) / result.seconds * 1e-6 : 0.0}};
  const auto* grid = dynamic_cast<const UniformGrid*>(&accel);
  if (grid) j["grid"] = grid_section(*grid, scene.triangles);
  nlohmann::ordered_json rays = nlohmann::ordered_json::object();
  if (grid && result.counters) {
    const RenderCounters& rc = *result.counters;
    const std::vector<std::uint32_t> theta = occupancies(*grid);
    CellCounters all(grid->info().resolution, rc.classes[0].per_cell());
    std::uint64_t all_predicted = 0;
    double all_seconds = 0;
    for (std::size_t k = 0; k < kRenderClasses; ++k) {
      rays[kRenderClassNames[k]] =
          ray_class_section(measurement(rc.classes[k], theta, rc.predicted_fixed[k], rc.sampled_seconds[k]), std::nullopt);
      all.merge(rc.classes[k]);
      all_predicted += rc.predicted_fixed[k];
      all_seconds += rc.sampled_seconds[k];
    }
    rays["all"] = ray_class_section(measurement(all, theta, all_predicted, all_seconds), std::nullopt);
    if (!result.stats_note.empty()) j["stats_note"] = result.stats_note;
  }
  j["rays"] = rays;
  j["cost"] = nullptr;  // without a calibration (kappa calibrate) there is no prediction
  if (calibration && grid && result.counters) {
    // Thread-seconds of traversal: eq 10 per class from its own counts, and
    // the sampled clock of the same queries (which includes the counting).
    double predicted = 0, measured = 0;
    for (std::size_t k = 0; k < kRenderClasses; ++k) {
      const ClassTotals& t = result.counters->classes[k].totals;
      if (t.rays == 0) continue;
      predicted += double(t.rays) * calibration->seconds_per_ray(double(t.cells) / double(t.rays),
                                                                 double(t.refs) / double(t.rays));
      measured += result.counters->sampled_seconds[k];
    }
    j["cost"] = {{"T0_ns", calibration->T0_ns},
                 {"Ts_ns", calibration->Ts_ns},
                 {"Th_ns", calibration->Th_ns},
                 {"predicted_s", predicted},
                 {"measured_s", measured},
                 {"relative_error", measured > 0 ? nlohmann::ordered_json(predicted / measured - 1.0) : nlohmann::ordered_json()}};
  }
  return j;
}

void print_report_table(const nlohmann::ordered_json& report) {
  if (!report.contains("rays") || report["rays"].empty()) return;
  if (report["cost"].is_object())
    std::printf("cost (eq 10, thread-seconds of traversal): predicted %.3f s, measured %.3f s, error %s (T0 %.1f ns, Ts %.1f ns, Th %.1f ns)\n",
                report["cost"]["predicted_s"].get<double>(), report["cost"]["measured_s"].get<double>(),
                cell(report["cost"]["relative_error"], "%+.3f").c_str(), report["cost"]["T0_ns"].get<double>(),
                report["cost"]["Ts_ns"].get<double>(), report["cost"]["Th_ns"].get<double>());
  std::printf("%-9s %11s %8s %9s %8s %8s %8s %7s %7s\n", "rays", "count", "cells", "predicted", "tests", "refs",
              "p_tot", "r", "kappa");
  for (const auto& [name, c] : report["rays"].items()) {
    std::printf("%-9s %11s %8s %9s %8s %8s %8s %7s %7s\n", name.c_str(), c["count"].dump().c_str(),
                cell(c["cells_per_ray"], "%.2f").c_str(), cell(c["cells_per_ray_predicted"], "%.2f").c_str(),
                cell(c["tests_per_ray"], "%.2f").c_str(), cell(c["refs_per_ray"], "%.2f").c_str(),
                cell(c["p_tot"], "%.2f").c_str(), cell(c["r"], "%.3f").c_str(), cell(c["kappa"], "%.3f").c_str());
  }
}

}  // namespace kappa
