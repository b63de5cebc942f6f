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
#include "renderer/render/frame.h"
#include "renderer/scene/scene.h"
#include "stats/calibration.h"

namespace kappa {

struct GridChoice {
  std::unique_ptr<UniformGrid> grid;  ///< the chosen resolution's grid
  nlohmann::ordered_json report;      ///< the report's grid_choice section
  std::string summary;                ///< for the summary line: "chosen by the cost model from ..."
  double seconds = 0;                 ///< pilot, candidates and the chosen grid's build
};

/// Chooses and builds the frame's grid. `frame_paths` is the frame's paths
/// (pixels x spp, or the budget's cap); `calibration_name` is the file the
/// constants came from or "built-in". Throws InputError when no candidate
/// fits `build`'s memory budget.
GridChoice choose_grid_by_model(const Scene& scene, const RenderSettings& settings, double frame_paths,
                                const AccelOptions& build, const Calibration& calibration,
                                const std::string& calibration_name);

}  // namespace kappa
