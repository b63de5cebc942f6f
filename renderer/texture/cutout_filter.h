// The cut-out test: the any-hit filter (accel/hit_filter.h) a scene with
// cut-outs gives its visibility queries. A hit counts unless its material is
// cut out there: everywhere for a constant opacity below 0.5, or where the
// opacity map's texel at the hit's (u, v) is below 0.5 (glTF's MASK rule).
// The texel is the one the point falls in at the finest level, from the
// mask read at load (Scene::opacity_masks), so the answer depends on the hit
// alone and every exact accelerator, asking it at the same point of its
// triangle test, still returns the same closest hit bitwise.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "accel/ray.h"
#include "renderer/scene/scene.h"

namespace kappa {

class CutoutFilter {
 public:
  static constexpr bool active = true;

  explicit CutoutFilter(const Scene& scene) : m_scene(&scene) {
    m_rule.assign(scene.materials.size(), kOpaque);
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
      const Material& m = scene.materials[i];
      if (m.opacity < 0.5f) {
        m_rule[i] = kInvisible;
      } else if (m.has_map(MapSlot::opacity)) {
        const TextureMap& map = scene.texture_maps[std::size_t(m.maps[std::size_t(MapSlot::opacity)])];
        if (map.mask >= 0) m_rule[i] = map.mask;
      }
    }
    for (std::int32_t r : m_rule) m_any = m_any || r != kOpaque;
  }

  /// Some material is cut out somewhere: the frame needs the filter.
  bool any() const { return m_any; }

  bool accepts(const Hit& h) const {
    std::uint64_t lookups = 0;
    return test(h, lookups);
  }

  /// accepts(), adding 1 to `lookups` when the material is cut out (an
  /// alpha test made: what the statistics count).
  bool test(const Hit& h, std::uint64_t& lookups) const {
    const std::int32_t rule = m_rule[m_scene->material_of[h.triangle]];
    if (rule == kOpaque) return true;
    ++lookups;
    if (rule == kInvisible) return false;
    const OpacityMask& mask = m_scene->opacity_masks[std::size_t(rule)];
    const TriangleUVs uvs = h.triangle < m_scene->uvs.size() ? m_scene->uvs[h.triangle] : TriangleUVs{};
    const Vec2f uv = uvs.uv[0] * h.b0 + uvs.uv[1] * h.b1 + uvs.uv[2] * h.b2;
    const float s = uv.u * mask.scale.u + mask.offset.u;
    const float t = 1.0f - (uv.v * mask.scale.v + mask.offset.v);
    return mask.opaque[std::size_t(texel(t, mask.height, mask.wrap_t)) * std::size_t(mask.width) +
                       std::size_t(texel(s, mask.width, mask.wrap_s))];
  }

 private:
  static constexpr std::int32_t kOpaque = -1, kInvisible = -2;

  /// The texel a coordinate falls in, under the map's wrap (as the colour
  /// lookup wraps: repeating, clamped to the edge, or mirrored).
  static std::int64_t texel(float c, int size, TextureWrap wrap) {
    const double x = std::floor(double(c) * double(size));
    if (!std::isfinite(x) || std::abs(x) > 9e15) return 0;
    const std::int64_t n = size;
    const std::int64_t i = std::int64_t(x);
    switch (wrap) {
      case TextureWrap::clamp: return std::clamp<std::int64_t>(i, 0, n - 1);
      case TextureWrap::mirror: {
        const std::int64_t m = ((i % (2 * n)) + 2 * n) % (2 * n);  // in [0, 2n)
        return m < n ? m : 2 * n - 1 - m;
      }
      case TextureWrap::periodic: break;
    }
    const std::int64_t r = i % n;
    return r < 0 ? r + n : r;
  }

  const Scene* m_scene;
  std::vector<std::int32_t> m_rule;      ///< per material: kOpaque, kInvisible or a mask
  bool m_any = false;
};

}  // namespace kappa
