// What a progressive frame's completed passes leave, to be saved in a
// checkpoint (--checkpoint-every, renderer/io/checkpoint_file.h) and begun
// from again (--resume): every pixel's sums and which still sample, the
// passes and samples so far, the frame's counts, and the statistics'
// counters flattened (RenderCounters::flatten). With them a resumed render
// takes the passes a render not stopped would, and ends with its image.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "renderer/render/frame_accumulator.h"
#include "renderer/render/pass_planner.h"

namespace kappa {

struct Film;
struct PassControl;
struct RenderResult;
class TileSchedule;

struct FrameProgress {
  int passes = 0;
  int spp = 0;                            ///< samples per still-sampling pixel (FrameState::spp)
  std::uint64_t rays = 0, nonfinite = 0;  ///< the frame's, over its passes
  double elapsed_s = 0;                   ///< the time budget spent (PassPlanner::elapsed)
  std::uint64_t cell_sample = 0;          ///< 1 path in this many counted per cell; 0 none
  std::vector<PixelSamples> samples;
  std::vector<PixelAovSums> aovs;         ///< empty without an AOV
  std::vector<std::uint8_t> active;       ///< empty until --adaptive retires a pixel
  std::vector<std::uint64_t> counters;    ///< empty with statistics off
};

/// A frame that counts (statistics on): its counters so far, flattened, and
/// the rate it counts per cell at, for a checkpoint.
struct FrameCounters {
  std::function<std::vector<std::uint64_t>()> so_far;
  std::uint64_t cell_sample = 0;
};

/// Begins a progressive frame from control.resume's passes: their sums into
/// `acc` and `film` (the image so far, should no pass follow), where the
/// frame stands (its estimate and pixels still sampling computed again
/// from the sums, as after the pass that saved it), its passes in `result`,
/// and the time budget already spent, to control.planner.
void resume_frame(const PassControl& control, FrameAccumulator& acc, Film& film, FrameState& state,
                  RenderResult& result);

/// After a completed pass: when `control` says a checkpoint is due (the
/// schedule's writer decides for every process), the frame so far, its
/// counters summed over the processes (and the checkpoint's it resumed
/// from), to control.checkpoint. Every process sharing the frame calls it.
void checkpoint_if_due(const PassControl& control, const FrameAccumulator& acc, const FrameState& state, int passes,
                       std::uint64_t rays, std::uint64_t nonfinite, double elapsed_s, const FrameCounters* counters,
                       TileSchedule* schedule);

}  // namespace kappa
