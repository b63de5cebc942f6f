#include "renderer/scene/generated_scene.h"

#include <cmath>
#include <random>
#include <string>

namespace kappa {
namespace {

void add_quad(Scene& scene, Vec3f a, Vec3f b, Vec3f c, Vec3f d, std::uint32_t material) {
  scene.triangles.push_back({a, b, c});
  scene.triangles.push_back({a, c, d});
  scene.material_of.insert(scene.material_of.end(), 2, material);
}

}  // namespace

Scene generated_soup_scene(std::size_t triangles, std::uint64_t seed) {
  Scene scene;
  scene.name = "soup" + std::to_string(triangles);
  scene.materials = {Material{"grey", {0.6f, 0.6f, 0.6f}, {0, 0, 0}}, Material{"lamp", {0, 0, 0}, {8, 8, 8}}};
  // The room: floor, ceiling, back and side walls, normals facing in (seen
  // counter-clockwise from inside); the front (z = 1) is open to the camera.
  add_quad(scene, {0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}, 0);  // floor, +y
  add_quad(scene, {0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}, 0);  // ceiling, -y
  add_quad(scene, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, 0);  // back, +z
  add_quad(scene, {0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}, 0);  // left, +x
  add_quad(scene, {1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}, 0);  // right, -x
  add_quad(scene, {0.4f, 0.999f, 0.4f}, {0.6f, 0.999f, 0.4f}, {0.6f, 0.999f, 0.6f}, {0.4f, 0.999f, 0.6f}, 1);  // lamp, -y
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
  scene.width = scene.height = 256;
  scene.camera = CameraSpec{{0.5f, 0.5f, 2.2f}, {0.5f, 0.5f, 0.5f}, {0, 1, 0}, 39.3077f};
  return scene;
}

}  // namespace kappa
