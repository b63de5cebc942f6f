// The two models of traversal time that `kappa calibrate` fits and a render's
// report applies to its own counts (never to a time measured in the frame it
// predicts):
//
//   eq 10, the paper's:  t = T0 + p_tot Ts + p_avg Theta_tot kappa Th per ray,
//     with Th per triangle test actually made: Kappa's grid mailboxes, so
//     its tests are the references p_avg Theta_tot kappa less the skipped
//     repeats (fitting Th on references made it absorb the calibration
//     scenes' skip rate);
//   extended: what eq 10 leaves out, each term a measured cost:
//     - a fixed cost per ray for each kind of query (camera rays are
//       coherent, bounce rays are not, an any-hit query stops early);
//     - per cell step, apart for empty cells (a bit in the occupancy words)
//       and occupied ones (the walk loads their offsets and loops over their
//       lists: measured 20 to 30 times dearer);
//     - per occupied cell and per test, a cost that grows with log2 of the
//       working set (the cell arrays and triangles) over the L2 cache: a walk
//       over a grid larger than the cache waits for memory;
//     - per mailbox skip (a reference already tested by this ray);
//     - per hit (a hit finishes its barycentrics and the surface record).
//
// Both are linear in their constants, so both are fitted the same way: least
// squares of the relative error over the calibration's measurements, every
// constant non-negative.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace kappa {

/// The kind of a visibility query, as the extended model tells them apart.
enum class QueryKind { camera, closest, any };

/// What a model knows of a set of queries: counts, never times.
struct QueryLoad {
  QueryKind kind = QueryKind::closest;
  double rays = 0;
  double cells = 0;   ///< cell steps, summed over the rays
  double occupied = 0;  ///< of them, steps into cells holding triangles
  double tests = 0;   ///< triangle tests made
  double skips = 0;   ///< references skipped by the mailbox
  double hits = 0;    ///< rays that hit (any-hit: that were occluded)
  double working_set_bytes = 0;  ///< the accelerator's bytes plus the triangles'
};

/// A model linear in its constants: seconds = sum_i c_i f_i(load).
struct TimeModel {
  std::string name;
  std::vector<std::string> terms;  ///< the constants' names, in ns
  std::vector<double> ns;          ///< the fitted constants (ns per unit of each feature)
  double cache_bytes = 0;          ///< L2 size the working-set terms are relative to (extended only)
  double rms_relative_error = 0;   ///< of the fit over its own measurements

  /// The features of `load`, per ray (the fit's rows).
  std::vector<double> features_per_ray(const QueryLoad& load) const;
  /// Predicted seconds for all of load's rays.
  double seconds(const QueryLoad& load) const;
};

/// The two models, unfitted (all constants 0).
TimeModel eq10_model();
/// `cache_bytes`: the L2 cache the working-set terms are relative to.
TimeModel extended_model(double cache_bytes);

/// This machine's L2 cache per core, from sysconf (1 MiB if unknown).
double l2_cache_bytes();

/// One measurement: a set of queries and the thread-seconds they took.
struct TimedLoad {
  QueryLoad load;
  double seconds = 0;
  std::string label;
};

/// Fits model's constants to the measurements: weighted least squares of
/// the relative error, no constant negative (every subset of free constants
/// is tried; the best feasible one wins). Throws std::runtime_error with
/// fewer than 3 measurements, a non-positive time, or measurements that do
/// not determine every constant.
void fit(TimeModel& model, std::span<const TimedLoad> measurements);

nlohmann::ordered_json to_json(const TimeModel& model);
/// Reads what to_json wrote; false if `j` is not such a model.
bool from_json(const nlohmann::json& j, TimeModel& model);

}  // namespace kappa
