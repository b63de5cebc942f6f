// The models of traversal time that `kappa calibrate` fits and a render's
// report applies to its own counts (never to a time measured in the frame it
// predicts):
//
//   eq 10, the paper's:  t = T0 + p_tot Ts + p_avg Theta_tot kappa Th per ray,
//     with Th per triangle test actually made: Kappa's grid mailboxes, so
//     its tests are the references p_avg Theta_tot kappa less the skipped
//     repeats (fitting Th on references made it absorb the calibration
//     scenes' skip rate);
//   extended: what eq 10 leaves out, each term a measured cost:
//     - a fixed cost per ray for each ray class (camera, shadow, bounce1,
//       bounce2, bounce3+);
//     - per cell step, and more per occupied cell (the walk loads its offsets
//       and loops over its list);
//     - per test and per hit;
//     - per cell step and per test, for each class, a cost times the share of
//       what the step or the test reads beyond the L2 cache, 1 - L2 / bytes:
//       the chance that it waits for memory, which grows with a class's
//       incoherence (camera rays share cache lines with their neighbours,
//       deep bounce rays do not). A step reads the cell records (offsets,
//       occupancy bits, grid2's nodes), a test the lists' references and
//       the triangles: each is judged by its own bytes;
//     - grid2's alone: per sub-grid entered, whose DDA is set up anew.
//   coherent: the extended model and one term more, per cold cell step
//     (stats/recent_cells.h): what a step costs when the walks just before it
//     did not enter its cell. A term per test in a cold cell was dropped: the
//     calibration frames do not tell it from the per-test and miss terms
//     (grid2's came out 28 to 55 ns over five calibrations of one build, 3 to
//     7 times a warm test's cost), and with it the verdict of grid against
//     grid2 on the shared scenes swung with the calibration (5 to 11 of 22
//     rows meeting the ratio target; 12 to 17 without it). Only a render's
//     counting frames count coherence, so only their reports (and the
//     calibration, whose frames are such) have it; the choices' pilots and
//     kappa sweep predict with the extended model.
//
// The form changed twice after it was measured on ../shared/scenes (the
// cost-model and results issues' notes give the forms' errors): the first
// (per-kind T0, log2 of the working set on occupied cells and tests)
// predicted 30 to 120 % too much on the scanned meshes, whose many tests per
// occupied cell share cache lines; the second judged steps and tests by the
// whole working set, and charged the teapot in the stadium's tests for a
// 3.7 MB grid of mostly empty cells when its 6,430 triangles fit in L2, and
// grid2 nothing for entering its sub-grids (its coarse top grids ran 15 to
// 25 % slower than predicted, its fine ones as much faster). The first two
// forms and grid2's term were chosen by leave-one-scene-out error over the
// calibration frames alone; judging steps and tests by their own bytes
// leaves those frames' error as it was (none is a grid of mostly empty
// cells around a small mesh) and is kept because it is what each reads.
//
// All are linear in their constants, so all are fitted the same way:
// least squares of the relative error over the calibration's measurements,
// every constant non-negative (Lawson-Hanson).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "render_counters.h"

namespace kappa {

/// What a model knows of a set of queries: counts, never times.
struct QueryLoad {
  RenderClass ray_class = kBounce1;
  double rays = 0;
  double cells = 0;   ///< cell steps, summed over the rays
  double occupied = 0;  ///< of them, steps into cells holding triangles
  double tests = 0;   ///< triangle tests made
  double skips = 0;   ///< references skipped by the mailbox
  double hits = 0;    ///< rays that hit (any-hit: that were occluded)
  double working_set_bytes = 0;  ///< the accelerator's bytes plus the triangles'
  double cold_cells = 0;  ///< cell steps that were cold (stats/recent_cells.h); 0 where not counted
  double cold_tests = 0;  ///< tests made in cold cells (counted and reported; no model term: time_model.h)
  /// Of the working set, what a test reads: the lists' references
  /// (Accelerator::reference_bytes) and the triangles; the rest is what a
  /// cell step reads.
  double list_bytes = 0;
  double descents = 0;  ///< sub-grids entered (grid2's walks); 0 for one level
};

/// The forms of model.
enum class ModelForm { eq10, extended, coherent };

/// A model linear in its constants: seconds = sum_i c_i f_i(load).
struct TimeModel {
  ModelForm form = ModelForm::eq10;
  std::string name;  ///< "eq10", "extended" or "coherent", for messages
  std::vector<std::string> terms;  ///< the constants' names, in ns
  std::vector<double> ns;          ///< the fitted constants (ns per unit of each feature)
  double cache_bytes = 0;          ///< L2 size the working-set terms are relative to (not eq10)
  bool nested = false;             ///< grid2's: its last term is per sub-grid entered (T_descend)
  double rms_relative_error = 0;   ///< of the fit over its own measurements

  /// The features of `load`, per ray (the fit's rows).
  std::vector<double> features_per_ray(const QueryLoad& load) const;
  /// Predicted seconds for all of load's rays.
  double seconds(const QueryLoad& load) const;
};

/// The models, unfitted (all constants 0).
TimeModel eq10_model();
/// `cache_bytes`: the L2 cache the working-set terms are relative to;
/// `nested`: grid2's, with a term per sub-grid entered.
TimeModel extended_model(double cache_bytes, bool nested = false);
/// The extended model with the coherence term Ts_cold, per cold cell step.
TimeModel coherent_model(double cache_bytes, bool nested = false);

/// This machine's L2 cache per core, from sysconf (1 MiB if unknown).
double l2_cache_bytes();

/// One measurement: a set of queries and the thread-seconds they took.
struct TimedLoad {
  QueryLoad load;
  double seconds = 0;
  std::string label;
};

/// Fits model's constants to the measurements: weighted least squares of
/// the relative error, no constant negative (Lawson-Hanson). Throws std::runtime_error with
/// fewer than 3 measurements, a non-positive time, or measurements that do
/// not determine every constant.
void fit(TimeModel& model, std::span<const TimedLoad> measurements);

/// The constants c >= 0 minimising sum_m (features_m . c / values_m - 1)^2,
/// the relative error, by Lawson-Hanson NNLS; `rms` gets the fit's rms
/// relative error. Throws std::runtime_error naming `what` (and a label) with
/// fewer than 3 rows, a value that is not positive and finite, a non-finite
/// feature, or rows that do not determine every constant.
std::vector<double> fit_relative(const std::vector<std::vector<double>>& features, const std::vector<double>& values,
                                 const std::vector<std::string>& labels, const std::string& what, double& rms);

/// {TERM_ns: ns, ...} of a model's constants, and back: false unless `j`'s
/// "constants" holds every term as a finite number >= 0.
nlohmann::ordered_json constants_json(const std::vector<std::string>& terms, const std::vector<double>& ns);
bool constants_from_json(const nlohmann::json& j, const std::vector<std::string>& terms, std::vector<double>& ns);

nlohmann::ordered_json to_json(const TimeModel& model);
/// Reads what to_json wrote; false if `j` is not such a model.
bool from_json(const nlohmann::json& j, TimeModel& model);

}  // namespace kappa
