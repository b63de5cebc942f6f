// The one interface through which the renderer makes every visibility query
// (camera, bounce and shadow rays). Accelerators know triangles, not materials.
#pragma once

#include <optional>
#include <string_view>

#include "ray.h"
#include "triangle.h"

namespace kappa {

class Accelerator {
 public:
  virtual ~Accelerator() = default;

  /// The nearest hit with ray.tmin < t <= ray.tmax (ties: lower triangle id).
  virtual std::optional<Hit> closest_hit(const Ray& ray) const = 0;

  /// True if anything is hit with ray.tmin < t <= ray.tmax; may stop at the first.
  virtual bool any_hit(const Ray& ray) const = 0;

  virtual std::string_view name() const = 0;
};

}  // namespace kappa
