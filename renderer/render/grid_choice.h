// --grid-res model in a render: the pilot of the frame through a grid at the
// default density, then the resolution the cost model predicts cheapest for
// the frame's rays (stats/resolution_choice.h), and the report's account of
// it (`grid_choice`).
#pragma once

#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "accel/factory.h"
#include "accel/grid.h"
#include "core/task_progress.h"
#include "renderer/render/frame.h"
#include "renderer/render/pilot.h"
#include "renderer/scene/scene.h"
#include "stats/calibration.h"
#include "stats/resolution_choice.h"

namespace kappa {

/// A frame's pilot and the grid it ran through: what --grid-res model and
/// --accel auto predict from (one pilot when both are asked for).
struct FramePilot {
  std::unique_ptr<UniformGrid> grid;  ///< the grid `auto` builds at the default budget, when the pilot built it
  Pilot pilot;
  double frame_paths = 0;  ///< the frame's paths (pixels x spp, or the budget's cap)
  double frame_pixels = 0;  ///< the frame's pixels
  double seconds = 0;      ///< the pilot grid's build (when it built one) and the pilot
};

/// Runs the pilot of a frame of `frame_paths` paths through `through`, or
/// when it is null through a grid it builds at the default budget (then
/// FramePilot::grid). Any exact accelerator records the same segments.
/// `progress` sees the grid's build and the pilot as phases.
FramePilot run_frame_pilot(const Scene& scene, const RenderSettings& settings, double frame_paths,
                           const Accelerator* through = nullptr, TaskProgress* progress = nullptr);

/// The chooser's settings for the frame: `traversal` (one of the
/// calibration's models: grid_choice_model's for --grid-res model, the
/// extended one for --accel auto) and its build model, the pilot's rays
/// scaled to the frame's, the frame's threads and memory budget.
ChoiceSettings frame_choice_settings(const FramePilot& pilot, const RenderSettings& settings, const AccelOptions& build,
                                     const Calibration& calibration, const TimeModel& traversal);

struct GridChoice {
  ResolutionChoice resolution;        ///< the candidates evaluated and the one chosen
  std::unique_ptr<UniformGrid> grid;  ///< the chosen resolution's grid, once built
  nlohmann::ordered_json report;      ///< the report's grid_choice section
  std::string summary;                ///< for the summary line: "chosen by the cost model from ..."
  double predicted_s = 0;             ///< the chosen candidate's predicted traversal and build
  double seconds = 0;                 ///< pilot, candidates and the chosen grid's build
};

/// Chooses the frame's grid resolution from `pilot` and builds nothing:
/// `predicted_s` is the choice's (--accel auto weighs it against the other
/// accelerators before building any). Throws InputError when no candidate
/// fits `build`'s memory budget.
GridChoice predict_grid_by_model(const Scene& scene, const RenderSettings& settings, const FramePilot& pilot,
                                 const AccelOptions& build, const Calibration& calibration,
                                 const TimeModel& traversal);

/// Builds the chosen grid (the pilot's grid, when it is the chosen
/// resolution, becomes the frame's) and writes the report and summary; the
/// calibration's `source` names it. Throws InputError when no candidate fits.
void build_grid_choice(GridChoice& choice, const Scene& scene, const RenderSettings& settings, FramePilot& pilot,
                       const AccelOptions& build, const Calibration& calibration,
                       const TimeModel& traversal);

/// Both: the grid --grid-res model gives the frame.
GridChoice choose_grid_by_model(const Scene& scene, const RenderSettings& settings, FramePilot& pilot,
                                const AccelOptions& build, const Calibration& calibration,
                                const TimeModel& traversal);

}  // namespace kappa
