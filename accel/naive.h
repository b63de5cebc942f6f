// The paper's baseline: test every triangle. Also the correctness oracle every
// other accelerator is compared against.
#pragma once

#include <span>
#include <vector>

#include "accel.h"

namespace kappa {

class NaiveAccelerator final : public Accelerator {
 public:
  explicit NaiveAccelerator(std::span<const Triangle> triangles);

  std::optional<Hit> closest_hit(const Ray& ray) const override;
  bool any_hit(const Ray& ray) const override;
  std::optional<Hit> closest_hit(const Ray& ray, const FunctionHitFilter& filter) const override {
    return closest_hit<FunctionHitFilter>(ray, filter);
  }
  bool any_hit(const Ray& ray, const FunctionHitFilter& filter) const override {
    return any_hit<FunctionHitFilter>(ray, filter);
  }
  std::string_view name() const override { return "naive"; }
  AccelKind kind() const override { return AccelKind::naive; }
  /// The list of usable triangle ids: all it keeps beside the triangles.
  std::uint64_t bytes() const override { return m_usable.size() * sizeof(TriangleId); }
  std::uint64_t reference_bytes() const override { return bytes(); }  // one list, of every usable triangle
  double build_s() const override { return m_build_s; }

  /// The same queries with an any-hit filter (hit_filter.h) asked of every
  /// candidate, in id order.
  template <HitFilter Filter>
  std::optional<Hit> closest_hit(const Ray& ray, const Filter& filter) const {
    const PreparedRay prepared(ray);
    Hit best;
    best.t = ray.tmax;
    for (const TriangleId i : m_usable) test_closest(prepared, m_triangles[i], i, ray.tmin, best, filter);
    if (!best.valid()) return std::nullopt;
    return best;
  }
  template <HitFilter Filter>
  bool any_hit(const Ray& ray, const Filter& filter) const {
    const PreparedRay prepared(ray);
    for (const TriangleId i : m_usable)
      if (test_any(prepared, m_triangles[i], i, ray.tmin, ray.tmax, filter)) return true;
    return false;
  }

 private:
  std::span<const Triangle> m_triangles;
  /// Ids of the triangles with non-zero area and finite vertices, ascending:
  /// the same set every accelerator may hit (a degenerate triangle can pass
  /// the float test's sign checks after rounding, so it is left out here too).
  std::vector<TriangleId> m_usable;
  double m_build_s = 0;
};

}  // namespace kappa
