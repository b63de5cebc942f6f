#include "renderer/render/grid_choice.h"

#include <chrono>
#include <cstdio>

#include "core/thread_limit.h"
#include "stats/counters.h"

namespace kappa {

FramePilot run_frame_pilot(const Scene& scene, const RenderSettings& settings, double frame_paths,
                           const Accelerator* through, TaskProgress* progress) {
  const auto start = std::chrono::steady_clock::now();
  FramePilot out;
  // Without `through`, the pilot's hits from the grid `auto` builds at the
  // default budget (any exact accelerator gives the same; --grid-max-bytes
  // bounds the candidates).
  if (!through) {
    out.grid = std::make_unique<UniformGrid>(scene.triangles, GridOptions{}, progress);
    through = out.grid.get();
  }
  const int pixels = pilot_pixels(frame_paths);
  begin_phase(progress, "pilot: " + std::to_string(pixels) + " pixels of the frame, to predict its cost", 0);
  out.pilot = run_pilot(scene, scene.width, scene.height, pixels, *through, settings);
  out.frame_paths = frame_paths;
  out.frame_pixels = double(scene.width) * double(scene.height);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

ChoiceSettings frame_choice_settings(const FramePilot& pilot, const RenderSettings& settings, const AccelOptions& build,
                                     const Calibration& calibration, const TimeModel& traversal) {
  ChoiceSettings s;
  s.traversal = &traversal;
  s.build = &calibration.build;
  const double pilot_paths = double(pilot.pilot.width) * double(pilot.pilot.height);
  s.rays_scale.fill(pilot.frame_paths / pilot_paths);
  s.threads = active_threads();
  s.frame_spp = pilot.frame_pixels > 0 ? pilot.frame_paths / pilot.frame_pixels : 1.0;
  s.max_bytes = build.max_bytes();
  // With statistics on, one shared set of per-cell arrays per class (the
  // least a frame keeps per cell; sampled paths count into it).
  s.stats_bytes_per_cell = settings.stats ? double(kRenderClasses * CellArrays::kBytesPerCell) : 0.0;
  return s;
}

GridChoice predict_grid_by_model(const Scene& scene, const RenderSettings& settings, const FramePilot& pilot,
                                 const AccelOptions& build, const Calibration& calibration, const TimeModel& traversal) {
  const auto start = std::chrono::steady_clock::now();
  const ChoiceSettings choice_settings = frame_choice_settings(pilot, settings, build, calibration, traversal);
  GridChoice out;
  out.resolution = choose_resolution_by_model(scene.triangles, pilot.pilot.segments, choice_settings, false,
                                              pilot.grid.get(), false);
  out.predicted_s = out.resolution.evaluated[out.resolution.chosen].total_s();
  out.seconds = pilot.seconds + std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

void build_grid_choice(GridChoice& out, const Scene& scene, const RenderSettings& settings, FramePilot& pilot,
                       const AccelOptions& build, const Calibration& calibration, const TimeModel& traversal) {
  const auto start = std::chrono::steady_clock::now();
  const ChoiceSettings choice_settings = frame_choice_settings(pilot, settings, build, calibration, traversal);
  ResolutionChoice& choice = out.resolution;
  build_chosen_grid(choice, scene.triangles, choice_settings, pilot.grid.get());
  out.grid = choice.grid ? std::move(choice.grid) : std::move(pilot.grid);
  out.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const Candidate& chosen = choice.evaluated[choice.chosen];
  out.predicted_s = chosen.total_s();
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
  for (std::uint64_t r : pilot.pilot.rays) pilot_rays += r;
  out.report = {{"requested", "model"},
                {"calibration", calibration.source},
                {"model", choice_settings.traversal->name},
                {"chosen", chosen.res.to_string()},
                {"predicted_s", chosen.total_s()},
                {"predicted_traversal_s", chosen.traversal_s},
                {"predicted_build_s", chosen.build_s},
                {"tolerance", choice_settings.tolerance},
                {"frame_paths", pilot.frame_paths},
                {"pilot",
                 {{"width", pilot.pilot.width},
                  {"height", pilot.pilot.height},
                  {"rays", pilot_rays},
                  {"seconds", pilot.pilot.seconds}}},
                {"seconds", out.seconds},
                {"candidates", candidates},
                {"skipped", choice.skipped}};
  char text[160];
  std::snprintf(text, sizeof text, "chosen by the cost model (%zu candidates, predicted %.3f s), in %.3f s",
                choice.evaluated.size(), chosen.total_s(), out.seconds);
  out.summary = text;
}

GridChoice choose_grid_by_model(const Scene& scene, const RenderSettings& settings, FramePilot& pilot,
                                const AccelOptions& build, const Calibration& calibration, const TimeModel& traversal) {
  GridChoice out = predict_grid_by_model(scene, settings, pilot, build, calibration, traversal);
  build_grid_choice(out, scene, settings, pilot, build, calibration, traversal);
  return out;
}

}  // namespace kappa
