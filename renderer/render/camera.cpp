#include "renderer/render/camera.h"

#include <cmath>
#include <numbers>

namespace kappa {

Camera::Camera(const CameraSpec& spec, int width, int height) {
  const Vec3d forward = normalize(Vec3d(spec.look_at) - Vec3d(spec.eye));
  const Vec3d right = normalize(cross(forward, Vec3d(spec.up)));
  const Vec3d up = cross(right, forward);
  m_eye = spec.eye;
  m_forward = Vec3f(forward);
  m_right = Vec3f(right);
  m_up = Vec3f(up);
  const double tan_half = std::tan(0.5 * double(spec.vfov_deg) * std::numbers::pi / 180.0);
  m_half_w = 0.5f * float(width);
  m_half_h = 0.5f * float(height);
  // Square pixels: the vertical field of view fixes the scale of both axes.
  m_scale_y = float(tan_half / m_half_h);
  m_scale_x = m_scale_y;
}

Ray Camera::generate_ray(float x, float y) const {
  const float sx = (x - m_half_w) * m_scale_x;
  const float sy = (m_half_h - y) * m_scale_y;
  Ray r;
  r.o = m_eye;
  r.d = normalize(m_forward + m_right * sx + m_up * sy);
  return r;
}

}  // namespace kappa
