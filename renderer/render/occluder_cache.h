// The occluder cache: Haines & Greenberg's light buffer (1986) reduced to
// one remembered triangle per light, as Radiance keeps it. The triangle that
// last stopped a shadow ray toward a light is tested first on the next
// shadow ray toward the same light: neighbouring shading points tend to be
// shadowed by the same triangle, and one test then replaces a walk.
//
// The answer stays the accelerator's: a shadow query asks whether anything
// lies in (tmin, tmax], and the cached triangle is tested with the walks' own
// test (accel/triangle.h's test_any, through the same any-hit filter), which
// an exact accelerator's walk would also have found true. So the image is
// bitwise the one without the cache; only the work changes.
//
// One cache per Queries object, that is per tile and thread (tile_loop.h):
// no sharing, no locks, fixed size (no allocation on the hot path). A ray
// that reaches its light clears its key: the lit points around it would
// pay a test for nothing.
#pragma once

#include <cmath>
#include <concepts>
#include <cstdint>
#include <span>

#include "accel/hit_filter.h"
#include "accel/recorder.h"
#include "accel/triangle.h"

namespace kappa {

/// What an accelerator needs for the cache: an any-hit walk that says which
/// triangle stopped it, and the triangles by id (the grids).
template <class A>
concept OccluderWalker = requires(const A& a, const Ray& r, NoRecorder& rec) {
  { a.occluder_of(r, rec) } -> std::same_as<TriangleId>;
  { a.triangles() } -> std::convertible_to<std::span<const Triangle>>;
};

/// A shadow ray's key in the cache: its light's index among the frame's
/// lights (renderer/render/lights.h), and for a light that fills the sky
/// (the environment) the part of the sphere the ray goes to, since an
/// environment's rays leave a point in every direction and only those close
/// in direction meet the same occluder.
using LightKey = std::uint64_t;

/// The key of light `light` (an index) alone: a triangle, point or directional light.
inline LightKey light_key(std::size_t light) { return LightKey(light); }

/// The key of the environment (index `light`) toward direction `d`: one of
/// 6 x 4 x 4 solid angles (a cube map's faces, each cut 4 x 4).
inline LightKey light_key(std::size_t light, const Vec3f& d) {
  const float ax = std::abs(d.x), ay = std::abs(d.y), az = std::abs(d.z);
  int face;
  float u, v, major;
  if (ax >= ay && ax >= az) face = d.x < 0, major = ax, u = d.y, v = d.z;
  else if (ay >= az) face = 2 + (d.y < 0), major = ay, u = d.x, v = d.z;
  else face = 4 + (d.z < 0), major = az, u = d.x, v = d.y;
  // u / major and v / major lie in [-1, 1]; compared in float, so that a
  // NaN (a zero or NaN direction) falls in cell 0 without converting it.
  const auto cell = [&](float w) {
    const float s = (w / major + 1.0f) * 2.0f;
    return s >= 3.0f ? 3 : s >= 2.0f ? 2 : s >= 1.0f ? 1 : 0;
  };
  const std::uint64_t part = std::uint64_t(face * 16 + cell(u) * 4 + cell(v)) + 1;
  return LightKey(light) | part << 32;
}

class OccluderCache {
 public:
  /// Keys kept at once; more share slots (a key then evicts another's
  /// occluder, which only costs a walk).
  static constexpr std::size_t kSlots = 256;

  /// The triangle that occluded the last ray with key `key`, or kNoTriangle
  /// (none kept, or that ray reached its light).
  TriangleId occluder(LightKey key) const {
    const Slot& s = m_slots[slot(key)];
    return s.key == key ? s.triangle : kNoTriangle;
  }
  /// What the last ray with key `key` met: its occluder, or kNoTriangle when
  /// it reached the light (the next ray, likely lit too, then tests nothing).
  void remember(LightKey key, TriangleId triangle) { m_slots[slot(key)] = {key, triangle}; }

 private:
  static std::size_t slot(LightKey key) {
    return std::size_t((key ^ (key >> 32) * 0x9E3779B97F4A7C15ull) & (kSlots - 1));
  }
  struct Slot {
    LightKey key = ~LightKey(0);
    TriangleId triangle = kNoTriangle;
  };
  Slot m_slots[kSlots];
};

/// Whether triangle `id` of `triangles` occludes `r` under `filter`: the
/// test every exact accelerator's any-hit walk makes.
template <HitFilter Filter>
[[gnu::always_inline]] inline bool occludes(std::span<const Triangle> triangles, TriangleId id, const Ray& r,
                                            const Filter& filter) {
  return test_any(PreparedRay(r), triangles[id], id, r.tmin, r.tmax, filter);
}

}  // namespace kappa
