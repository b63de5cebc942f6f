#include "renderer/render/pilot.h"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "renderer/render/queries.h"
#include "renderer/render/tile_loop.h"

namespace kappa {
namespace {

/// Answers every query with the closest hit and records it; the path tracer
/// sees what it would from the frame's queries (a shadow ray is occluded
/// exactly when it has a closest hit within its range).
struct RecordingQueries {
  const Accelerator& accel;
  std::vector<PilotSegment>& out;
  std::vector<std::uint32_t>& pixel_rays;  ///< a pixel's element written by the one thread rendering it
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
    out.push_back({r, hit ? hit->t : r.tmax, hit.has_value(), k});
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
  tbb::enumerable_thread_specific<std::vector<PilotSegment>> per_thread;
  pilot.pixel_rays.assign(std::size_t(pilot.width) * std::size_t(pilot.height), 0);
  render_tiles(scene, one, film, {}, [&] { return RecordingQueries{accel, per_thread.local(), pilot.pixel_rays}; });
  std::size_t total = 0;
  for (const auto& v : per_thread) total += v.size();
  pilot.segments.reserve(total);
  for (const auto& v : per_thread) pilot.segments.insert(pilot.segments.end(), v.begin(), v.end());
  for (const PilotSegment& s : pilot.segments) ++pilot.rays[s.ray_class];
  pilot.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return pilot;
}

}  // namespace kappa
