#include "renderer/render/grid_choice.h"

#include <chrono>
#include <cstdio>

#include "accel/thread_limit.h"
#include "renderer/render/pilot.h"
#include "stats/counters.h"
#include "stats/resolution_choice.h"

namespace kappa {

GridChoice choose_grid_by_model(const Scene& scene, const RenderSettings& settings, double frame_paths,
                                const AccelOptions& build, const Calibration& calibration,
                                const std::string& calibration_name) {
  const auto start = std::chrono::steady_clock::now();
  // The pilot's hits from the grid `auto` builds at the default budget (any
  // exact accelerator gives the same; it is freed before the frame renders,
  // and --grid-max-bytes bounds the candidates).
  const UniformGrid pilot_grid(scene.triangles, GridOptions{});
  const Pilot pilot = run_pilot(scene, scene.width, scene.height, pilot_pixels(frame_paths), pilot_grid, settings);

  ChoiceSettings choice_settings;
  choice_settings.traversal = &calibration.extended;
  choice_settings.build = &calibration.build;
  const double pilot_paths = double(pilot.width) * double(pilot.height);
  choice_settings.rays_scale.fill(frame_paths / pilot_paths);
  choice_settings.threads = active_threads();
  choice_settings.max_bytes = build.max_bytes();
  // With statistics on, one shared set of per-cell arrays per class (the
  // least a frame keeps per cell; sampled paths count into it).
  choice_settings.stats_bytes_per_cell = settings.stats ? double(kRenderClasses * CellArrays::kBytesPerCell) : 0.0;
  ResolutionChoice choice = choose_resolution_by_model(scene.triangles, pilot.segments, choice_settings);

  GridChoice out;
  out.grid = std::move(choice.grid);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const Candidate& chosen = choice.evaluated[choice.chosen];
  nlohmann::ordered_json candidates = nlohmann::ordered_json::array();
  for (const Candidate& c : choice.evaluated)
    candidates.push_back({{"res", c.res.to_string()},
                          {"N_c", c.res.cells()},
                          {"lambda", c.lambda},
                          {"theta_tot", c.theta_tot},
                          {"bytes", c.bytes},
                          {"traversal_s", c.traversal_s},
                          {"build_s", c.build_s},
                          {"predicted_s", c.total_s()}});
  std::uint64_t pilot_rays = 0;
  for (std::uint64_t r : pilot.rays) pilot_rays += r;
  out.report = {{"requested", "model"},
                {"calibration", calibration_name},
                {"chosen", chosen.res.to_string()},
                {"predicted_s", chosen.total_s()},
                {"predicted_traversal_s", chosen.traversal_s},
                {"predicted_build_s", chosen.build_s},
                {"tolerance", choice_settings.tolerance},
                {"frame_paths", frame_paths},
                {"pilot", {{"width", pilot.width}, {"height", pilot.height}, {"rays", pilot_rays}, {"seconds", pilot.seconds}}},
                {"seconds", out.seconds},
                {"candidates", candidates},
                {"skipped", choice.skipped}};
  char text[160];
  std::snprintf(text, sizeof text, "chosen by the cost model (%zu candidates, predicted %.3f s), in %.3f s", choice.evaluated.size(),
                chosen.total_s(), out.seconds);
  out.summary = text;
  return out;
}

}  // namespace kappa
