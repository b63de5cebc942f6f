// grid2's cost, as --accel auto predicts it beside naive's and the grid's
// (issue #21): the extended model's form (stats/time_model.h) and the build
// model's (stats/build_model.h), each with constants of grid2's own, which
// `kappa calibrate` fits to grid2's frames and builds. The same form, other
// numbers: a grid2 leaf step costs more than a grid cell step (a sub-grid's
// DDA is set up each time the walk enters a refined cell) and its build
// repeats the overlap tests at each level. grid2's counts for a frame come
// from its own queries over the pilot's segments (closest hit, any hit for
// shadow rays), so they are the walks the frame would make, not a bound.
#pragma once

#include <array>
#include <span>

#include <nlohmann/json.hpp>

#include "accel/grid2.h"
#include "build_model.h"
#include "resolution_choice.h"
#include "time_model.h"

namespace kappa {

struct Grid2Model {
  TimeModel traversal = extended_model(l2_cache_bytes(), /*nested=*/true);
  BuildModel build;
};

/// The pilot's segments through grid2's own queries, one load per class:
/// its leaf steps, occupied leaves, tests, skips and hits, with working set
/// = grid2's bytes and the triangles', cold steps those of a frame of
/// `frame_spp` samples per pixel (stats/pilot_replay.h), none without it.
/// The integer sums do not depend on the thread count.
std::array<QueryLoad, kRenderClasses> count_segments(const NestedGrid& grid, std::span<const PilotSegment> segments,
                                                     std::optional<double> frame_spp = 1.0);

/// What grid2 is predicted to cost for a frame.
struct Grid2Prediction {
  double traversal_s = 0;  ///< the frame's rays by grid2's traversal model, over the frame's threads (wall seconds)
  double build_s = 0;      ///< by grid2's build model from the built structure's N, Theta_tot and leaves
  double total_s() const { return traversal_s + build_s; }
};

/// The prediction for `grid` from the pilot's segments; `settings` gives the
/// rays' scale to the frame and its threads (its models are the grid's and
/// are not used).
Grid2Prediction predict_grid2(const NestedGrid& grid, std::span<const PilotSegment> segments, const ChoiceSettings& settings,
                              const Grid2Model& model);

nlohmann::ordered_json to_json(const Grid2Model& model);
/// Reads what to_json wrote; false if `j` is not such a model.
bool from_json(const nlohmann::json& j, Grid2Model& model);

}  // namespace kappa
