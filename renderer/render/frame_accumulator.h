// A frame's pixels across its passes: every pixel's samples (pixel_samples.h)
// and, for the selected AOVs, their sums; which pixels still sample under
// --adaptive; and the film they resolve to after each pass.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "renderer/render/film.h"
#include "renderer/render/pixel_samples.h"

namespace kappa {

/// The AOVs' sums of one pixel over its samples.
struct PixelAovSums {
  double albedo[3] = {0, 0, 0};
  double normal[3] = {0, 0, 0};
  double depth = 0;
  std::uint32_t depth_hits = 0;  ///< samples whose camera ray hit
  double cells = 0, tests = 0;   ///< the cost AOV's
};

/// The spread of the samples per pixel (--adaptive makes it uneven).
struct SppSpread {
  std::uint32_t min = 0, max = 0;
  double mean = 0;
};

/// Pixels per block of the frame-wide passes (resolve, estimate, retire).
inline constexpr std::size_t kBlock = 4096;

/// Bytes a frame of `pixels` holds while it renders with `aov`: each pixel's
/// sums (FrameAccumulator), the film's channels, and the interleaved copy the
/// EXR writer makes of them.
std::uint64_t frame_bytes(std::size_t pixels, const AovSelection& aov);

/// Throws InputError when a width x height frame needs more than the
/// machine's physical memory: refused before anything is allocated, not ended
/// by the allocator halfway through.
void refuse_frame_over_memory(int width, int height, const AovSelection& aov);

/// Writes one pixel's selected channels of `film` from its sums.
void resolve_pixel(Film& film, std::size_t pixel, const PixelSamples& samples, const PixelAovSums& aovs);

class FrameAccumulator {
 public:
  FrameAccumulator(std::size_t pixels, const AovSelection& aov);

  std::size_t pixels() const { return m_samples.size(); }
  PixelSamples& samples(std::size_t pixel) { return m_samples[pixel]; }
  const PixelSamples& samples(std::size_t pixel) const { return m_samples[pixel]; }
  /// Only when an AOV is selected (aov_sums() is empty otherwise).
  PixelAovSums& aov_sums(std::size_t pixel) { return m_aovs[pixel]; }
  bool has_aovs() const { return !m_aovs.empty(); }

  bool active(std::size_t pixel) const { return m_active.empty() || m_active[pixel] != 0; }
  std::size_t active_pixels() const { return m_active_count; }
  /// --adaptive: pixels with at least `min_spp` samples whose own estimate
  /// is below `target` stop sampling. Returns how many still sample.
  std::size_t retire_converged(double target, std::uint32_t min_spp);

  /// The mean over pixels and channels of (s²/n)/(x̄² + 0.01), summed in
  /// pixel order (the same figure for any thread count).
  double relmse_estimate() const;
  SppSpread spp_spread() const;
  /// Writes every selected channel of `film` from the sums so far.
  void resolve(Film& film) const;

  /// Every pixel's sums and which still sample (empty: all), as a
  /// checkpoint keeps them (frame_progress.h).
  const std::vector<PixelSamples>& all_samples() const { return m_samples; }
  const std::vector<PixelAovSums>& all_aov_sums() const { return m_aovs; }
  const std::vector<std::uint8_t>& all_active() const { return m_active; }
  /// Back to a checkpoint's sums: each array of this frame's size (aov
  /// sums only when it keeps them; active empty or one a pixel).
  void restore(std::vector<PixelSamples> samples, std::vector<PixelAovSums> aovs, std::vector<std::uint8_t> active);

 private:
  std::vector<PixelSamples> m_samples;
  std::vector<PixelAovSums> m_aovs;
  std::vector<std::uint8_t> m_active;  ///< empty until the first retirement
  std::size_t m_active_count;
};

}  // namespace kappa
