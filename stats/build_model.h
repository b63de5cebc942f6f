// The time a uniform grid takes to build, as the resolution chooser
// (resolution_choice.h) predicts it for each candidate: linear in the
// triangles (bounds, then two passes over them), the references (each
// counted, then written and sorted) and the cells (offsets, prefix sum,
// occupancy bits), fitted by `kappa calibrate` to its own grids' builds.
#pragma once

#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace kappa {

struct BuildModel {
  std::vector<std::string> terms = {"per_triangle", "per_reference", "per_cell"};
  std::vector<double> ns = {0, 0, 0};  ///< ns per triangle, per reference, per cell
  int threads = 1;                     ///< the threads the fitted builds ran on
  double rms_relative_error = 0;

  /// Seconds to build N triangles into `cells` cells holding `theta_tot`
  /// references with `run_threads` threads (the fit's time scaled by
  /// threads / run_threads: the passes are parallel loops).
  double seconds(double N, double theta_tot, double cells, int run_threads) const;
};

/// One grid a calibration built, and the seconds it took.
struct TimedBuild {
  double N = 0, theta_tot = 0, cells = 0, seconds = 0;
  std::string label;
};

/// Fits the constants (relative error, each >= 0). Throws std::runtime_error
/// with fewer than 3 builds or builds that do not determine them.
void fit(BuildModel& model, std::span<const TimedBuild> builds, int threads);

nlohmann::ordered_json to_json(const BuildModel& model);
/// Reads what to_json wrote; false if `j` is not such a model.
bool from_json(const nlohmann::json& j, BuildModel& model);

}  // namespace kappa
