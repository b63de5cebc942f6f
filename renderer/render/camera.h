// Pinhole camera. Screen right is normalize(forward x up), so with up = +y and
// forward = +z the image's right points to -x (the Cornell box's red wall, at
// x = 556, appears on the left as in the reference photographs).
#pragma once

#include "accel/ray.h"
#include "renderer/scene/scene.h"

namespace kappa {

class Camera {
 public:
  Camera(const CameraSpec& spec, int width, int height);

  /// Primary ray through film position (x, y) in pixels, y down from the top
  /// row; direction normalized, so hit t is the distance from the eye.
  Ray generate_ray(float x, float y) const;

 private:
  Vec3f m_eye, m_forward, m_right, m_up;
  float m_scale_x = 1, m_scale_y = 1;  ///< tan(half fov) times 2/size per axis
  float m_half_w = 0, m_half_h = 0;
};

}  // namespace kappa
