// The cost model's machine constants (eq 10): T0 per ray, Ts per cell step,
// Th per triangle reference, fitted by least squares to measured traversal
// times, and the prediction they give for a frame.
#pragma once

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace kappa {

/// One measured ray set: mean traversal seconds per ray, with the mean cells
/// and triangle references per ray counted on the same rays.
struct CostSample {
  double seconds_per_ray = 0;
  double cells_per_ray = 0;
  double refs_per_ray = 0;
  std::string label;  ///< scene, resolution and class, for the record
};

struct Calibration {
  double T0_ns = 0, Ts_ns = 0, Th_ns = 0;
  std::size_t samples = 0;
  double rms_relative_error = 0;  ///< of the fit over its own samples
  std::string machine;            ///< what it was measured on

  /// eq 10: T0 + p_tot Ts + p_avg Theta_tot kappa Th per ray, in seconds.
  double seconds_per_ray(double cells_per_ray, double refs_per_ray) const {
    return (T0_ns + cells_per_ray * Ts_ns + refs_per_ray * Th_ns) * 1e-9;
  }
};

/// Least squares fit of seconds = T0 + cells Ts + refs Th over the samples,
/// each weighted by 1/seconds (relative errors count alike), with no
/// constant negative (non-negative least squares). Throws
/// std::runtime_error (an internal error: the measurements are Kappa's own)
/// with fewer than 3 samples or a singular system.
Calibration fit_calibration(std::span<const CostSample> samples);

nlohmann::ordered_json to_json(const Calibration& c, std::span<const CostSample> samples = {});
/// kappa_calibration.json beside the running executable (build/ for a build
/// tree): where `kappa calibrate` writes and `kappa render` looks by default.
std::filesystem::path default_calibration_path();

/// Reads a calibration file; nullopt if it does not exist. Throws
/// InputError naming the file if it is malformed.
std::optional<Calibration> load_calibration(const std::filesystem::path& file);

}  // namespace kappa
