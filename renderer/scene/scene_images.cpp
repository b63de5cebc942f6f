#include "renderer/scene/scene_images.h"

#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/input_error.h"
#include "core/srgb.h"
#include "renderer/image/image_library.h"

namespace kappa {
namespace {

std::string size_text(const ImageFacts& f) { return std::to_string(f.width) + "x" + std::to_string(f.height); }

/// Reads the image file `file` once (hashed for the report's provenance) and
/// hands its bytes to the library, which decodes it from memory from then on:
/// no image is opened again after loading.
void read_image_file(ImageLibrary& lib, const std::filesystem::path& file, const std::filesystem::path& where,
                     std::size_t line, const std::string& what) {
  std::string bytes;
  try {
    bytes = read_input_file(file, "an image file");
  } catch (const InputError& e) {
    fail(where, line, what + ": " + e.what());
  }
  lib.add_memory_file(file.string(), std::vector<unsigned char>(bytes.begin(), bytes.end()));
}

/// The header of `file`, refused (at `where`:`line`) when OpenImageIO cannot
/// read it or it is empty or over the size limit.
ImageFacts checked_facts(ImageLibrary& lib, const std::filesystem::path& file, const std::filesystem::path& where,
                         std::size_t line, const std::string& what) {
  ImageFacts f;
  try {
    f = lib.inspect(file.string());
  } catch (const std::runtime_error& e) {
    fail(where, line, what + " '" + file.string() + "': " + e.what());
  }
  if (f.width < 1 || f.height < 1 || f.channels < 1)
    fail(where, line, what + " '" + file.string() + "' has no texels (" + size_text(f) + ")");
  if (std::uint64_t(f.width) * std::uint64_t(f.height) > kMaxImageTexels)
    fail(where, line, what + " '" + file.string() + "' is " + size_text(f) + ": more than Kappa's limit of " +
                          std::to_string(kMaxImageTexels) + " texels (16384 x 16384)");
  return f;
}

/// Reads every texel once (a truncated or corrupt file is refused here, not
/// found out as black texels in the render) and warns about unusable ones.
void check_texels(ImageLibrary& lib, const std::filesystem::path& file, const std::filesystem::path& where,
                  std::size_t line, const std::string& what, const std::string& becomes, Warnings& warnings) {
  TexelScan scan;
  try {
    scan = lib.scan(file.string());
  } catch (const std::runtime_error& e) {
    fail(where, line, what + " '" + file.string() + "': " + e.what());
  }
  if (scan.nan + scan.infinite + scan.negative > 0)
    warnings.push_back(located(where, line, what + " '" + file.string() + "' has " + std::to_string(scan.nan) +
                                                " NaN, " + std::to_string(scan.infinite) + " infinite and " +
                                                std::to_string(scan.negative) + " negative texel values: " + becomes));
}

/// The mean of a colour map's texels as lookups decode them (NaN and
/// negatives 0): an emission map's power.
Vec3f mean_colour(ImageLibrary& lib, const TextureMap& map, const ImageFacts& f) {
  std::vector<float> texels;
  try {
    texels = lib.read(map.file.string(), 3);
  } catch (const std::runtime_error& e) {
    fail(map.declared_in, map.line, map.keyword + " '" + map.file.string() + "': " + e.what());
  }
  double sum[3] = {0, 0, 0};
  const std::size_t n = texels.size() / 3;
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      float v = texels[3 * i + std::size_t(f.channels >= 3 ? c : 0)];
      if (!f.floating) v = srgb_to_linear(v);
      sum[c] += v > 0.0f && std::isfinite(v) ? double(v) : 0.0;
    }
  return {float(sum[0] / double(n)) * map.factor.x, float(sum[1] / double(n)) * map.factor.y,
          float(sum[2] / double(n)) * map.factor.z};
}

void load_texture_maps(Scene& scene, ImageLibrary& lib, Warnings& warnings) {
  std::map<std::filesystem::path, ImageFacts> opened;  // a file named by several maps is checked once
  for (std::size_t k = 0; k < scene.texture_maps.size(); ++k) {
    TextureMap& map = scene.texture_maps[k];
    const std::string what = map.keyword;
    auto it = opened.find(map.file);
    if (it == opened.end()) {
      if (map.embedded) lib.add_memory_file(map.file.string(), *map.embedded);
      else read_image_file(lib, map.file, map.declared_in, map.line, what);
      const ImageFacts f = checked_facts(lib, map.file, map.declared_in, map.line, what);
      check_texels(lib, map.file, map.declared_in, map.line, what,
                   "NaN and negative values read as 0, values above 1 as 1", warnings);
      it = opened.emplace(map.file, f).first;
    }
    const ImageFacts& f = it->second;
    map.channels = f.channels;
    // Blender decodes every 8- and 16-bit image from sRGB, data maps too
    // (its OBJ importer sets no colour space); float images are linear.
    // Alpha is never encoded.
    map.srgb = !f.floating && !map.linear;
    if (f.width == 1 && f.height == 1)
      warnings.push_back(located(map.declared_in, map.line, what + " '" + map.file.string() +
                                                                "' is 1x1: a constant over the surface"));
    if (map.slot == MapSlot::opacity) {
      if (!f.alpha && !map.warn_without_alpha) {
        // glTF: an image without alpha has alpha 1 everywhere.
        if (!(map.alpha_factor >= map.alpha_cutoff)) {
          OpacityMask none;  // cut out everywhere: a 1x1 mask of 0
          none.width = none.height = 1;
          none.opaque = {0};
          map.mask = std::int32_t(scene.opacity_masks.size());
          scene.opacity_masks.push_back(std::move(none));
        }
        continue;
      }
      if (!f.alpha) {
        // Blender links the image's alpha output, which is 1 without an alpha channel.
        warnings.push_back(located(map.declared_in, map.line,
                                   what + " '" + map.file.string() + "' has no alpha channel: the surface stays opaque "
                                   "(Blender reads map_d's alpha); give the mask an alpha channel"));
        continue;
      }
      map.first_channel = f.alpha_channel;
      std::vector<float> texels;
      try {
        texels = lib.read(map.file.string(), f.channels);
      } catch (const std::runtime_error& e) {
        fail(map.declared_in, map.line, what + " '" + map.file.string() + "': " + e.what());
      }
      OpacityMask mask;
      mask.width = f.width;
      mask.height = f.height;
      mask.scale = map.scale;
      mask.offset = map.offset;
      mask.wrap_s = map.wrap_s;
      mask.wrap_t = map.wrap_t;
      mask.opaque.resize(std::size_t(f.width) * std::size_t(f.height));
      for (std::size_t i = 0; i < mask.opaque.size(); ++i)
        mask.opaque[i] =
            texels[i * std::size_t(f.channels) + std::size_t(f.alpha_channel)] * map.alpha_factor >= map.alpha_cutoff;
      map.mask = std::int32_t(scene.opacity_masks.size());
      scene.opacity_masks.push_back(std::move(mask));
      continue;
    }
    if (map.slot == MapSlot::emission) map.mean = mean_colour(lib, map, f);
    map.handle = lib.texture(map.file.string());
  }
  // An opacity map that became no mask leaves its material opaque.
  for (Material& m : scene.materials) {
    std::int32_t& k = m.maps[std::size_t(MapSlot::opacity)];
    if (k >= 0 && scene.texture_maps[std::size_t(k)].mask < 0) k = -1;
  }
}

void load_environment(Scene& scene, ImageLibrary& lib, Warnings& warnings) {
  const std::filesystem::path& file = scene.environment_file;
  const std::string what = "environment image";
  read_image_file(lib, file, scene.source, 0, what);
  const ImageFacts f = checked_facts(lib, file, scene.source, 0, what);
  if (f.width != 2 * f.height)
    warnings.push_back(located(scene.source, 0, what + " '" + file.string() + "' is " + size_text(f) +
                                                    ", not 2:1: stretched over the sphere's latitude and longitude"));
  std::vector<float> texels;
  try {
    texels = lib.read(file.string(), 3);
  } catch (const std::runtime_error& e) {
    fail(scene.source, 0, what + " '" + file.string() + "': " + e.what());
  }
  if (f.channels < 3)
    for (std::size_t i = 0; i < texels.size(); i += 3) texels[i + 1] = texels[i + 2] = texels[i];
  std::uint64_t unusable = 0;
  for (float& v : texels)
    if (!(v >= 0.0f) || !std::isfinite(v)) {
      v = 0.0f;
      ++unusable;
    }
  if (unusable > 0)
    warnings.push_back(located(scene.source, 0, what + " '" + file.string() + "' has " + std::to_string(unusable) +
                                                    " NaN, infinite or negative values: read as 0"));
  if (!f.floating)
    for (float& v : texels) v = srgb_to_linear(v);
  // A constant image is the constant environment: the same image bitwise,
  // and no importance sampling of a flat distribution.
  bool constant = true;
  for (std::size_t i = 3; i < texels.size() && constant; ++i) constant = texels[i] == texels[i % 3];
  if (constant) {
    scene.environment = {texels[0], texels[1], texels[2]};
    return;
  }
  // Its mean radiance over the sphere (exact solid angle per row): the
  // constant the light's power, and code that asks "is there an
  // environment", read.
  double sum[3] = {0, 0, 0};
  const double pi = 3.14159265358979323846;
  for (int y = 0; y < f.height; ++y) {
    const double omega = 2.0 * pi / double(f.width) *
                         (std::cos(pi * double(y) / double(f.height)) - std::cos(pi * double(y + 1) / double(f.height)));
    for (int x = 0; x < f.width; ++x)
      for (int c = 0; c < 3; ++c) sum[c] += double(texels[3 * (std::size_t(y) * std::size_t(f.width) + std::size_t(x)) + std::size_t(c)]) * omega;
  }
  scene.environment = {float(sum[0] / (4.0 * pi)), float(sum[1] / (4.0 * pi)), float(sum[2] / (4.0 * pi))};
  auto image = std::make_shared<EnvironmentImage>();
  image->width = f.width;
  image->height = f.height;
  image->rgb = std::move(texels);
  scene.environment_image = std::move(image);
}

}  // namespace

void load_scene_images(Scene& scene, Warnings& warnings) {
  if (scene.texture_maps.empty() && scene.environment_file.empty()) return;
  ImageLibrary& lib = image_library();
  load_texture_maps(scene, lib, warnings);
  if (!scene.environment_file.empty()) load_environment(scene, lib, warnings);
}

}  // namespace kappa
