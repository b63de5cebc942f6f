#include "renderer/report/cost_section.h"

#include "accel/triangle.h"
#include "stats/query_clock.h"

namespace kappa {
namespace {

nlohmann::ordered_json relative_error(double predicted, double measured) {
  return measured > 0 ? nlohmann::ordered_json(predicted / measured - 1.0) : nlohmann::ordered_json();
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
  const double working_set = double(accel.bytes()) + double(triangles * sizeof(Triangle));

  double measured = 0, eq10 = 0, extended = 0;
  std::uint64_t capped = 0;
  nlohmann::ordered_json per_class = nlohmann::ordered_json::object();
  for (std::size_t k = 0; k < kRenderClasses; ++k) {
    const ClassTotals& t = rc.classes[k].totals;
    const QueryLoad load{RenderClass(k),      double(t.rays),          double(t.cells), double(t.occupied_cells),
                         double(t.tests), double(t.mailbox_skips), double(t.hits),  working_set};
    const double m = clock.seconds(rc.ticks[k]);
    measured += m;
    capped += rc.capped[k];
    nlohmann::ordered_json c = {{"measured_s", m}, {"capped_queries", rc.capped[k]}, {"eq10_s", nullptr},
                                {"extended_s", nullptr}};
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
  j["capped_queries"] = capped;
  j["eq10"] = nullptr;
  j["extended"] = nullptr;
  if (modelled) {
    const TimeModel& e = calibration->eq10;
    j["eq10"] = {{"T0_ns", e.ns[0]}, {"Ts_ns", e.ns[1]}, {"Th_ns", e.ns[2]}, {"predicted_s", eq10},
                 {"relative_error", relative_error(eq10, measured)}};
  }
  if (extended_model)
    j["extended"] = {{"predicted_s", extended},
                     {"relative_error", relative_error(extended, measured)},
                     {"constants", to_json(*extended_model)["constants"]}};
  j["per_class"] = std::move(per_class);
  return j;
}

}  // namespace kappa
