#include "renderer/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace kappa {

bool Scene::has_materials() const {
  for (const Material& m : materials)
    if (!m.lambertian()) return true;
  return false;
}

bool Scene::has_cutouts() const {
  for (const Material& m : materials)
    if (m.cut_out()) return true;
  return false;
}

Bounds3f Scene::bounds() const {
  Bounds3f b;
  for (const Triangle& t : triangles) {
    b.extend(t.v0);
    b.extend(t.v1);
    b.extend(t.v2);
  }
  return b;
}

CameraSpec framing_camera(const Bounds3f& box, float vfov_deg, float aspect) {
  const Vec3d lo(box.lo), hi(box.hi);
  const Vec3d center = (lo + hi) * 0.5;
  double radius = 0.5 * length(hi - lo);
  if (!(radius > 0)) radius = std::max(1.0, std::abs(max_component(abs(center))) * 1e-3);
  // The narrower of the two fields of view decides the distance.
  const double half_v = 0.5 * double(vfov_deg) * std::numbers::pi / 180.0;
  const double half_h = std::atan(std::tan(half_v) * aspect);
  const double distance = 1.1 * radius / std::sin(std::min(half_v, half_h));
  const Vec3d view_dir = normalize(Vec3d{0.0, 0.25, 1.0});
  CameraSpec c;
  c.look_at = Vec3f(center);
  c.eye = Vec3f(center + view_dir * distance);
  c.up = {0, 1, 0};
  c.vfov_deg = vfov_deg;
  return c;
}

}  // namespace kappa
