#include "renderer/report/render_report.h"

#include "accel/cell_layout.h"
#include "renderer/report/cost_section.h"
#include "renderer/report/report_sections.h"
#include "stats/cast.h"
#include "stats/query_clock.h"
#include "stats/report.h"

namespace kappa {
namespace {

/// One class's summary: p_i from the per-cell counts (of the sampled paths,
/// if per-cell counting was sampled), exact totals otherwise.
ClassSummary summary(const ClassTotals& totals, std::uint64_t per_cell_rays, std::span<const std::uint64_t> visits,
                     const std::vector<std::uint32_t>& theta, double seconds, bool uniform_cells) {
  ClassSummary m;
  m.totals = totals;
  m.per_cell_rays = per_cell_rays;
  const std::uint64_t rays = totals.rays;
  // Without per-cell counts (empty visits): Theta's moments and what the
  // totals give; what needs p_i is undefined.
  m.collusion = collusion_sampled(visits, theta, visits.empty() ? 0 : per_cell_rays, rays, totals.cells, totals.refs);
  if (!visits.empty()) m.sample = collusion(visits, theta, per_cell_rays);
  // Eq 24 needs one cell size: undefined (null) over cells of differing sizes (grid2's leaves).
  m.cells_per_ray_predicted = !uniform_cells ? NAN : rays > 0 ? totals.predicted_cells() / double(rays) : 0.0;
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
                 {"mrays_per_s", result.seconds > 0 ? double(result.rays - result.resumed_rays) / result.seconds * 1e-6 : 0.0},
                 {"passes", result.passes},
                 {"resumed_passes", result.resumed_passes},
                 {"checkpoints", result.checkpoints_saved},
                 {"time_budget_s", frame.time_budget_s > 0 ? nlohmann::ordered_json(frame.time_budget_s) : nullptr},
                 {"target_relmse", frame.target_relmse > 0 ? nlohmann::ordered_json(frame.target_relmse) : nullptr},
                 {"stop_reason", result.stop_reason.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(result.stop_reason)},
                 {"relmse_estimate", result.relmse_estimate},
                 {"spp_min", result.spp_spread.min},
                 {"spp_mean", result.spp_spread.mean},
                 {"spp_max", result.spp_spread.max},
                 {"nonfinite_samples", result.nonfinite_samples},
                 {"interrupted", result.interrupted},
                 {"abandoned_rays", result.abandoned_rays},
                 {"path_variant", result.path_variant},
                 {"settings", settings}};
  if (nlohmann::ordered_json section = accel_section(accel, scene.triangles); !section.is_null())
    j[std::string(accel.name())] = std::move(section);
  const CellLayout* cells = accel.cells();
  const QueryClock& clock = QueryClock::get();
  nlohmann::ordered_json rays = nlohmann::ordered_json::object();
  if (cells && result.counters) {
    const RenderCounters& rc = *result.counters;
    const std::vector<std::uint32_t> theta = cells->occupancies();
    const bool uniform = cells->uniform_cell_size().has_value();
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
          summary(c.totals, c.per_cell_queries(), visits, theta, clock.seconds(rc.ticks[k]), uniform),
          std::nullopt);
      add_level_figures(rays[kRenderClassNames[k]], c.totals, cells->levels());
      all += c.totals;
      all_per_cell_rays += c.per_cell_queries();
      all_seconds += clock.seconds(rc.ticks[k]);
    }
    rays["all"] = ray_class_section(summary(all, all_per_cell_rays, all_visits, theta, all_seconds, uniform),
                                    std::nullopt);
    // Shadow rays the occluder cache answered walked nothing: apart from the class's walks.
    rays["shadow"]["occluder_cache"] = {{"enabled", result.occluder_cache},
                                        {"tests", rc.occluder_cache_tests},
                                        {"hits", rc.occluder_cache_hits}};
    add_level_figures(rays["all"], all, cells->levels());
    // Bounce rays by the lobe that sampled them. A scene whose surfaces are
    // all Lambertian counts no lobes: its bounces are all diffuse.
    nlohmann::ordered_json by_lobe;
    for (std::size_t l = 0; l < kBounceLobes; ++l) {
      ClassTotals t;
      std::uint64_t per_cell_rays = 0;
      double seconds = 0;
      std::vector<std::uint64_t> lobe_visits(per_cell ? theta.size() : 0, 0);
      const auto add = [&](const CellCounters& c, std::uint64_t ticks) {
        t += c.totals;
        per_cell_rays += c.per_cell_queries();
        seconds += clock.seconds(ticks);
        if (per_cell && c.per_cell())
          for (std::size_t i = 0; i < lobe_visits.size(); ++i) lobe_visits[i] += c.visits_at(i);
      };
      if (rc.lobes_counted) add(rc.lobes[l], rc.lobe_ticks[l]);
      else if (l == 0)
        for (std::size_t k : {kBounce1, kBounce2, kBounce3Plus}) add(rc.classes[k], rc.ticks[k]);
      by_lobe[kBounceLobeNames[l]] =
          ray_class_section(summary(t, per_cell_rays, lobe_visits, theta, seconds, uniform), std::nullopt);
    }
    rays["bounce_by_lobe"] = std::move(by_lobe);
    add_stats_block(j, per_cell, result.cell_sample, result.stats_note);
  } else if (result.counters) {
    // Another accelerator: per class what applies to any.
    const RenderCounters& rc = *result.counters;
    ClassTotals all;
    double all_seconds = 0;
    const auto section = [](const ClassTotals& t, double seconds) {
      return any_accel_class_section(t.rays, t.hits, seconds, t.alpha_tests);
    };
    for (std::size_t k = 0; k < kRenderClasses; ++k) {
      rays[kRenderClassNames[k]] = section(rc.classes[k].totals, clock.seconds(rc.ticks[k]));
      all += rc.classes[k].totals;
      all_seconds += clock.seconds(rc.ticks[k]);
    }
    rays["all"] = section(all, all_seconds);
    rays["shadow"]["occluder_cache"] = {{"enabled", result.occluder_cache},
                                        {"tests", rc.occluder_cache_tests},
                                        {"hits", rc.occluder_cache_hits}};
    nlohmann::ordered_json by_lobe;
    for (std::size_t l = 0; l < kBounceLobes; ++l) {
      ClassTotals t;
      double seconds = 0;
      if (rc.lobes_counted) {
        t = rc.lobes[l].totals;
        seconds = clock.seconds(rc.lobe_ticks[l]);
      } else if (l == 0) {
        for (std::size_t k : {kBounce1, kBounce2, kBounce3Plus}) {
          t += rc.classes[k].totals;
          seconds += clock.seconds(rc.ticks[k]);
        }
      }
      by_lobe[kBounceLobeNames[l]] = section(t, seconds);
    }
    rays["bounce_by_lobe"] = std::move(by_lobe);
    add_stats_block(j, false, std::nullopt, "");
  }
  j["rays"] = rays;
  j["cost"] = cost_section(accel, scene.triangles.size(), result, calibration);
  return j;
}

}  // namespace kappa
