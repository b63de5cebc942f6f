#include "renderer/render/accel_choice.h"

#include <algorithm>
#include <chrono>
#include <limits>

#include "accel/check.h"
#include "accel/thread_limit.h"
#include "accel/grid2.h"
#include "accel/input_error.h"
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

/// The grid the request's --grid-res names: by the model from `pilot`, the
/// pilot's own grid when it is what `auto` would build, or a new one.
FrameAccelerator build_grid(const Scene& scene, const RenderSettings& settings, const AccelRequest& request,
                            const Calibration& calibration, FramePilot* pilot, TaskProgress* progress) {
  FrameAccelerator out;
  if (request.build.grid_res == "model") {
    KAPPA_CHECK(pilot != nullptr);
    begin_phase(progress, "grid: choosing the resolution by the cost model", 0);
    out.grid_choice = choose_grid_by_model(scene, settings, *pilot, request.build, calibration);
    out.accel = std::move(out.grid_choice->grid);
  } else if (pilot && request.build.grid_res == "auto" && request.build.grid_density == 0 &&
             request.build.grid_max_bytes == 0) {
    out.accel = std::move(pilot->grid);  // GridOptions{}: what make_accelerator would build again
  } else {
    out.accel = make_accelerator("grid", scene.triangles, request.build, progress);
  }
  return out;
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
    if (request.accel != "grid") return {make_accelerator(request.accel, scene.triangles, request.build, progress), {}, nullptr};
    std::optional<FramePilot> pilot;
    if (by_model) pilot = run_frame_pilot(scene, settings, request.frame_paths);
    return build_grid(scene, settings, request, calibration, pilot ? &*pilot : nullptr, progress);
  }

  const auto start = std::chrono::steady_clock::now();
  const std::vector<std::string> candidates = auto_candidates(request.needs_cells);
  nlohmann::ordered_json choice = {{"requested", "auto"}, {"candidates", candidates}, {"calibration", calibration.source}};
  begin_phase(progress, "accel: predicting each accelerator's cost from a pilot of the frame", 0);
  FramePilot pilot = run_frame_pilot(scene, settings, request.frame_paths);
  const ChoiceSettings choice_settings = frame_choice_settings(pilot, settings, request.build, calibration);
  nlohmann::ordered_json predicted, skipped = nlohmann::ordered_json::object();
  const bool with_naive = std::find(candidates.begin(), candidates.end(), "naive") != candidates.end();
  const double naive_s = with_naive ? naive_seconds(pilot, choice_settings, calibration, scene.triangles.size())
                                    : std::numeric_limits<double>::infinity();
  if (with_naive) predicted["naive"] = naive_s;
  // The grid the request would run, and its prediction: the model's choice,
  // or the named resolution evaluated on the pilot like a candidate.
  FrameAccelerator out = build_grid(scene, settings, request, calibration, &pilot, progress);
  double grid_s = 0;
  if (out.grid_choice) {
    grid_s = out.grid_choice->predicted_s;
  } else {
    const auto& grid = static_cast<const UniformGrid&>(*out.accel);
    grid_s = evaluate_candidate(grid, pilot.pilot.segments, choice_settings).total_s();
  }
  predicted["grid"] = grid_s;
  // grid2 as the request would build it, counted by its own queries over the
  // pilot's segments; over the memory budget it is no candidate.
  std::unique_ptr<Accelerator> grid2;
  double grid2_s = std::numeric_limits<double>::infinity();
  try {
    auto built = std::make_unique<NestedGrid>(scene.triangles, grid2_options(request.build), progress);
    grid2_s = predict_grid2(*built, pilot.pilot.segments, choice_settings, calibration.grid2).total_s();
    predicted["grid2"] = grid2_s;
    grid2 = std::move(built);
  } catch (const InputError& e) {
    predicted["grid2"] = nullptr;
    skipped["grid2"] = e.what();
  }
  // grid2 replaces the grid, the paper's accelerator, only when predicted
  // faster by more than its model's own rms relative error over the
  // calibration: within it the two are a tie the model cannot call (Sponza:
  // grid2 predicted 4 % faster, measured 10 % slower).
  const double margin = calibration.grid2.traversal.rms_relative_error;
  std::string chosen = "grid";
  if (naive_s < std::min(grid_s, grid2_s)) {
    chosen = "naive";
    out.accel = make_accelerator("naive", scene.triangles, request.build, progress);
  } else if (grid2_s * (1 + margin) < grid_s) {
    chosen = "grid2";
    out.accel = std::move(grid2);
  }
  if (chosen != "grid") out.grid_choice.reset();  // the report's grid_choice is the grid that ran's
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
  return out;
}

}  // namespace kappa
