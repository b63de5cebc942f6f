#include "renderer/report/render_report.h"

#include "accel/cell_layout.h"
#include "renderer/report/report_sections.h"
#include "stats/cast.h"
#include "stats/report.h"

namespace kappa {
namespace {

/// One class's summary: p_i from the per-cell counts (of the sampled paths,
/// if per-cell counting was sampled), exact totals otherwise.
ClassSummary summary(const ClassTotals& totals, std::uint64_t per_cell_rays, std::span<const std::uint64_t> visits,
                     const std::vector<std::uint32_t>& theta, double seconds) {
  ClassSummary m;
  m.totals = totals;
  m.per_cell_rays = per_cell_rays;
  const std::uint64_t rays = totals.rays;
  // Without per-cell counts (empty visits): Theta's moments and what the
  // totals give; what needs p_i is undefined.
  m.collusion = collusion_sampled(visits, theta, visits.empty() ? 0 : per_cell_rays, rays, totals.cells, totals.refs);
  if (!visits.empty()) m.sample = collusion(visits, theta, per_cell_rays);
  m.cells_per_ray_predicted = rays > 0 ? totals.predicted_cells() / double(rays) : 0.0;
  m.time_s = seconds;
  return m;
}

}  // namespace

nlohmann::ordered_json render_report(const Scene& scene, const Accelerator& accel, const FrameFacts& frame,
                                     const RenderResult& result, const std::optional<Calibration>& calibration,
                                     const nlohmann::ordered_json& settings) {
  nlohmann::ordered_json j = report_header(scene, accel);
  j["render"] = {{"width", frame.width},
                 {"height", frame.height},
                 {"spp", frame.spp},
                 {"threads", frame.threads},
                 {"seed", frame.seed},
                 {"time_s", result.seconds},
                 {"rays", result.rays},
                 {"mrays_per_s", result.seconds > 0 ? double(result.rays) / result.seconds * 1e-6 : 0.0},
                 {"settings", settings}};
  if (nlohmann::ordered_json section = accel_section(accel, scene.triangles); !section.is_null())
    j[std::string(accel.name())] = std::move(section);
  const CellLayout* cells = accel.cells();
  nlohmann::ordered_json rays = nlohmann::ordered_json::object();
  if (cells && result.counters) {
    const RenderCounters& rc = *result.counters;
    const std::vector<std::uint32_t> theta = cells->occupancies();
    const bool per_cell = rc.classes[0].per_cell();
    std::vector<std::uint64_t> visits, all_visits(per_cell ? theta.size() : 0, 0);
    ClassTotals all;
    std::uint64_t all_per_cell_rays = 0;
    double all_seconds = 0;
    for (std::size_t k = 0; k < kRenderClasses; ++k) {
      const CellCounters& c = rc.classes[k];
      if (per_cell) {
        visits = c.visits();
        for (std::size_t i = 0; i < visits.size(); ++i) all_visits[i] += visits[i];
      }
      rays[kRenderClassNames[k]] = ray_class_section(
          summary(c.totals, c.per_cell_queries(), visits, theta, rc.sampled_seconds[k]),
          std::nullopt);
      all += c.totals;
      all_per_cell_rays += c.per_cell_queries();
      all_seconds += rc.sampled_seconds[k];
    }
    rays["all"] = ray_class_section(summary(all, all_per_cell_rays, all_visits, theta, all_seconds),
                                    std::nullopt);
    add_stats_block(j, per_cell, result.cell_sample, result.stats_note);
  } else if (result.counters) {
    // Another accelerator: per class what applies to any.
    const RenderCounters& rc = *result.counters;
    ClassTotals all;
    double all_seconds = 0;
    const auto section = [](const ClassTotals& t, double seconds) {
      return any_accel_class_section(t.rays, t.hits, seconds);
    };
    for (std::size_t k = 0; k < kRenderClasses; ++k) {
      rays[kRenderClassNames[k]] = section(rc.classes[k].totals, rc.sampled_seconds[k]);
      all += rc.classes[k].totals;
      all_seconds += rc.sampled_seconds[k];
    }
    rays["all"] = section(all, all_seconds);
    add_stats_block(j, false, std::nullopt, "");
  }
  j["rays"] = rays;
  j["cost"] = nullptr;  // without a calibration (kappa calibrate) there is no prediction
  // The calibrated constants are the uniform grid's (kappa calibrate times its walk).
  if (calibration && accel.kind() == AccelKind::grid && result.counters) {
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

}  // namespace kappa
