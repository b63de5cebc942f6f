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

void Camera::footprint(const Vec3f& p, const Vec3f& n, const Vec3f& d, Vec3f& dpdx, Vec3f& dpdy) const {
  dpdx = dpdy = Vec3f{0, 0, 0};
  // The film plane at distance 1 along forward: the ray's direction scaled
  // to it, and the neighbouring pixels' directions one pixel step away.
  const float along = dot(d, m_forward);
  if (!(along > 0.0f)) return;
  const Vec3f D = d / along;
  const Vec3f to_p = p - m_eye;
  const float plane = dot(n, to_p);
  auto meet = [&](const Vec3f& dir, Vec3f& dp) {
    const float denom = dot(n, dir);
    if (!(std::abs(denom) > 1e-8f)) return;
    const float t = plane / denom;
    if (!(t > 0.0f) || !std::isfinite(t)) return;
    dp = m_eye + dir * t - p;
  };
  meet(D + m_right * m_scale_x, dpdx);
  meet(D - m_up * m_scale_y, dpdy);
}

}  // namespace kappa
