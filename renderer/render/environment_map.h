// An environment image as a light: radiance by direction from a latitude-
// longitude image, and directions drawn in proportion to its luminance times
// sin(theta) (a piecewise-constant 2D distribution over its texels, pbrt-v4's
// ImageInfiniteLight idea on the equirectangular map) for next-event
// estimation, with the density MIS weighs BSDF samples against.
//
// Orientation (docs/scene-format.md): +y is up; row 0 of the image is
// straight up, the middle row the horizon; the image's centre column looks
// along +x and u grows towards +z, so a Y-up OBJ exported from Blender sees
// the image where Blender's world shows it. `environment_rotation_deg`
// turns the image about +y, right-handed (+z towards +x for a positive
// angle). Texels are read nearest (no filtering), so the radiance is
// exactly the piecewise-constant function the distribution samples.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include "core/piecewise_constant.h"
#include "core/vec3.h"
#include "renderer/scene/scene.h"

namespace kappa {

class EnvironmentMap {
 public:
  EnvironmentMap(const EnvironmentImage& image, float rotation_deg) : m_image(&image) {
    const double a = double(rotation_deg) * std::numbers::pi / 180.0;
    m_cos = float(std::cos(a));
    m_sin = float(std::sin(a));
    const std::size_t w = std::size_t(image.width), h = std::size_t(image.height);
    std::vector<double> f(w * h);
    for (std::size_t y = 0; y < h; ++y) {
      const double sin_theta = std::sin(std::numbers::pi * (double(y) + 0.5) / double(h));
      for (std::size_t x = 0; x < w; ++x) {
        const float* t = &image.rgb[3 * (y * w + x)];
        f[y * w + x] = (0.2126 * t[0] + 0.7152 * t[1] + 0.0722 * t[2]) * sin_theta;
      }
    }
    m_distribution = PiecewiseConstant2D(f, w, h);
  }

  /// Radiance arriving from direction `d` (unit; towards the environment).
  Vec3f Le(const Vec3f& d) const {
    double u, v;
    image_uv(d, u, v);
    return texel(u, v);
  }

  /// Solid-angle density of sample() drawing `d`.
  float pdf(const Vec3f& d) const {
    double u, v;
    image_uv(d, u, v);
    const double sin_theta = std::sin(std::numbers::pi * v);
    if (!(sin_theta > 0)) return 0.0f;
    return float(m_distribution.pdf(u, v) / (2.0 * std::numbers::pi * std::numbers::pi * sin_theta));
  }

  struct Sample {
    Vec3f wi;   ///< towards the environment
    Vec3f Le;
    float pdf;  ///< solid angle
  };
  std::optional<Sample> sample(float u1, float u2) const {
    double u, v, pdf_uv;
    m_distribution.sample(u1, u2, u, v, pdf_uv);
    const double theta = std::numbers::pi * v, phi = 2.0 * std::numbers::pi * (u - 0.5);
    const double sin_theta = std::sin(theta);
    if (!(sin_theta > 0) || !(pdf_uv > 0)) return std::nullopt;
    const Vec3f local{float(std::cos(phi) * sin_theta), float(std::cos(theta)), float(std::sin(phi) * sin_theta)};
    const float pdf = float(pdf_uv / (2.0 * std::numbers::pi * std::numbers::pi * sin_theta));
    if (!(pdf > 0.0f) || !std::isfinite(pdf)) return std::nullopt;
    return Sample{rotate(local, m_sin), texel(u, v), pdf};
  }

 private:
  /// About +y by the angle whose sine is s (cosine m_cos); -s undoes it.
  Vec3f rotate(const Vec3f& d, float s) const { return {m_cos * d.x + s * d.z, d.y, -s * d.x + m_cos * d.z}; }

  void image_uv(const Vec3f& world, double& u, double& v) const {
    const Vec3f d = rotate(world, -m_sin);
    u = 0.5 + std::atan2(double(d.z), double(d.x)) / (2.0 * std::numbers::pi);
    v = std::acos(std::clamp(double(d.y), -1.0, 1.0)) / std::numbers::pi;
    if (!(u >= 0.0)) u = 0.0;  // NaN from a degenerate direction
    if (!(v >= 0.0)) v = 0.0;
  }

  Vec3f texel(double u, double v) const {
    const int w = m_image->width, h = m_image->height;
    const int x = std::clamp(int(u * double(w)), 0, w - 1), y = std::clamp(int(v * double(h)), 0, h - 1);
    const float* t = &m_image->rgb[3 * (std::size_t(y) * std::size_t(w) + std::size_t(x))];
    return {t[0], t[1], t[2]};
  }

  const EnvironmentImage* m_image;
  float m_cos = 1, m_sin = 0;
  PiecewiseConstant2D m_distribution;
};

}  // namespace kappa
