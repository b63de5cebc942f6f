// Grid resolution: parsing `--grid-res` and choosing near-cubic cells for a
// target cell count.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "core/vec3.h"

namespace kappa {

struct GridResolution {
  int nx = 1, ny = 1, nz = 1;

  std::uint64_t cells() const { return std::uint64_t(nx) * std::uint64_t(ny) * std::uint64_t(nz); }
  int operator[](int axis) const { return axis == 0 ? nx : (axis == 1 ? ny : nz); }
  std::string to_string() const;
  bool operator==(const GridResolution&) const = default;
};

/// Largest resolution accepted per axis by `--grid-res`.
inline constexpr int kMaxGridAxis = 1 << 14;

/// Parses "auto" (returns nullopt), "64" (cubic) or "64x32x16". Throws
/// InputError with a one-line reason for anything else.
std::optional<GridResolution> parse_grid_resolution(std::string_view text);

/// Cells as close to cubes as the box allows with about `target_cells` cells
/// in all. Axes of (near) zero extent get one cell, so flat scenes get a 2D or
/// 1D grid rather than slivers.
GridResolution choose_resolution(const Vec3d& extent, double target_cells);

}  // namespace kappa
