// A loaded scene: flat triangle arrays, materials, camera, environment, film
// size. Loading lives in scene_loader / obj_loader; the accelerator sees only
// `triangles`.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "accel/triangle.h"
#include "core/vec3.h"

namespace kappa {

/// Lambertian reflector that may also emit (one-sided, towards its normal).
struct Material {
  std::string name;
  Vec3f albedo{0.5f, 0.5f, 0.5f};  ///< Kd, in [0, 1]
  Vec3f emission{0, 0, 0};         ///< Ke, radiance (W sr^-1 m^-2, scene units)

  bool emissive() const { return emission.x > 0 || emission.y > 0 || emission.z > 0; }
};

struct CameraSpec {
  Vec3f eye{0, 0, 1};
  Vec3f look_at{0, 0, 0};
  Vec3f up{0, 1, 0};
  float vfov_deg = 39.3077f;
};

struct Scene {
  std::string name;                    ///< used for the default output file name
  std::filesystem::path source;        ///< the file it was loaded from
  /// Every file read to make it: the scene file, each OBJ and each MTL (what
  /// no output of the run may overwrite).
  std::vector<std::filesystem::path> inputs;
  std::vector<Triangle> triangles;     ///< indexed by 32-bit TriangleId
  std::vector<std::uint32_t> material_of;  ///< per triangle, index into materials
  std::vector<Material> materials;
  CameraSpec camera;
  bool camera_framed = false;  ///< the camera frames the bounds (no camera given): re-frame if the film changes
  Vec3f environment{0, 0, 0};  ///< constant radiance of rays that escape
  int width = 512;
  int height = 512;
  /// Seconds load_scene took to read, check and parse the files (reported
  /// apart from the accelerator's build and the render).
  double load_s = 0;

  Bounds3f bounds() const;
};

/// Camera framing a bounding box from the front (+z) and slightly above, far
/// enough that the bounding sphere fits the vertical field of view.
CameraSpec framing_camera(const Bounds3f& box, float vfov_deg, float aspect);

}  // namespace kappa
