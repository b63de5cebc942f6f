// glTF materials onto Kappa's material record (renderer/scene/material.h),
// whose model is glTF's own metallic-roughness BSDF: the factors, their
// textures (through the texture maps' OpenImageIO path, with each texture's
// sampler), alphaMode MASK as cut-outs, and the extensions Kappa models
// (KHR_materials_emissive_strength, _transmission, _ior, _specular). What it
// does not model is warned once per kind: normal and occlusion maps, other
// extensions, texture coordinate sets other than 0, BLEND (read as MASK at 0.5).
#pragma once

#include <cstdint>
#include <map>

#include "renderer/scene/gltf/gltf_file.h"
#include "renderer/scene/gltf/gltf_warnings.h"
#include "renderer/scene/scene.h"

namespace kappa {

class GltfMaterials {
 public:
  GltfMaterials(const GltfFile& gltf, Scene& scene, GltfWarnings& warnings)
      : m_gltf(gltf), m_scene(scene), m_warnings(warnings) {}

  /// The scene's index of glTF material `index` (-1: the specification's
  /// default material), converted on its first use.
  std::uint32_t material(int index, const std::string& user);

 private:
  Material convert(int index);
  /// A map of texture `info` for `slot` (its index in Scene::texture_maps),
  /// or -1 when the texture has no image Kappa reads (warned).
  std::int32_t texture_map(const tinygltf::TextureInfo& info, const std::string& pointer, MapSlot slot);

  const GltfFile& m_gltf;
  Scene& m_scene;
  GltfWarnings& m_warnings;
  std::map<int, std::uint32_t> m_converted;
};

}  // namespace kappa
