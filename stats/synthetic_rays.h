// The seed paper's synthetic ray distributions, through a box.
#pragma once

#include <cstdint>
#include <vector>

#include "accel/ray.h"
#include "accel/vec3.h"

namespace kappa {

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
