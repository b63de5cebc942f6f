#include "renderer/render/frame_progress.h"

#include "core/check.h"
#include "renderer/render/frame.h"
#include "renderer/render/tile_schedule.h"

namespace kappa {

void resume_frame(const PassControl& control, FrameAccumulator& acc, Film& film, FrameState& state,
                  RenderResult& result) {
  const FrameProgress& from = *control.resume;
  acc.restore(from.samples, from.aovs, from.active);
  state.spp = from.spp;
  state.active_pixels = acc.active_pixels();
  state.relmse_estimate = acc.relmse_estimate();
  result.passes = from.passes;
  control.planner->resume(from.elapsed_s);
  acc.resolve(film);
  result.spp_spread = acc.spp_spread();
}

void checkpoint_if_due(const PassControl& control, const FrameAccumulator& acc, const FrameState& state, int passes,
                       std::uint64_t rays, std::uint64_t nonfinite, double elapsed_s, const FrameCounters* counters,
                       TileSchedule* schedule) {
  bool due = control.checkpoint_due();
  if (schedule) due = schedule->writer_value(due) != 0;
  if (!due) return;
  FrameProgress progress;
  progress.passes = passes;
  progress.spp = state.spp;
  progress.rays = rays;
  progress.nonfinite = nonfinite;
  progress.elapsed_s = elapsed_s;
  if (counters) {
    progress.cell_sample = counters->cell_sample;
    progress.counters = counters->so_far();
    if (schedule) schedule->sum_on_writer(progress.counters);
    if (control.resume && !control.resume->counters.empty()) {
      KAPPA_CHECK_EQ(control.resume->counters.size(), progress.counters.size());
      for (std::size_t i = 0; i < progress.counters.size(); ++i) progress.counters[i] += control.resume->counters[i];
    }
  }
  progress.samples = acc.all_samples();
  progress.aovs = acc.all_aov_sums();
  progress.active = acc.all_active();
  control.checkpoint(progress);
}

}  // namespace kappa
