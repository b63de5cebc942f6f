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
  std::string_view name() const override { return "naive"; }
  AccelKind kind() const override { return AccelKind::naive; }
  /// The list of usable triangle ids: all it keeps beside the triangles.
  std::uint64_t bytes() const override { return m_usable.size() * sizeof(TriangleId); }
  double build_s() const override { return m_build_s; }

 private:
  std::span<const Triangle> m_triangles;
  /// Ids of the triangles with non-zero area and finite vertices, ascending:
  /// the same set every accelerator may hit (a degenerate triangle can pass
  /// the float test's sign checks after rounding, so it is left out here too).
  std::vector<TriangleId> m_usable;
  double m_build_s = 0;
};

}  // namespace kappa
