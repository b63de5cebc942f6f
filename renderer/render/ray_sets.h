// The renderer's own rays as fixed sets (camera, bounce, shadow) and the
// paper's uniform lines, generated once from the scene and then replayed
// identically: what `kappa bench` times, `kappa cast` counts and `kappa
// calibrate` fits the cost model to.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "accel/accel.h"
#include "renderer/scene/scene.h"

namespace kappa {

enum class RayClass { camera, bounce, shadow, lines };

/// "camera", "bounce", "shadow", "lines".
const char* ray_class_name(RayClass c);
/// Throws InputError for an unknown name.
RayClass parse_ray_class(const std::string& name);

struct RaySet {
  RayClass kind = RayClass::camera;
  bool occlusion = false;  ///< timed with any_hit (shadow rays), else closest_hit
  std::vector<Ray> rays;
  std::string note;        ///< how the set was made, or why it is short
};

/// Builds `n` rays of class `kind`. `reference` finds the camera rays' hits
/// from which bounce and shadow rays start. Camera rays cover the film
/// (stratified over pixels); bounce rays are cosine-weighted about the
/// oriented normal at camera hits; shadow rays run from those hits to points
/// on emitters chosen by power, or, for a scene lit only by its environment,
/// along cosine-weighted directions with an infinite tmax; lines are
/// isotropic uniform random lines through the scene's bounding box
/// (stats/synthetic_rays.h's uniform_lines, as cast and calibrate use).
RaySet make_ray_set(RayClass kind, const Scene& scene, const Accelerator& reference, std::size_t n,
                    std::uint64_t seed);

}  // namespace kappa
