// The one interface through which the renderer makes every visibility query
// (camera, bounce and shadow rays). Accelerators know triangles, not materials.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

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

  /// Batch forms over caller-owned spans (hits[i] is invalid for a miss).
  void closest_hit(std::span<const Ray> rays, std::span<Hit> hits) const;
  void any_hit(std::span<const Ray> rays, std::span<bool> occluded) const;

  virtual std::string_view name() const = 0;
};

/// Build settings of the accelerators that have any.
struct AccelOptions {
  std::string grid_res = "auto";  ///< "auto", "N" or "NxNxN"
  double grid_density = 0;        ///< lambda in N_c = lambda * N for "auto"; 0 = the grid's default
  std::uint64_t grid_max_bytes = 0;  ///< refuse grids larger than this; 0 = the default (a quarter of RAM)
};

/// The names make_accelerator accepts, for help texts and validation.
std::vector<std::string> accelerator_names();

/// Builds the accelerator called `name` over `triangles` (which must outlive
/// it). Throws std::invalid_argument for an unknown name or options the
/// accelerator refuses (e.g. a grid over its memory limit).
std::unique_ptr<Accelerator> make_accelerator(std::string_view name, std::span<const Triangle> triangles,
                                              const AccelOptions& options = {});

}  // namespace kappa
