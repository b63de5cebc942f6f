// --grid-res model: the grid resolution that minimises a frame's predicted
// cost, N_r E(T) + T_build (seed paper, section 7), over candidates whose
// counts come from the frame's own rays. A pilot (renderer/render/pilot.h)
// records its rays' segments (origin, direction, the hit t); each candidate
// grid walks them without testing a triangle (count_closest_walk), so its
// cells, lists and tests per ray -- and with them its kappa, which moves
// with the resolution -- are its own, and their cold steps are estimated
// (stats/pilot_replay.h); the calibration's coherent model, or the extended
// one without it, turns those counts into seconds (--accel auto passes the
// extended one), the build model gives the build's. The choice depends only
// on the scene, the settings and the constants: never on a time measured in
// the run.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "accel/grid.h"
#include "accel/ray.h"
#include "build_model.h"
#include "pilot_replay.h"
#include "render_counters.h"
#include "time_model.h"

namespace kappa {

/// What a candidate resolution is predicted to cost.
struct Candidate {
  GridResolution res;
  double lambda = 0;           ///< N_c / N
  std::uint64_t theta_tot = 0;  ///< the whole grid's: eq 19's for a counting grid (counting_grid), else its own
  std::uint64_t bytes = 0;     ///< the whole grid's, plus the per-cell statistics' when they are on
  double traversal_s = 0;      ///< N_r E(T): the frame's rays by the settings' traversal model, over the frame's threads (wall seconds)
  double build_s = 0;          ///< T_build, by the build model
  double total_s() const { return traversal_s + build_s; }
};

/// The index of the smallest N_c whose total is within (1 + tolerance) of
/// the least total (paper, section 7: past the knee the cost curve is flat,
/// and fewer cells are less memory); `candidates` in any order, not empty.
std::size_t smallest_within(std::span<const Candidate> candidates, double tolerance = 0.02);

/// The constants and the frame a choice is made for.
struct ChoiceSettings {
  const TimeModel* traversal = nullptr;  ///< the coherent, extended (or eq 10's) model
  const BuildModel* build = nullptr;
  /// Rays of each class in the frame per ray of that class in the pilot.
  std::array<double, kRenderClasses> rays_scale{};
  int threads = 1;                   ///< the frame's threads (the build is parallel)
  double frame_spp = 1;              ///< the frame's samples per pixel, for its camera rays' cold steps
  std::uint64_t max_bytes = 0;       ///< --grid-max-bytes: the grid plus `stats_bytes_per_cell` per cell
  double stats_bytes_per_cell = 0;   ///< the per-cell statistics' bytes a cell when they are on, else 0
  double tolerance = 0.02;
};

/// Counts `segments` on `grid` (its walks without triangle tests) into one
/// load per class, hits from the pilot, working set the grid's bytes and the
/// triangles' (a partial grid: those of the whole grid of `whole_theta_tot`
/// references), cold steps those of a frame of `frame_spp` samples per
/// pixel (stats/pilot_replay.h), none without it.
std::array<QueryLoad, kRenderClasses> count_segments(const UniformGrid& grid, std::span<const PilotSegment> segments,
                                                     std::optional<double> whole_theta_tot = std::nullopt,
                                                     std::optional<double> frame_spp = 1.0);

/// The frame's samples per pixel when `model` has cold-step terms, else none:
/// a model without them is not worth the replay's table lookups.
std::optional<double> cold_steps_spp(const TimeModel& model, double frame_spp);

/// The cells the segments' walks visit on `grid`, as a bitset of N_c bits:
/// its lists play no part (a walk stops at the pilot's hit), so an empty grid
/// of the resolution gives them.
std::vector<std::uint64_t> visited_cells(const UniformGrid& grid, std::span<const PilotSegment> segments);

/// A candidate's grid for counting `segments`: the lists of the cells they
/// visit only (GridOptions::cells_to_fill), so its counting walks are the
/// whole grid's while its build skips the separating-axis tests of every
/// other cell. Throws InputError as the grid does (e.g. offsets over
/// `max_bytes`).
std::unique_ptr<UniformGrid> counting_grid(std::span<const Triangle> triangles, const GridResolution& res,
                                           std::span<const PilotSegment> segments, std::uint64_t max_bytes);
/// The same for the grid `options` describe (its resolution, or its density
/// and budget for auto): what --accel auto predicts a named grid from
/// without building it whole.
std::unique_ptr<UniformGrid> counting_grid(std::span<const Triangle> triangles, GridOptions options,
                                           std::span<const PilotSegment> segments);

/// The candidate's predicted costs from its grid and the pilot's segments.
/// A counting grid's whole Theta_tot, bytes and working set are predicted,
/// Theta_tot by eq 19 (`occupancy`, required then).
Candidate evaluate_candidate(const UniformGrid& grid, std::span<const PilotSegment> segments, const ChoiceSettings& settings,
                             const OccupancyModel* occupancy = nullptr);

/// The candidate resolutions: N_c = lambda N for lambda = 32 * 2^(k/2),
/// k = kMinStep ... kMaxStep (lambda 1/4 ... 1024 in steps of sqrt 2), each
/// near-cubic over the grid's box and within the Theta_tot bound, listed
/// once each, ascending in N_c.
inline constexpr int kMinStep = -14, kMaxStep = 10;
std::vector<GridResolution> candidate_resolutions(std::span<const Triangle> triangles);

/// The search over candidates 0 ... count - 1 (ascending N_c) whose cost
/// `cost(i)` (memoised by the caller; infinite for one that does not fit)
/// is unimodal: from `start` (down first while it does not fit), downhill
/// towards the least cost, then below it while the cost stays within
/// (1 + tolerance) of the least, so that smallest_within over what was
/// evaluated is smallest_within over all.
void search_unimodal(std::size_t count, std::size_t start, const std::function<double(std::size_t)>& cost,
                     double tolerance);

struct ResolutionChoice {
  std::vector<Candidate> evaluated;  ///< in the order they were evaluated
  std::size_t chosen = 0;            ///< index into `evaluated`
  /// The chosen candidate's whole grid, built after the choice; null when
  /// the chosen one is `whole`'s resolution (that grid is the frame's).
  std::unique_ptr<UniformGrid> grid;
  std::vector<std::string> skipped;  ///< candidates over the memory budget
};

/// Walks down the candidates' predicted total from the one nearest lambda =
/// 32 (the cost is unimodal in N_c: traversal falls, build and the empty
/// cells' walk rise), evaluating a candidate only when the search reaches it,
/// then takes smallest_within over those evaluated. Each candidate counts on
/// its counting_grid, except one of `whole`'s resolution (the pilot's grid,
/// built whole), which counts on `whole`. With `exhaustive` every candidate
/// is evaluated (the tests compare the two). Throws InputError when no
/// candidate fits the memory budget. With `build_chosen` false the choice
/// is made and nothing is built (--accel auto builds the grid only once it
/// is chosen over the other accelerators: build_chosen_grid).
ResolutionChoice choose_resolution_by_model(std::span<const Triangle> triangles, std::span<const PilotSegment> segments,
                                            const ChoiceSettings& settings, bool exhaustive = false,
                                            const UniformGrid* whole = nullptr, bool build_chosen = true);

/// Builds `choice`'s chosen grid (none when it is `whole`'s resolution). Its
/// bytes were predicted (eq 19): one that does not fit after all gives way
/// to the next choice, and `chosen` and `skipped` say so. Throws InputError
/// when none fits.
void build_chosen_grid(ResolutionChoice& choice, std::span<const Triangle> triangles, const ChoiceSettings& settings,
                       const UniformGrid* whole = nullptr);

}  // namespace kappa
