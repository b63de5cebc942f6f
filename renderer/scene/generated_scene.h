// Scenes made in code, for `kappa calibrate`: a room lit by a ceiling lamp
// around a soup of random triangles or a dense mesh. Their sizes set the working set (cell
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

/// The same room around a closed, bumpy sphere of about `triangles`
/// triangles, numbered ring by ring as a scanned mesh numbers its faces (so
/// a cell's triangles lie near each other in memory), standing on the floor:
/// dense meshes make rays test many triangles per occupied cell, as the
/// bunny, dragon or Lucy do.
Scene generated_blob_scene(std::size_t triangles);

}  // namespace kappa
