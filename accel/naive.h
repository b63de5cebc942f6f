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

 private:
  std::span<const Triangle> m_triangles;
  /// Ids of the triangles with non-zero area and finite vertices, ascending:
  /// the same set every accelerator may hit (a degenerate triangle can pass
  /// the float test's sign checks after rounding, so it is left out here too).
  std::vector<TriangleId> m_usable;
};

}  // namespace kappa
