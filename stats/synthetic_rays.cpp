#include "synthetic_rays.h"

#include <cmath>
#include <numbers>
#include <random>

namespace kappa {
namespace {

Vec3d isotropic(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double z = 1.0 - 2.0 * u(rng), phi = 2.0 * std::numbers::pi * u(rng);
  const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {s * std::cos(phi), s * std::sin(phi), z};
}

}  // namespace

std::optional<std::pair<double, double>> clip_to_box(const Vec3d& o, const Vec3d& d, const Vec3d& lo, const Vec3d& hi,
                                                     double t0, double t1) {
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0) {
      if (o[a] < lo[a] || o[a] > hi[a]) return std::nullopt;
      continue;
    }
    double tn = (lo[a] - o[a]) / d[a], tf = (hi[a] - o[a]) / d[a];
    if (tn > tf) std::swap(tn, tf);
    t0 = std::max(t0, tn);
    t1 = std::min(t1, tf);
  }
  if (!(t0 <= t1)) return std::nullopt;
  return std::pair{t0, t1};
}

std::vector<Ray> uniform_lines(const Vec3d& lo, const Vec3d& hi, std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed ^ 0x6c696e6573ull);  // "lines"
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Vec3d center = (lo + hi) * 0.5;
  const double radius = 0.5 * length(hi - lo);
  std::vector<Ray> rays;
  rays.reserve(n);
  for (std::size_t tries = 0; rays.size() < n && tries < 100 * n + 100; ++tries) {
    const Vec3d d = isotropic(rng);
    // Orthonormal basis around d (Duff et al. 2017).
    const double sign = std::copysign(1.0, d.z), a = -1.0 / (sign + d.z), b = d.x * d.y * a;
    const Vec3d s{1.0 + sign * d.x * d.x * a, sign * b, -sign * d.x}, t{b, sign + d.y * d.y * a, -d.y};
    const double r = radius * std::sqrt(u(rng)), phi = 2.0 * std::numbers::pi * u(rng);
    const Vec3d p = center + s * (r * std::cos(phi)) + t * (r * std::sin(phi));
    if (!clip_to_box(p, d, lo, hi)) continue;
    rays.push_back(Ray{Vec3f(p - d * (1.01 * radius)), Vec3f(d)});
  }
  return rays;
}

std::vector<Ray> uniform_segments(const Vec3d& lo, const Vec3d& hi, double length, std::size_t n,
                                  std::uint64_t seed) {
  std::mt19937_64 rng(seed ^ 0x7365676dull);  // "segm"
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Ray> rays;
  rays.reserve(n);
  for (std::size_t tries = 0; rays.size() < n && tries < 1000 * n + 100; ++tries) {
    const Vec3d o = lo + Vec3d{u(rng), u(rng), u(rng)} * (hi - lo);
    const Vec3d d = isotropic(rng);
    const Vec3d e = o + d * length;
    if (e.x < lo.x || e.y < lo.y || e.z < lo.z || e.x > hi.x || e.y > hi.y || e.z > hi.z) continue;
    rays.push_back(Ray{Vec3f(o), Vec3f(d), 0.0f, float(length)});
  }
  return rays;
}

}  // namespace kappa
