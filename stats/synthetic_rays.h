// The seed paper's synthetic ray distributions, through a box.
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "accel/ray.h"
#include "core/vec3.h"

namespace kappa {

/// The slab test: the part [t0, t1] of the ray o + t d inside the box [lo,
/// hi], narrowed from the given [t0, t1]; nullopt if the ray misses the box.
/// Axes with d = 0 are tested without dividing. (The grid walk clips in its
/// own loop, where it also keeps 1/d.)
std::optional<std::pair<double, double>> clip_to_box(const Vec3d& o, const Vec3d& d, const Vec3d& lo, const Vec3d& hi,
                                                     double t0 = -INFINITY, double t1 = INFINITY);

/// n isotropic uniform random lines meeting the box [lo, hi]: a direction
/// uniform on the sphere, then a point uniform on the disk the box's bounding
/// sphere projects to, kept if the line meets the box. Each ray starts outside
/// the bounding sphere with tmax = +inf, so walking it covers the whole chord.
std::vector<Ray> uniform_lines(const Vec3d& lo, const Vec3d& hi, std::size_t n, std::uint64_t seed);

/// n segments of the given length: a start uniform in the box, an isotropic
/// direction, kept only if the end stays in the box; d is unit, tmax = length.
std::vector<Ray> uniform_segments(const Vec3d& lo, const Vec3d& hi, double length, std::size_t n,
                                  std::uint64_t seed);

}  // namespace kappa
