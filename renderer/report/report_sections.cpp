#include "renderer/report/report_sections.h"

#include "renderer/version.h"
#include "stats/report.h"

namespace kappa {

nlohmann::ordered_json report_header(const Scene& scene, const Accelerator& accel) {
  nlohmann::ordered_json j;
  j["schema_version"] = kReportSchemaVersion;
  j["kappa_version"] = version_string();
  j["scene"] = scene.source.string();
  j["load_s"] = scene.load_s;
  j["accel"] = std::string(accel.name());
  j["accel_choice"] = nullptr;  // how --accel auto chose, in a render that asked for it
  j["grid_choice"] = nullptr;   // how --grid-res model chose, in a render that asked for it
  return j;
}

void add_stats_block(nlohmann::ordered_json& report, bool per_cell, std::optional<std::uint64_t> cell_sample,
                     const std::string& note) {
  report["stats"] = {{"per_cell", per_cell}};
  if (cell_sample) report["stats"]["cell_sample"] = *cell_sample;
  if (!note.empty()) report["stats_note"] = note;
}

nlohmann::ordered_json any_accel_class_section(std::uint64_t rays, std::uint64_t hits, double seconds) {
  return {{"count", rays},
          {"hit_fraction", rays > 0 ? nlohmann::ordered_json(double(hits) / double(rays)) : nlohmann::ordered_json()},
          {"time_s", seconds}};
}

}  // namespace kappa
