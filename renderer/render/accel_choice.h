// The accelerator a render runs: the one --accel names, or with --accel auto
// the exact accelerator predicted fastest for the frame (issues #16, #21),
// and the grid's resolution by --grid-res, `model` included. `auto` decides
// from predictions alone, never from times measured in the run: the naive
// accelerator's by its calibrated T0 + N Th per ray (stats/naive_model.h),
// the grid's by the extended and build models on its own counting walks of
// the frame's pilot (stats/resolution_choice.h), grid2's by its own
// constants of those models on its own queries of the pilot's segments
// (stats/grid2_model.h). Where the render asks for cell statistics (--stats
// on, --aov cost, --cell-map) only the cell-based accelerators, grid and
// grid2, can give them. Choosing costs one build: grid2 is built first and
// the pilot runs through it, the grid is predicted from counting walks and
// built only when chosen, naive has nothing to build.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "accel/accel.h"
#include "accel/factory.h"
#include "core/task_progress.h"
#include "renderer/render/frame.h"
#include "renderer/render/grid_choice.h"
#include "renderer/scene/scene.h"
#include "stats/calibration.h"

namespace kappa {

/// What the command line asks of the frame's accelerator.
struct AccelRequest {
  std::string accel = "grid";  ///< a name of accelerator_names(), or "auto"
  AccelOptions build;          ///< --grid-res (`model` too), --grid-density, --grid-max-bytes
  bool needs_cells = false;    ///< statistics, the cost AOVs or a cell map: only cell-based accelerators
  double frame_paths = 0;      ///< the frame's paths, for the pilot's scale
};

/// The exact accelerators `auto` may run for a request: the cell-based ones
/// when it needs cells, else every exact one.
std::vector<std::string> auto_candidates(bool needs_cells);

struct FrameAccelerator {
  std::unique_ptr<Accelerator> accel;
  std::optional<GridChoice> grid_choice;  ///< with --grid-res model
  nlohmann::ordered_json accel_choice;    ///< the report's accel_choice with --accel auto, else null
  std::vector<double> tile_costs;         ///< by tile, predicted from the pilot where one ran (tile_costs.h), else empty
};

/// Builds the frame's accelerator. Throws InputError as make_accelerator and
/// choose_grid_by_model do.
FrameAccelerator build_frame_accelerator(const Scene& scene, const RenderSettings& settings, const AccelRequest& request,
                                         const Calibration& calibration, TaskProgress* progress);

}  // namespace kappa
