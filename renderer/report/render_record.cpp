#include "renderer/report/render_record.h"

#include <cstdio>

#include "core/hash.h"
#include "core/input_file.h"

namespace kappa {

std::string hex16(std::uint64_t h) {
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

std::string input_hash(const Scene& scene) {
  // Each input's hash was taken from its bytes as they were read (no file
  // is opened again); chained here in the scene's order.
  std::uint64_t h = kFnv1aOffset;
  for (const auto& file : scene.inputs) {
    const std::optional<InputRecord> record = input_read(file);
    const std::uint64_t part = record ? record->hash : fnv1a64(file.string());
    char bytes[8];
    for (int i = 0; i < 8; ++i) bytes[i] = char(part >> (8 * i));
    h = fnv1a64(std::string_view(bytes, 8), h);
  }
  return hex16(h);
}

RenderRecord render_record(const RenderOptions& options, const Scene& scene, const std::string& grid_res, int spp,
                           const Budget& budget) {
  RenderRecord record = {
      {"scene", scene.source.string()},
      {"input_hash", input_hash(scene)},
      {"accel", options.accel},
      {"grid_res", grid_res},
      {"width", scene.width},
      {"height", scene.height},
      {"spp", spp},
      {"sampler", options.sampler},
      {"light_sampling", options.light_sampling},
      {"max_depth", options.max_depth},
      {"rr_depth", options.rr_depth},
      {"russian_roulette", !options.no_rr},
      {"seed", double(options.seed)},
      {"aov", options.aov},
      {"stats", options.stats},
      {"cell_sample", options.cell_sample},
  };
  if (budget.time_s > 0) record.emplace_back("time_budget", options.time_budget);
  if (budget.target_relmse > 0) record.emplace_back("target_relmse", budget.target_relmse);
  if (budget.adaptive) {
    record.emplace_back("adaptive", true);
    record.emplace_back("adaptive_min_spp", budget.adaptive_min_spp);
  }
  return record;
}

nlohmann::ordered_json to_json(const RenderRecord& record) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (const auto& [key, value] : record) std::visit([&, k = key](const auto& v) { j[k] = v; }, value);
  return j;
}

}  // namespace kappa
