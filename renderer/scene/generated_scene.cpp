#include "renderer/scene/generated_scene.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>

namespace kappa {
namespace {

void add_quad(Scene& scene, Vec3f a, Vec3f b, Vec3f c, Vec3f d, std::uint32_t material) {
  scene.triangles.push_back({a, b, c});
  scene.triangles.push_back({a, c, d});
  scene.material_of.insert(scene.material_of.end(), 2, material);
}

/// The room, its lamp and materials: everything but what stands in it.
Scene lit_room(const std::string& name) {
  Scene scene;
  scene.name = name;
  scene.materials = {Material{"grey", {0.6f, 0.6f, 0.6f}, {0, 0, 0}}, Material{"lamp", {0, 0, 0}, {8, 8, 8}}};
  // Floor, ceiling, back and side walls, normals facing in (seen
  // counter-clockwise from inside); the front (z = 1) is open to the camera.
  add_quad(scene, {0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}, 0);  // floor, +y
  add_quad(scene, {0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}, 0);  // ceiling, -y
  add_quad(scene, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, 0);  // back, +z
  add_quad(scene, {0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}, 0);  // left, +x
  add_quad(scene, {1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}, 0);  // right, -x
  add_quad(scene, {0.4f, 0.999f, 0.4f}, {0.6f, 0.999f, 0.4f}, {0.6f, 0.999f, 0.6f}, {0.4f, 0.999f, 0.6f}, 1);  // lamp, -y
  scene.width = scene.height = 256;
  scene.camera = CameraSpec{{0.5f, 0.5f, 2.2f}, {0.5f, 0.5f, 0.5f}, {0, 1, 0}, 39.3077f};
  return scene;
}

}  // namespace

Scene generated_blob_scene(std::size_t triangles) {
  Scene scene = lit_room("blob" + std::to_string(triangles));
  // rings x segments quads of two triangles, poles as fans.
  const int n = std::max(4, int(std::lround(std::sqrt(double(triangles) / 2.0))));
  const int rings = n, segments = n;
  const Vec3d centre{0.5, 0.36, 0.5};
  auto vertex = [&](int ring, int seg) {
    const double theta = std::numbers::pi * ring / rings, phi = 2 * std::numbers::pi * (seg % segments) / segments;
    // Bumps of a few wavelengths: a non-convex surface, as scanned models are.
    const double r = 0.3 * (1 + 0.12 * std::sin(5 * theta) * std::cos(4 * phi) + 0.05 * std::sin(13 * theta + 3 * phi));
    return Vec3f(centre + Vec3d{r * std::sin(theta) * std::cos(phi), r * std::cos(theta), r * std::sin(theta) * std::sin(phi)});
  };
  for (int ring = 0; ring < rings; ++ring)
    for (int seg = 0; seg < segments; ++seg) {
      const Vec3f a = vertex(ring, seg), b = vertex(ring + 1, seg), c = vertex(ring + 1, seg + 1), d = vertex(ring, seg + 1);
      // Outward: counter-clockwise seen from outside; the poles' degenerate
      // halves have zero area and are left out by the grid like any other.
      scene.triangles.push_back({a, b, c});
      scene.triangles.push_back({a, c, d});
      scene.material_of.insert(scene.material_of.end(), 2, 0);
    }
  return scene;
}

Scene generated_soup_scene(std::size_t triangles, std::uint64_t seed) {
  Scene scene = lit_room("soup" + std::to_string(triangles));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> inside(0.05f, 0.95f);
  const float size = 1.5f * 0.9f / std::cbrt(float(std::max<std::size_t>(triangles, 1)));
  std::uniform_real_distribution<float> edge(-size, size);
  for (std::size_t i = 0; i < triangles; ++i) {
    const Vec3f c{inside(rng), inside(rng), inside(rng)};
    scene.triangles.push_back({c + Vec3f{edge(rng), edge(rng), edge(rng)}, c + Vec3f{edge(rng), edge(rng), edge(rng)},
                               c + Vec3f{edge(rng), edge(rng), edge(rng)}});
    scene.material_of.push_back(0);
  }
  return scene;
}

}  // namespace kappa
