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

  /// How the point p (unit geometric normal n) seen along the camera ray of
  /// direction d moves per pixel across (dpdx) and down (dpdy): where the
  /// rays through the neighbouring film positions meet p's tangent plane
  /// (exact ray differentials for a pinhole; zero at grazing angles).
  void footprint(const Vec3f& p, const Vec3f& n, const Vec3f& d, Vec3f& dpdx, Vec3f& dpdy) const;

 private:
  Vec3f m_eye, m_forward, m_right, m_up;
  float m_scale_x = 1, m_scale_y = 1;  ///< tan(half fov) times 2/size per axis
  float m_half_w = 0, m_half_h = 0;
};

}  // namespace kappa
