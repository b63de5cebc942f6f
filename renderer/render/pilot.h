// The pilot of --grid-res model and --accel auto: a small render of the
// frame's own paths (its camera, film aspect, lights, depth and sampler) at
// one sample per pixel, every query answered by an exact accelerator and
// recorded as a segment (stats/pilot_replay.h), so that candidate
// structures can count the frame's walks without rendering it.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "accel/accel.h"
#include "renderer/render/frame.h"
#include "renderer/scene/scene.h"
#include "stats/resolution_choice.h"

namespace kappa {

struct Pilot {
  std::vector<PilotSegment> segments;  ///< every query of the pilot's paths, by frame tile, then pixel, then in the path's order
  std::array<std::uint64_t, kRenderClasses> rays{};  ///< of them, per class
  int width = 0, height = 0;           ///< the pilot's film: the frame's aspect, about the pixels asked for
  double seconds = 0;                  ///< the pilot render's wall time
  /// Each pilot pixel's queries (width x height, row by row): where the
  /// frame's samples cost more, for the order of its first pass's tiles
  /// (tile_costs.h).
  std::vector<std::uint32_t> pixel_rays;
};

/// The pilot's paths for a frame of `frame_paths` (pixels x spp): 1/256 of
/// them, within 1,024 ... 16,384 (a 128 x 128 film), so that the pilot and the
/// candidates' counting walks cost about 1 % of the frame while the counts
/// per ray of each class stay within a few per cent of the frame's.
int pilot_pixels(double frame_paths);

/// Renders the pilot of `scene` (film width x height) at `pixels` pixels of
/// the frame's aspect (never more than the frame's), one sample each, with
/// `settings` (its samples, statistics, AOVs and passes aside) through
/// `accel`, an exact accelerator. Shadow queries record their closest occluder.
Pilot run_pilot(const Scene& scene, int width, int height, int pixels, const Accelerator& accel,
                const RenderSettings& settings);

}  // namespace kappa
