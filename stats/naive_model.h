// The naive accelerator's traversal time, as --accel auto predicts it
// beside the grid's (issue #16): T0 + N Th per ray, N the triangles, since a
// closest-hit query tests every one; an occluded shadow ray stops at its
// first occluder, some way down the list, so it costs T0 + N Th_occluded
// instead (Th_occluded < Th: a soup's many occluders stop it after a sixth of
// the list, a scanned mesh's one occluder after most of it). Fitted by
// `kappa calibrate` to naive renders of its small scenes.
#pragma once

#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "render_counters.h"

namespace kappa {

/// What the naive model knows of one class's queries: counts, never times.
struct NaiveLoad {
  RenderClass ray_class = kCamera;
  double rays = 0;
  double hits = 0;       ///< rays that hit (shadow: that were occluded)
  double triangles = 0;  ///< N
};

struct NaiveModel {
  std::vector<std::string> terms = {"T0", "Th", "Th_occluded"};
  std::vector<double> ns = {0, 0, 0};  ///< ns per query, per triangle, per triangle of an occluded shadow ray
  double rms_relative_error = 0;

  /// The load's features per ray, in the order of `terms`.
  static std::vector<double> features_per_ray(const NaiveLoad& load);
  double seconds(const NaiveLoad& load) const;
};

/// One class of a naive calibration frame and the thread-seconds it took.
struct TimedNaiveLoad {
  NaiveLoad load;
  double seconds = 0;
  std::string label;
};

/// Fits the constants (relative error, each >= 0). Throws std::runtime_error with
/// fewer than 3 measurements or measurements that do not determine them.
void fit(NaiveModel& model, std::span<const TimedNaiveLoad> measurements);

nlohmann::ordered_json to_json(const NaiveModel& model);
/// Reads what to_json wrote; false if `j` is not such a model.
bool from_json(const nlohmann::json& j, NaiveModel& model);

}  // namespace kappa
