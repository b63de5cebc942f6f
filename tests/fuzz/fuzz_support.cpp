#include "fuzz_support.h"

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <fstream>

#include "core/check.h"
#include "core/error.h"
#include "renderer/scene/obj/obj_limits.h"
#include "renderer/scene/scene_loader.h"

namespace kappa::fuzz {
namespace {

bool finite(const Vec3f& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool within_limit(const Vec3f& v) {
  return std::fabs(double(v.x)) <= kMaxCoordinate && std::fabs(double(v.y)) <= kMaxCoordinate &&
         std::fabs(double(v.z)) <= kMaxCoordinate;
}

bool in_unit_range(const Vec3f& v) { return v.x >= 0 && v.x <= 1 && v.y >= 0 && v.y <= 1 && v.z >= 0 && v.z <= 1; }

}  // namespace

const std::filesystem::path& scratch_dir() {
  static const std::filesystem::path dir = [] {
    auto p = std::filesystem::temp_directory_path() / ("kappa-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(p);
    return p;
  }();
  // Registered once `dir` is constructed, so that it runs before dir's
  // destructor (atexit calls run in reverse order of registration): from
  // inside dir's initialiser it ran after, on a destroyed path, and left
  // every replay's folder behind.
  static const bool removed_at_exit = std::atexit([] {
    std::error_code ec;
    std::filesystem::remove_all(scratch_dir(), ec);
  }) == 0;
  (void)removed_at_exit;
  return dir;
}

std::filesystem::path write_scratch(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const auto path = scratch_dir() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  KAPPA_CHECK(bool(out));
  return path;
}

void require_refusal_names_an_input(const std::string& message) {
  // The fuzzed file, one beside it, or an absolute path the input names
  // (`mtllib /` is refused as "/: is a directory"): a path either way.
  KAPPA_CHECK(message.rfind(scratch_dir().string() + "/", 0) == 0 || message.rfind("/", 0) == 0);
  KAPPA_CHECK(message.find(": ") != std::string::npos);
}

void require_valid_scene(const Scene& scene) {
  KAPPA_CHECK_EQ(scene.material_of.size(), scene.triangles.size());
  for (const Triangle& t : scene.triangles) {
    for (const Vec3f& v : {t.v0, t.v1, t.v2}) {
      KAPPA_CHECK(finite(v));
      KAPPA_CHECK(within_limit(v));
    }
  }
  for (const std::uint32_t m : scene.material_of) KAPPA_CHECK_LT(m, scene.materials.size());
  for (const Material& m : scene.materials) {
    KAPPA_CHECK(finite(m.albedo) && in_unit_range(m.albedo));
    KAPPA_CHECK(finite(m.emission) && m.emission.x >= 0 && m.emission.y >= 0 && m.emission.z >= 0);
  }
  KAPPA_CHECK(finite(scene.camera.eye) && finite(scene.camera.look_at) && finite(scene.camera.up));
  KAPPA_CHECK(std::isfinite(scene.camera.vfov_deg) && scene.camera.vfov_deg > 0 && scene.camera.vfov_deg < 180);
  KAPPA_CHECK(finite(scene.environment) && scene.environment.x >= 0 && scene.environment.y >= 0 &&
              scene.environment.z >= 0);
  KAPPA_CHECK_GT(scene.width, 0);
  KAPPA_CHECK_GT(scene.height, 0);
  for (const NamedCamera& c : scene.cameras) {
    KAPPA_CHECK(finite(c.spec.eye) && finite(c.spec.look_at) && finite(c.spec.up));
    KAPPA_CHECK(length(cross(c.spec.look_at - c.spec.eye, c.spec.up)) > 0.0f);
    KAPPA_CHECK(std::isfinite(c.spec.vfov_deg) && c.spec.vfov_deg > 0 && c.spec.vfov_deg < 180);
  }
  for (const PunctualLight& l : scene.punctual_lights) {
    KAPPA_CHECK(finite(l.position) && within_limit(l.position) && finite(l.direction) && finite(l.intensity));
    KAPPA_CHECK(l.intensity.x >= 0 && l.intensity.y >= 0 && l.intensity.z >= 0);
    KAPPA_CHECK(std::isfinite(l.cos_inner) && std::isfinite(l.cos_outer));
  }
  for (const TextureMap& m : scene.texture_maps) KAPPA_CHECK(finite(m.factor));
}

void load_and_check(const std::filesystem::path& file) {
  Warnings warnings;
  try {
    require_valid_scene(load_scene(file, warnings));
  } catch (const InputError& e) {
    require_refusal_names_an_input(e.what());
  }
}

}  // namespace kappa::fuzz
