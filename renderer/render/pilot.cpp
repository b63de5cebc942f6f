#include "renderer/render/pilot.h"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "renderer/render/queries.h"
#include "renderer/render/tile_loop.h"
#include "renderer/render/tile_schedule.h"

namespace kappa {
namespace {

/// Answers every query with the closest hit and records it; the path tracer
/// sees what it would from the frame's queries (a shadow ray is occluded
/// exactly when it has a closest hit within its range).
struct RecordingQueries {
  const Accelerator& accel;
  std::vector<PilotSegment>& out;
  std::vector<std::uint32_t>& pixel_rays;  ///< a pixel's element written by the one thread rendering it
  const std::vector<std::uint32_t>& frame_tile;  ///< per pilot pixel, the frame's tile it stands for
  std::uint64_t rays = 0;
  std::size_t pixel = 0;

  QueryWork work() const { return {}; }
  void begin_path(std::uint64_t next_pixel, std::uint64_t /*sample*/) { pixel = std::size_t(next_pixel); }

  template <HitFilter F = NoHitFilter>
  std::optional<Hit> closest(const Ray& r, int depth, const F& filter = {}) {
    return record(r, class_of_depth(depth), filter);
  }
  template <HitFilter F = NoHitFilter>
  std::optional<Hit> closest_by_lobe(const Ray& r, int depth, bsdf::Lobe /*lobe*/, const F& filter = {}) {
    return closest(r, depth, filter);
  }
  /// Every shadow ray is recorded, also one the frame's occluder cache would
  /// answer: naive walks them all, and for the grids the prediction then
  /// counts a walk where the frame may make one triangle test.
  template <HitFilter F = NoHitFilter>
  bool shadow(const Ray& r, LightKey /*light*/, const F& filter = {}) {
    return record(r, kShadow, filter).has_value();
  }

 private:
  /// The hit under the frame's cut-outs, if any: the walk a candidate grid
  /// would make ends there.
  template <HitFilter F>
  std::optional<Hit> record(const Ray& r, RenderClass k, const F& filter) {
    ++rays;
    ++pixel_rays[pixel];
    const std::optional<Hit> hit = filtered_closest(accel, r, filter);
    out.push_back({r, hit ? hit->t : r.tmax, hit.has_value(), k, frame_tile[pixel], std::uint32_t(pixel)});
    return hit;
  }
};

}  // namespace

int pilot_pixels(double frame_paths) { return int(std::clamp(frame_paths / 256.0, 1024.0, 16384.0)); }

Pilot run_pilot(const Scene& scene, int width, int height, int pixels, const Accelerator& accel,
                const RenderSettings& settings) {
  const auto start = std::chrono::steady_clock::now();
  Pilot pilot;
  // The frame's aspect at about `pixels` pixels, never more than the frame's.
  const double scale = std::min(1.0, std::sqrt(double(pixels) / (double(width) * double(height))));
  pilot.width = std::max(1, int(std::lround(width * scale)));
  pilot.height = std::max(1, int(std::lround(height * scale)));
  RenderSettings one = settings;
  one.spp = 1;
  one.stats = false;
  one.aov = AovSelection{};
  one.passes = nullptr;
  one.test_nonfinite = nullptr;
  Film film(pilot.width, pilot.height, AovSelection{});
  // Each pilot pixel stands for the frame's pixels around its centre; the
  // frame's tile holding that centre is the one whose walks it replays.
  const int frame_tiles_x = (width + kTileSize - 1) / kTileSize;
  std::vector<std::uint32_t> frame_tile(std::size_t(pilot.width) * std::size_t(pilot.height));
  for (int y = 0; y < pilot.height; ++y)
    for (int x = 0; x < pilot.width; ++x) {
      const int fx = std::min(width - 1, int((x + 0.5) * width / pilot.width));
      const int fy = std::min(height - 1, int((y + 0.5) * height / pilot.height));
      frame_tile[std::size_t(y) * std::size_t(pilot.width) + std::size_t(x)] =
          std::uint32_t((fy / kTileSize) * frame_tiles_x + fx / kTileSize);
    }
  tbb::enumerable_thread_specific<std::vector<PilotSegment>> per_thread;
  pilot.pixel_rays.assign(std::size_t(pilot.width) * std::size_t(pilot.height), 0);
  render_tiles(scene, one, film, {},
               [&] { return RecordingQueries{accel, per_thread.local(), pilot.pixel_rays, frame_tile}; });
  std::size_t total = 0;
  for (const auto& v : per_thread) total += v.size();
  pilot.segments.reserve(total);
  for (const auto& v : per_thread) pilot.segments.insert(pilot.segments.end(), v.begin(), v.end());
  // By frame tile, then pixel (row by row, as a tile walks them): one
  // thread rendered each pixel's segments in order, so the stable sort's
  // order is the same for any thread count.
  std::stable_sort(pilot.segments.begin(), pilot.segments.end(), [](const PilotSegment& a, const PilotSegment& b) {
    return a.tile != b.tile ? a.tile < b.tile : a.pixel < b.pixel;
  });
  for (const PilotSegment& s : pilot.segments) ++pilot.rays[s.ray_class];
  pilot.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return pilot;
}

}  // namespace kappa
