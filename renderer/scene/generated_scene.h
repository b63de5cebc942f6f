// Scenes made in code, for `kappa calibrate`: a room lit by a ceiling lamp
// around a soup of random triangles. Their sizes set the working set (cell
// arrays and triangles) from well inside the L2 cache to past the L3, which
// the two asset scenes alone do not span, so the extended cost model's
// memory terms are determined.
#pragma once

#include <cstddef>
#include <cstdint>

#include "renderer/scene/scene.h"

namespace kappa {

/// A unit room (walls facing in) with a lamp in its ceiling and `triangles`
/// random triangles inside, each about 1.5 times the mean spacing across;
/// the camera frames the room from outside its open front.
Scene generated_soup_scene(std::size_t triangles, std::uint64_t seed);

}  // namespace kappa
