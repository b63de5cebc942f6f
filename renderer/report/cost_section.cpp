#include "renderer/report/cost_section.h"

#include "accel/triangle.h"
#include "stats/query_clock.h"

namespace kappa {
namespace {

nlohmann::ordered_json relative_error(double predicted, double measured) {
  return measured > 0 ? nlohmann::ordered_json(predicted / measured - 1.0) : nlohmann::ordered_json();
}

/// The probe's mean around the frame over its time at calibration: how much
/// slower (> 1) or faster the machine ran than when the constants were
/// measured; 0 when either is unknown.
double probe_speed_ratio(const RenderResult& result, const std::optional<Calibration>& calibration) {
  if (!calibration || !(calibration->probe_s > 0) || !(result.probe_before_s > 0) || !(result.probe_after_s > 0))
    return 0;
  return 0.5 * (result.probe_before_s + result.probe_after_s) / calibration->probe_s;
}

nlohmann::ordered_json machine_probe_section(const RenderResult& result, const std::optional<Calibration>& calibration) {
  if (!(result.probe_before_s > 0)) return nullptr;
  const double ratio = probe_speed_ratio(result, calibration);
  const auto or_null = [](double v) { return v > 0 ? nlohmann::ordered_json(v) : nlohmann::ordered_json(); };
  return {{"before_s", result.probe_before_s},
          {"after_s", or_null(result.probe_after_s)},
          {"calibration_s", calibration ? or_null(calibration->probe_s) : nlohmann::ordered_json()},
          {"slowdown", ratio > 0 ? nlohmann::ordered_json(ratio - 1.0) : nlohmann::ordered_json()}};
}

/// A model's prediction of the frame beside its measurement, and the same
/// prediction for the machine as fast as the probe found it around this
/// frame (`ratio`, 0 if unknown): what is left is the model's error, not the
/// minute's.
nlohmann::ordered_json prediction_section(const TimeModel& model, double predicted, double measured, double ratio) {
  return {{"predicted_s", predicted},
          {"relative_error", relative_error(predicted, measured)},
          {"relative_error_at_probe_speed",
           ratio > 0 ? relative_error(predicted * ratio, measured) : nlohmann::ordered_json()},
          {"constants", to_json(model)["constants"]}};
}

}  // namespace

nlohmann::ordered_json cost_section(const Accelerator& accel, std::size_t triangles, const RenderResult& result,
                                    const std::optional<Calibration>& calibration) {
  if (!result.counters) return nullptr;
  const RenderCounters& rc = *result.counters;
  const QueryClock& clock = QueryClock::get();
  // eq 10 is the uniform grid's; the extended model's form has constants
  // for the grid and for grid2 (stats/grid2_model.h), the others have none.
  const bool modelled = calibration && accel.kind() == AccelKind::grid;
  const TimeModel* extended_model = !calibration                          ? nullptr
                                    : accel.kind() == AccelKind::grid  ? &calibration->extended
                                    : accel.kind() == AccelKind::grid2 ? &calibration->grid2.traversal
                                                                       : nullptr;
  const std::optional<TimeModel>* coherent_model = !calibration                          ? nullptr
                                                  : accel.kind() == AccelKind::grid  ? &calibration->coherent
                                                  : accel.kind() == AccelKind::grid2 ? &calibration->grid2_coherent
                                                                                     : nullptr;
  const TimeModel* coherent = coherent_model && *coherent_model ? &**coherent_model : nullptr;
  const double working_set = double(accel.bytes()) + double(triangles * sizeof(Triangle));
  const double list_bytes = double(accel.reference_bytes()) + double(triangles * sizeof(Triangle));

  double measured = 0, eq10 = 0, extended = 0, coherent_s = 0;
  std::uint64_t capped = 0;
  nlohmann::ordered_json per_class = nlohmann::ordered_json::object();
  for (std::size_t k = 0; k < kRenderClasses; ++k) {
    const ClassTotals& t = rc.classes[k].totals;
    const QueryLoad load{RenderClass(k),      double(t.rays),          double(t.cells), double(t.occupied_cells),
                         double(t.tests), double(t.mailbox_skips), double(t.hits),  working_set,
                         double(t.cold_cells), double(t.cold_tests), list_bytes, double(t.descents)};
    const double m = clock.seconds(rc.ticks[k]);
    measured += m;
    capped += rc.capped[k];
    // Coherence is counted by the grids' counting walks alone: null for
    // naive and Embree, whose frames enter no cells.
    const bool cells = accel.kind() == AccelKind::grid || accel.kind() == AccelKind::grid2;
    const auto per_ray = [&](std::uint64_t v) {
      return cells && t.rays > 0 ? nlohmann::ordered_json(double(v) / double(t.rays)) : nlohmann::ordered_json();
    };
    nlohmann::ordered_json c = {{"measured_s", m},
                                {"capped_queries", rc.capped[k]},
                                {"cold_cells_per_ray", per_ray(t.cold_cells)},
                                {"cold_tests_per_ray", per_ray(t.cold_tests)},
                                {"eq10_s", nullptr},
                                {"extended_s", nullptr},
                                {"coherent_s", nullptr}};
    if (modelled) {
      const double e10 = calibration->eq10.seconds(load);
      eq10 += e10;
      c["eq10_s"] = e10;
    }
    if (extended_model) {
      const double ext = extended_model->seconds(load);
      extended += ext;
      c["extended_s"] = ext;
    }
    if (coherent) {
      const double coh = coherent->seconds(load);
      coherent_s += coh;
      c["coherent_s"] = coh;
    }
    per_class[kRenderClassNames[k]] = std::move(c);
  }

  nlohmann::ordered_json j;
  j["calibration"] = calibration ? nlohmann::ordered_json(calibration->source) : nlohmann::ordered_json();
  j["calibration_fit"] = calibration ? nlohmann::ordered_json{{"machine", calibration->machine},
                                                              {"clock", calibration->clock},
                                                              {"samples", calibration->samples}}
                                     : nlohmann::ordered_json();
  j["clock"] = clock.source();
  j["measured_s"] = measured;
  // The loads' bytes (QueryLoad), so that a reader can predict the frame
  // again under another calibration's constants from the report alone.
  j["working_set_bytes"] = working_set;
  j["list_bytes"] = list_bytes;
  j["capped_queries"] = capped;
  j["machine_probe"] = machine_probe_section(result, calibration);
  j["eq10"] = nullptr;
  j["extended"] = nullptr;
  j["coherent"] = nullptr;
  if (modelled) {
    const TimeModel& e = calibration->eq10;
    j["eq10"] = {{"T0_ns", e.ns[0]}, {"Ts_ns", e.ns[1]}, {"Th_ns", e.ns[2]}, {"predicted_s", eq10},
                 {"relative_error", relative_error(eq10, measured)}};
  }
  const double ratio = probe_speed_ratio(result, calibration);
  if (extended_model) j["extended"] = prediction_section(*extended_model, extended, measured, ratio);
  if (coherent) j["coherent"] = prediction_section(*coherent, coherent_s, measured, ratio);
  j["per_class"] = std::move(per_class);
  return j;
}

}  // namespace kappa
