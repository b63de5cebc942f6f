// The one interface through which the renderer makes every visibility query
// (camera, bounce and shadow rays), and what reports need of any accelerator.
// Accelerators know triangles, not materials. The hot path reaches a concrete
// accelerator through visit_accelerator (dispatch.h), not through this
// interface, where that pays.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <optional>
#include <string_view>

#include "hit_filter.h"
#include "ray.h"
#include "triangle.h"

namespace kappa {

class CellLayout;

/// Every accelerator Kappa has: what visit_accelerator (dispatch.h) switches on.
enum class AccelKind { naive, grid, grid2, embree };

class Accelerator {
 public:
  virtual ~Accelerator() = default;

  /// The nearest hit with ray.tmin < t <= ray.tmax (ties: lower triangle id).
  virtual std::optional<Hit> closest_hit(const Ray& ray) const = 0;

  /// True if anything is hit with ray.tmin < t <= ray.tmax; may stop at the first.
  virtual bool any_hit(const Ray& ray) const = 0;

  /// The same queries where a hit counts only if `filter` accepts it (the
  /// any-hit filter seam, hit_filter.h: cut-outs). Embree needs to know at
  /// its build (AccelOptions::filtered) that it will be asked these.
  virtual std::optional<Hit> closest_hit(const Ray& ray, const FunctionHitFilter& filter) const = 0;
  virtual bool any_hit(const Ray& ray, const FunctionHitFilter& filter) const = 0;

  virtual std::string_view name() const = 0;
  virtual AccelKind kind() const = 0;

  /// Bytes of the structure built beside the scene's triangles (0 for naive).
  virtual std::uint64_t bytes() const = 0;
  /// Of bytes(), the triangle references of the cells' lists: what a
  /// triangle test reads beside its triangle (stats/time_model.h's memory
  /// terms); 0 for a structure without lists.
  virtual std::uint64_t reference_bytes() const { return 0; }
  /// Seconds its build took.
  virtual double build_s() const = 0;
  /// Its own section of the report (keys in stats/README.md), or null for an
  /// accelerator that has none; the model's predictions are added by stats/.
  virtual nlohmann::ordered_json report_section() const;
  /// The cells of a cell-based accelerator (what statistics count), or
  /// nullptr for one without cells.
  virtual const CellLayout* cells() const { return nullptr; }
};

}  // namespace kappa
