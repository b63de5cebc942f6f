// The cost model's machine constants: eq 10's T0, Ts, Th, the extended
// model's terms and the coherent model's (stats/time_model.h), fitted by `kappa calibrate` to the
// traversal times of its own measurements, kept in a file beside the binary.
#pragma once

#include <filesystem>
#include <optional>
#include <span>
#include <string>

#include <nlohmann/json.hpp>

#include "build_model.h"
#include "grid2_model.h"
#include "naive_model.h"
#include "time_model.h"

namespace kappa {

/// The calibration file's format; files of another one were made by another
/// Kappa and are refused with a word to run `kappa calibrate` again.
/// Format 8: steps and tests are judged by their own bytes, and grid2's
/// models have a term per sub-grid entered (stats/time_model.h); a format-7
/// file's constants were fitted to other features and would mispredict.
/// Format 9: the coherent models have no term per cold test (a format-8
/// file's coherent constants were fitted with one).
inline constexpr int kCalibrationFormat = 9;

struct Calibration {
  TimeModel eq10 = eq10_model();
  TimeModel extended = extended_model(l2_cache_bytes());
  BuildModel build;  ///< the grid's build time (format 4 on), for --grid-res model
  NaiveModel naive;  ///< the naive accelerator's traversal time (format 5 on), for --accel auto
  Grid2Model grid2;  ///< grid2's traversal and build times (format 6 on), for --accel auto
  std::size_t samples = 0;
  std::string machine;  ///< what it was measured on
  std::string clock;    ///< the QueryClock's source ("tsc", "steady_clock")
  std::string source;   ///< the file it was read from, or "built-in" (builtin_calibration.h)
  double probe_s = 0;   ///< machine_probe()'s seconds as it was measured (machine_probe.h); 0 = unknown
  /// The coherent model (time_model.h) of the grid and of grid2, fitted
  /// where the measurements determine it; none in the built-in constants
  /// (optional in the file: null, or absent as a whole).
  std::optional<TimeModel> coherent, grid2_coherent;
};

/// The traversal model --grid-res model chooses a resolution with: the
/// coherent one where it was fitted (it predicts the ratios of two grid
/// resolutions' costs better, and chose resolutions nearer the fastest:
/// issue 50's note), else the extended one. --accel auto weighs the grid
/// against grid2 by the extended model.
inline const TimeModel& grid_choice_model(const Calibration& c) { return c.coherent ? *c.coherent : c.extended; }

/// The coherent model fitted to `measurements`, or nullopt when none of
/// them counted coherence (a cold step) or they do not determine it;
/// `nested`: grid2's measurements, for its model with a term per descent.
std::optional<TimeModel> fit_coherent(std::span<const TimedLoad> measurements, bool nested = false);

/// Fits eq 10, the extended and the coherent model to the measurements. Throws std::runtime_error (an
/// internal error: the measurements are Kappa's own) with fewer than 3, a
/// non-positive time, or measurements that do not determine eq 10's three
/// constants.
Calibration fit_calibration(std::span<const TimedLoad> measurements);

/// What `kappa calibrate` measured, written beside the constants fitted to it.
struct CalibrationMeasurements {
  std::span<const TimedLoad> grid;
  std::span<const TimedBuild> builds;
  std::span<const TimedNaiveLoad> naive;
  std::span<const TimedLoad> grid2;
  std::span<const TimedBuild> grid2_builds;
};

nlohmann::ordered_json to_json(const Calibration& c, const CalibrationMeasurements& measured = {});
/// kappa_calibration.json beside the running executable (build/ for a build
/// tree): where `kappa calibrate` writes and `kappa render` looks by default.
std::filesystem::path default_calibration_path();
/// The running executable (/proc/self/exe), or an empty path where it cannot
/// be read: the folder beside it holds the calibration and converge's references.
std::filesystem::path executable_path();

/// Whether `file` is a calibration of another Kappa's format: JSON whose
/// "format" is not this one's. False for a missing or malformed file (which
/// load_calibration reports) and for a current one.
bool calibration_of_another_format(const std::filesystem::path& file);

/// Reads a calibration file; nullopt if it does not exist. Throws
/// InputError naming the file if it is malformed or of another format.
std::optional<Calibration> load_calibration(const std::filesystem::path& file);

}  // namespace kappa
