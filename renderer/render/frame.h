// What a frame is asked (RenderSettings) and what it gives back
// (RenderResult), apart from render() itself so that the frames of each
// query choice (render_counting.h, tile_loop.h) and the report share them.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "renderer/render/film.h"
#include "renderer/render/frame_accumulator.h"
#include "renderer/render/pass_planner.h"
#include "renderer/render/path_variant.h"
#include "renderer/render/sampler_kind.h"
#include "renderer/render/tile_schedule.h"
#include "stats/per_cell_budget.h"
#include "stats/render_counters.h"

namespace kappa {

struct FrameProgress;  // frame_progress.h, which reads PassControl

/// A progressive render's control (render_command.cpp, tests). Without one
/// a frame is one pass of RenderSettings::spp.
struct PassControl {
  PassPlanner* planner = nullptr;                ///< sizes the passes and stops them
  const std::atomic<bool>* interrupt = nullptr;  ///< once set, the pass in progress is abandoned
  /// After each completed pass, with the passes so far (for a progress line).
  std::function<void(const FrameState&, int)> on_pass;
  /// --checkpoint-every: asked after each completed pass whether a
  /// checkpoint is due (with processes sharing the frame, the writer's
  /// answer is every one's); given the frame so far when one is.
  std::function<bool()> checkpoint_due = nullptr;
  std::function<void(const FrameProgress&)> checkpoint = nullptr;
  /// --resume: the passes a checkpoint saved, to begin from (with
  /// processes sharing the frame, each has the pixels; only the writer's
  /// has the counts and counters, which the others would add again).
  const FrameProgress* resume = nullptr;
};

struct RenderSettings {
  int spp = 16;
  int max_depth = 32;       ///< bounces after the camera ray; 1 = direct lighting only
  int rr_depth = 5;         ///< Russian roulette from this many bounces on; < 0 disables it (render's default)
  std::uint64_t seed = 0;
  SamplerKind sampler = SamplerKind::sobol;  ///< samplers.h (render's default); stratified needs spp, so no budget
  LightSampling light_sampling = LightSampling::mis;  ///< path_variant.h
  /// The integrator compiled for what the scene has (false: the general one,
  /// the same image, to measure what specialising saves).
  bool specialise = true;
  /// Shadow rays test the triangle that last occluded a ray toward the same
  /// light first (occluder_cache.h), where the accelerator can (the grids):
  /// the same image, less work; false to measure what it saves.
  bool occluder_cache = true;
  AovSelection aov;
  bool stats = false;       ///< per-class counters (grid only), chosen once per frame
  std::uint64_t stats_max_bytes = std::uint64_t(1) << 32;  ///< budget for per-cell counters plus the grid
  /// Per-cell counts for 1 path in this many (1 = every path; 0 = auto, see
  /// auto_cell_sample); per-class totals always count every ray.
  std::uint64_t cell_sample = 0;
  PassControl* passes = nullptr;  ///< a progressive render's budgets, or one pass of spp
  /// The tiles this process renders in each pass (tile_schedule.h), or
  /// nullptr for every tile. With `passes` too, the schedule's writer
  /// decides each pass (its planner's) and every process keeps every
  /// pixel's sums (TileSchedule::share_pass_state).
  TileSchedule* tiles = nullptr;
  /// Test-only: samples for which this returns true read NaN, as a broken
  /// BSDF's would (tests show that such samples are dropped, not averaged).
  bool (*test_nonfinite)(std::uint64_t pixel, std::uint64_t sample) = nullptr;
};

struct RenderResult {
  double seconds = 0;
  std::shared_ptr<const RenderCounters> counters;  ///< merged per-class counters when stats were on
  std::string stats_note;                          ///< why per-cell statistics were refused, if they were
  std::uint64_t cell_sample = 1;                   ///< per-cell counts kept for 1 path in this many
  std::uint64_t rays = 0;            ///< every accelerator query (closest and any hit)
  std::uint64_t abandoned_rays = 0;  ///< of those, cast by a pass abandoned on an interrupt
  std::uint64_t nonfinite_samples = 0;  ///< non-finite radiance samples, dropped from their pixel
  int spp = 0;                       ///< the completed passes' samples per pixel (the most any pixel took)
  int passes = 0;                    ///< completed passes
  int resumed_passes = 0;            ///< of them, those a checkpoint brought (--resume)
  std::uint64_t resumed_rays = 0;    ///< of `rays`, those a checkpoint brought
  int checkpoints_saved = 0;         ///< --checkpoint-every: checkpoints this run saved
  bool interrupted = false;          ///< a pass was abandoned: the film holds the passes before it
  double relmse_estimate = 0;        ///< FrameAccumulator::relmse_estimate of the film
  SppSpread spp_spread;              ///< samples per pixel, min, mean and max
  std::string stop_reason;           ///< the planner's (PassPlanner::stop_reason), "" without one
  std::string path_variant;          ///< the integrator that ran (path_variant_name)
  bool occluder_cache = false;       ///< shadow rays went through the occluder cache (occluder_cache.h)
  double probe_before_s = 0;         ///< machine_probe() just before the frame (stats/machine_probe.h), 0 if not run
  double probe_after_s = 0;          ///< and just after it
};

/// Called after each finished tile with (tiles done, tiles in all); it must be
/// cheap and thread-safe.
using ProgressCallback = std::function<void(std::size_t, std::size_t)>;

}  // namespace kappa
