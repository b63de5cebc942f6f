#include "renderer/render/accel_choice.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <utility>

#include "accel/grid2.h"
#include "core/check.h"
#include "core/input_error.h"
#include "core/thread_limit.h"
#include "renderer/render/tile_costs.h"
#include "stats/grid2_model.h"
#include "stats/naive_model.h"

namespace kappa {
namespace {

/// The naive accelerator's predicted wall seconds for the frame: the
/// pilot's queries per class, scaled to the frame's, by the naive model,
/// shared by the frame's threads (it has no build to speak of).
double naive_seconds(const FramePilot& pilot, const ChoiceSettings& choice, const Calibration& calibration,
                     std::size_t triangles) {
  std::array<double, kRenderClasses> hits{};
  for (const PilotSegment& s : pilot.pilot.segments) hits[s.ray_class] += s.hit;
  double seconds = 0;
  for (std::size_t k = 0; k < kRenderClasses; ++k) {
    const NaiveLoad load{RenderClass(k), double(pilot.pilot.rays[k]) * choice.rays_scale[k], hits[k] * choice.rays_scale[k],
                         double(triangles)};
    seconds += calibration.naive.seconds(load);
  }
  return seconds / double(std::max(1, choice.threads));
}

/// The request's grid is the one the pilot builds (GridOptions{}).
bool is_default_grid(const AccelOptions& build) {
  return build.grid_res == "auto" && build.grid_density == 0 && build.grid_max_bytes == 0;
}

/// The grid the request's --grid-res names: by the model from `pilot`, the
/// pilot's own grid when it is what `auto` would build, or a new one.
FrameAccelerator build_grid(const Scene& scene, const RenderSettings& settings, const AccelRequest& request,
                            const Calibration& calibration, FramePilot* pilot, TaskProgress* progress) {
  FrameAccelerator out;
  if (request.build.grid_res == "model") {
    KAPPA_CHECK(pilot != nullptr);
    begin_phase(progress, "grid: choosing the resolution by the cost model", 0);
    // --grid-res model alone: the coherent model where fitted (it chose
    // resolutions nearer the fastest: issue 50's note).
    out.grid_choice = choose_grid_by_model(scene, settings, *pilot, request.build, calibration, grid_choice_model(calibration));
    out.accel = std::move(out.grid_choice->grid);
  } else if (pilot && pilot->grid && is_default_grid(request.build)) {
    out.accel = std::move(pilot->grid);  // GridOptions{}: what make_accelerator would build again
  } else {
    out.accel = make_accelerator("grid", scene.triangles, request.build, progress);
  }
  return out;
}

/// The grid's predicted seconds for the frame without building it whole:
/// the model's choice (`by_model`, built later if the grid is chosen), the
/// pilot's own grid when it is the request's, or the request's grid counted
/// on a grid that fills only the cells the pilot's walks visit, its
/// Theta_tot by eq 19. Infinite, with the reason in `skipped`, when it does
/// not fit the memory budget.
double predict_grid(const Scene& scene, const RenderSettings& settings, const AccelRequest& request,
                    const Calibration& calibration, const FramePilot& pilot, const ChoiceSettings& choice_settings,
                    std::optional<GridChoice>& by_model, nlohmann::ordered_json& skipped) {
  try {
    if (request.build.grid_res == "model") {
      by_model = predict_grid_by_model(scene, settings, pilot, request.build, calibration, *choice_settings.traversal);
      return by_model->predicted_s;
    }
    if (pilot.grid && is_default_grid(request.build))
      return evaluate_candidate(*pilot.grid, pilot.pilot.segments, choice_settings).total_s();
    const OccupancyModel occupancy(scene.triangles);
    GridOptions options = grid_options(request.build);
    options.occupancy = &occupancy;
    const auto counting = counting_grid(scene.triangles, std::move(options), pilot.pilot.segments);
    return evaluate_candidate(*counting, pilot.pilot.segments, choice_settings, &occupancy).total_s();
  } catch (const InputError& e) {
    skipped["grid"] = e.what();
    return std::numeric_limits<double>::infinity();
  }
}

}  // namespace

std::vector<std::string> auto_candidates(bool needs_cells) {
  if (needs_cells) return {"grid", "grid2"};
  return {"naive", "grid", "grid2"};  // the exact ones; Embree is not exact
}

FrameAccelerator build_frame_accelerator(const Scene& scene, const RenderSettings& settings, const AccelRequest& request,
                                         const Calibration& calibration, TaskProgress* progress) {
  const bool by_model = request.build.grid_res == "model";
  if (request.accel != "auto") {
    if (request.accel != "grid")
      return {make_accelerator(request.accel, scene.triangles, request.build, progress), {}, nullptr, {}};
    std::optional<FramePilot> pilot;
    if (by_model) pilot = run_frame_pilot(scene, settings, request.frame_paths, nullptr, progress);
    FrameAccelerator out = build_grid(scene, settings, request, calibration, pilot ? &*pilot : nullptr, progress);
    if (pilot) out.tile_costs = predicted_tile_costs(pilot->pilot, scene.width, scene.height);
    return out;
  }

  const auto start = std::chrono::steady_clock::now();
  const std::vector<std::string> candidates = auto_candidates(request.needs_cells);
  nlohmann::ordered_json choice = {{"requested", "auto"}, {"candidates", candidates}, {"calibration", calibration.source}};
  nlohmann::ordered_json predicted, skipped = nlohmann::ordered_json::object();
  // grid2 first, as the request would build it: its prediction counts its
  // own queries, so it is built whole whatever is chosen, and the pilot runs
  // through it rather than through a grid of its own (the teapot in a
  // stadium's pilot took 0.41 s through the default grid, its frame 2.2 s
  // through grid2). Over the memory budget it is no candidate, and the pilot
  // builds the default grid as --grid-res model does.
  std::unique_ptr<NestedGrid> grid2;
  try {
    grid2 = std::make_unique<NestedGrid>(scene.triangles, grid2_options(request.build), progress);
  } catch (const InputError& e) {
    skipped["grid2"] = e.what();
  }
  FramePilot pilot = run_frame_pilot(scene, settings, request.frame_paths, grid2.get(), progress);
  begin_phase(progress, "accel: predicting each accelerator's cost from the pilot", 0);
  // --accel auto weighs grid against grid2 and naive by the extended model:
  // with the pilot's estimate of the frame's cold steps, the coherent one
  // chose worse between grid and grid2 (issue 50's note: the Cornell box and
  // Sponza).
  const ChoiceSettings choice_settings =
      frame_choice_settings(pilot, settings, request.build, calibration, calibration.extended);
  const bool with_naive = std::find(candidates.begin(), candidates.end(), "naive") != candidates.end();
  const double naive_s = with_naive ? naive_seconds(pilot, choice_settings, calibration, scene.triangles.size())
                                    : std::numeric_limits<double>::infinity();
  if (with_naive) predicted["naive"] = naive_s;
  // The grid the request would run, predicted and not yet built: building
  // it whole before the choice cost the dragon's frames 0.66 s when grid2
  // ran.
  std::optional<GridChoice> model_choice;
  const double grid_s = predict_grid(scene, settings, request, calibration, pilot, choice_settings, model_choice, skipped);
  predicted["grid"] = std::isfinite(grid_s) ? nlohmann::ordered_json(grid_s) : nlohmann::ordered_json(nullptr);
  const Grid2Model& grid2_model = calibration.grid2;
  const double grid2_s = grid2 ? predict_grid2(*grid2, pilot.pilot.segments, choice_settings, grid2_model).total_s()
                               : std::numeric_limits<double>::infinity();
  predicted["grid2"] = grid2 ? nlohmann::ordered_json(grid2_s) : nlohmann::ordered_json(nullptr);
  // grid2 replaces the grid, the paper's accelerator, only when predicted
  // faster by more than its model's own rms relative error over the
  // calibration: within it the two are a tie the model cannot call (Sponza:
  // grid2 predicted 4 % faster, measured 10 % slower).
  const double margin = grid2_model.traversal.rms_relative_error;
  choice["models"] = {{"grid", choice_settings.traversal->name}, {"grid2", grid2_model.traversal.name}};
  std::string chosen = "grid";
  if (naive_s < std::min(grid_s, grid2_s)) {
    chosen = "naive";
  } else if (grid2_s * (1 + margin) < grid_s || (grid2 && !std::isfinite(grid_s))) {
    chosen = "grid2";
  }
  FrameAccelerator out;
  if (chosen == "grid2") {
    out.accel = std::move(grid2);
  } else {
    grid2.reset();  // before the chosen one's build: the two need not fit at once
    if (chosen == "naive") {
      out.accel = make_accelerator("naive", scene.triangles, request.build, progress);
    } else if (model_choice) {
      begin_phase(progress, "grid: building the cost model's choice", 0);
      build_grid_choice(*model_choice, scene, settings, pilot, request.build, calibration, calibration.extended);
      out.accel = std::move(model_choice->grid);
      out.grid_choice = std::move(model_choice);  // the report's grid_choice is the grid that ran's
    } else {
      out = build_grid(scene, settings, request, calibration, &pilot, progress);
    }
  }
  std::uint64_t pilot_rays = 0;
  for (std::uint64_t r : pilot.pilot.rays) pilot_rays += r;
  choice["chosen"] = chosen;
  if (request.needs_cells)
    choice["reason"] = "the render counts cells (statistics, cost AOVs or a cell map): only cell-based accelerators";
  choice["predicted_s"] = std::move(predicted);
  choice["skipped"] = std::move(skipped);
  choice["grid2_margin"] = margin;
  choice["pilot"] = {{"width", pilot.pilot.width},
                     {"height", pilot.pilot.height},
                     {"rays", pilot_rays},
                     {"seconds", pilot.pilot.seconds}};
  choice["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.accel_choice = std::move(choice);
  out.tile_costs = predicted_tile_costs(pilot.pilot, scene.width, scene.height);
  return out;
}

}  // namespace kappa
