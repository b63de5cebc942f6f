#include "renderer/report/report_sections.h"

#include <algorithm>

#include "core/error.h"
#include "core/input_file.h"
#include "renderer/image/image_library.h"
#include "renderer/report/render_record.h"
#include "renderer/version.h"
#include "stats/report.h"

namespace kappa {

nlohmann::ordered_json mpi_section(const std::vector<ProcessShare>& shares, const std::vector<double>& tile_seconds,
                                   const std::vector<double>& tile_predicted) {
  nlohmann::ordered_json per_rank = nlohmann::ordered_json::array(), threads = nlohmann::ordered_json::array();
  bool same_threads = true;
  double slowest = 0, sum = 0;
  for (const ProcessShare& s : shares) {
    per_rank.push_back({{"rank", s.process}, {"host", s.host}, {"threads", s.threads}, {"tiles", s.tiles},
                        {"rays", s.rays}, {"time_s", s.time_s}});
    threads.push_back(s.threads);
    same_threads = same_threads && s.threads == shares.front().threads;
    slowest = std::max(slowest, s.time_s);
    sum += s.time_s;
  }
  nlohmann::ordered_json j;
  j["ranks"] = shares.size();
  j["threads_per_rank"] = same_threads && !shares.empty() ? nlohmann::ordered_json(shares.front().threads) : threads;
  j["per_rank"] = per_rank;
  j["imbalance"] = sum > 0 ? nlohmann::ordered_json(slowest / (sum / double(shares.size()))) : nlohmann::ordered_json();
  j["tile_size"] = kTileSize;
  j["tile_seconds"] = tile_seconds;
  j["first_pass_order"] = tile_predicted.empty() ? "tiles" : "pilot";
  j["tile_predicted"] = tile_predicted.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(tile_predicted);
  return j;
}

nlohmann::ordered_json warnings_section(const std::vector<WarningKind>& kinds) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  // As printed: file content in a warning (a Latin-1 name) is not UTF-8.
  for (const WarningKind& k : kinds)
    list.push_back({{"kind", printable_line(k.kind)}, {"count", k.count}, {"first", printable_line(k.first)}});
  return list;
}

nlohmann::ordered_json images_section(const Scene& scene) {
  nlohmann::ordered_json j;
  // Whether this process loaded the OpenImageIO module: never for a scene
  // without textures or an environment image (and no PNG preview).
  j["module_loaded"] = image_library_loaded();
  j["texture_maps"] = scene.texture_maps.size();
  j["opacity_masks"] = scene.opacity_masks.size();
  if (scene.environment_image) {
    j["environment_image"] = {{"file", scene.environment_file.string()},
                              {"width", scene.environment_image->width},
                              {"height", scene.environment_image->height},
                              {"rotation_deg", scene.environment_rotation_deg}};
  } else {
    j["environment_image"] = nullptr;
  }
  j["texture_cache"] = nullptr;
  if (image_library_loaded() && !scene.texture_maps.empty()) {
    const TextureCacheStats c = image_library().statistics();
    const double hit_rate =
        c.tile_lookups > 0 ? 1.0 - double(c.tiles_read) / double(c.tile_lookups) : 0.0;
    j["texture_cache"] = {{"tile_lookups", c.tile_lookups}, {"tiles_read", c.tiles_read},
                          {"hit_rate", c.tile_lookups > 0 ? nlohmann::ordered_json(hit_rate) : nlohmann::ordered_json()},
                          {"bytes_read", c.bytes_read},     {"cache_bytes", c.cache_bytes},
                          {"cache_limit_bytes", c.cache_limit_bytes}, {"files", c.files},
                          {"file_io_s", c.file_io_s}};
  }
  return j;
}

nlohmann::ordered_json report_header(const Scene& scene, const Accelerator& accel) {
  nlohmann::ordered_json j;
  j["schema_version"] = kReportSchemaVersion;
  j["kappa_version"] = version_string();
  j["scene"] = scene.source.string();
  j["load_s"] = scene.load_s;
  // Provenance: each file read, its size and the hash of the bytes parsed.
  j["inputs"] = nlohmann::ordered_json::array();
  for (const auto& file : scene.inputs) {
    const std::optional<InputRecord> record = input_read(file);
    j["inputs"].push_back({{"file", printable_line(file.string())},
                           {"bytes", record ? nlohmann::ordered_json(record->bytes) : nlohmann::ordered_json(nullptr)},
                           {"hash", record ? hex16(record->hash) : std::string()}});
  }
  j["images"] = images_section(scene);
  j["gltf"] = nlohmann::ordered_json::array();
  for (const GltfSummary& g : scene.gltf_files)
    j["gltf"].push_back({{"file", g.file.string()}, {"nodes", g.nodes}, {"meshes", g.meshes},
                         {"mesh_instances", g.mesh_instances}, {"primitives", g.primitives},
                         {"triangles", g.triangles}, {"cameras", g.cameras}, {"lights", g.lights},
                         {"materials", g.materials}, {"images", g.images}});
  j["camera"] = nullptr;
  if (scene.camera_index >= 0)
    j["camera"] = {{"name", scene.cameras[std::size_t(scene.camera_index)].name},
                   {"index", scene.cameras[std::size_t(scene.camera_index)].file_index}};
  j["punctual_lights"] = scene.punctual_lights.size();
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

nlohmann::ordered_json any_accel_class_section(std::uint64_t rays, std::uint64_t hits, double seconds,
                                               std::uint64_t alpha_tests) {
  return {{"count", rays},
          {"hit_fraction", rays > 0 ? nlohmann::ordered_json(double(hits) / double(rays)) : nlohmann::ordered_json()},
          {"alpha_tests", alpha_tests},
          {"time_s", seconds}};
}

}  // namespace kappa
