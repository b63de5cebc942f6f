#include "renderer/scene/gltf/gltf_material.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace kappa {
namespace {

/// A factor in [lo, hi]: clamped, with a warning, when outside; refused when
/// not a finite number.
double checked_factor(const std::filesystem::path& file, double v, double lo, double hi, const std::string& pointer,
                      GltfWarnings& warnings) {
  if (!std::isfinite(v)) fail(file, 0, pointer + ": not a finite number");
  const double c = std::clamp(v, lo, hi);
  // One warning a kind of factor (its key), not one a material.
  if (c != v)
    warnings.once("range " + pointer.substr(pointer.find_last_of('/') + 1), pointer,
                  std::to_string(v) + " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "], clamped");
  return c;
}

/// A number of an extension object, or `fallback` when absent.
double extension_number(const tinygltf::Value& ext, const char* key, double fallback, const std::filesystem::path& file,
                        const std::string& pointer) {
  if (!ext.IsObject() || !ext.Has(key)) return fallback;
  const tinygltf::Value& v = ext.Get(key);
  if (!v.IsNumber()) fail(file, 0, pointer + "/" + key + ": must be a number");
  return v.GetNumberAsDouble();
}

TextureWrap wrap_mode(int mode, const std::filesystem::path& file, const std::string& pointer) {
  switch (mode) {
    case TINYGLTF_TEXTURE_WRAP_REPEAT: return TextureWrap::periodic;
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return TextureWrap::clamp;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return TextureWrap::mirror;
    default: fail(file, 0, pointer + ": " + std::to_string(mode) + " is not a glTF wrap mode (10497, 33071, 33648)");
  }
}

/// The extension Kappa models on a material, or warns about.
const std::set<std::string>& modelled_material_extensions() {
  static const std::set<std::string> names = {"KHR_materials_emissive_strength", "KHR_materials_transmission",
                                              "KHR_materials_ior", "KHR_materials_specular"};
  return names;
}

}  // namespace

std::uint32_t GltfMaterials::material(int index, const std::string& user) {
  if (index < -1 || (index >= 0 && std::size_t(index) >= m_gltf.model.materials.size()))
    fail(m_gltf.file, 0, user + "/material: " + std::to_string(index) + " does not exist (" +
                             std::to_string(m_gltf.model.materials.size()) + " materials)");
  const auto it = m_converted.find(index);
  if (it != m_converted.end()) return it->second;
  Material m = convert(index);
  m_scene.materials.push_back(std::move(m));
  const auto k = std::uint32_t(m_scene.materials.size() - 1);
  m_converted.emplace(index, k);
  return k;
}

std::int32_t GltfMaterials::texture_map(const tinygltf::TextureInfo& info, const std::string& pointer, MapSlot slot) {
  const std::filesystem::path& file = m_gltf.file;
  const tinygltf::Model& model = m_gltf.model;
  if (info.index < 0 || std::size_t(info.index) >= model.textures.size())
    fail(file, 0, pointer + "/index: texture " + std::to_string(info.index) + " does not exist (" +
                      std::to_string(model.textures.size()) + " textures)");
  const std::string texture_pointer = json_pointer({"textures", std::to_string(info.index)});
  const tinygltf::Texture& texture = model.textures[std::size_t(info.index)];
  if (texture.source < 0) {
    std::string via;
    for (const auto& [name, value] : texture.extensions) via += (via.empty() ? " (" : ", ") + name;
    m_warnings.once("texture without source", texture_pointer,
                    "no image Kappa reads" + (via.empty() ? std::string() : via + ")") + ": the texture is ignored");
    return -1;
  }
  if (std::size_t(texture.source) >= model.images.size())
    fail(file, 0, texture_pointer + "/source: image " + std::to_string(texture.source) + " does not exist (" +
                      std::to_string(model.images.size()) + " images)");
  for (const auto& [name, value] : texture.extensions)
    m_warnings.once("texture extension " + name, texture_pointer, "extension " + name + " is not read: ignored");
  if (info.texCoord != 0)
    m_warnings.once("texCoord", pointer + "/texCoord",
                    "texture coordinate set " + std::to_string(info.texCoord) +
                        " is not read: the texture is looked up with TEXCOORD_0");
  for (const auto& [name, value] : info.extensions)
    m_warnings.once("texture info extension " + name, pointer,
                    "extension " + name + (name == "KHR_texture_transform" ? " (the texture's placement)" : "") +
                        " is not read: ignored");

  TextureMap map;
  map.slot = slot;
  map.declared_in = file;
  map.keyword = pointer;
  const std::size_t image = std::size_t(texture.source);
  const tinygltf::Image& img = model.images[image];
  if (m_gltf.embedded_images[image]) {
    std::string ext = img.mimeType.rfind("image/", 0) == 0 ? img.mimeType.substr(6) : std::string("img");
    if (ext == "jpeg") ext = "jpg";
    map.file = file.string() + "#images/" + std::to_string(image) + "." + ext;
    map.embedded = m_gltf.embedded_images[image];
  } else {
    map.file = img.uri;
    if (std::find(m_scene.inputs.begin(), m_scene.inputs.end(), map.file) == m_scene.inputs.end())
      m_scene.inputs.push_back(map.file);
  }
  if (texture.sampler >= 0) {
    if (std::size_t(texture.sampler) >= model.samplers.size())
      fail(file, 0, texture_pointer + "/sampler: " + std::to_string(texture.sampler) + " does not exist");
    const tinygltf::Sampler& s = model.samplers[std::size_t(texture.sampler)];
    const std::string sp = json_pointer({"samplers", std::to_string(texture.sampler)});
    map.wrap_s = wrap_mode(s.wrapS, file, sp + "/wrapS");
    map.wrap_t = wrap_mode(s.wrapT, file, sp + "/wrapT");
  }
  // glTF's v runs down the image: the loader stores 1 - v, as an OBJ's v
  // runs, so the lookup's flip gives the glTF row back.
  m_scene.texture_maps.push_back(std::move(map));
  return std::int32_t(m_scene.texture_maps.size() - 1);
}

Material GltfMaterials::convert(int index) {
  const std::filesystem::path& file = m_gltf.file;
  Material m;
  m.specular = 0.5f;  // the dielectric's own Fresnel (F0 0.04 at IOR 1.5)
  if (index < 0) {
    // The specification's default material: every property at its default.
    m.name = "(glTF default material)";
    m.albedo = {1, 1, 1};
    m.metallic = 1;
    m.roughness = 1;
    return m;
  }
  const tinygltf::Material& g = m_gltf.model.materials[std::size_t(index)];
  const std::string p = json_pointer({"materials", std::to_string(index)});
  m.name = g.name.empty() ? "material " + std::to_string(index) : g.name;
  const tinygltf::PbrMetallicRoughness& pbr = g.pbrMetallicRoughness;
  const std::string pp = p + "/pbrMetallicRoughness";
  if (pbr.baseColorFactor.size() != 4) fail(file, 0, pp + "/baseColorFactor: must be 4 numbers");
  double base[4];
  for (int c = 0; c < 4; ++c)
    base[c] = checked_factor(file, pbr.baseColorFactor[std::size_t(c)], 0, 1, pp + "/baseColorFactor", m_warnings);
  m.albedo = {float(base[0]), float(base[1]), float(base[2])};
  m.metallic = float(checked_factor(file, pbr.metallicFactor, 0, 1, pp + "/metallicFactor", m_warnings));
  m.roughness = float(checked_factor(file, pbr.roughnessFactor, 0, 1, pp + "/roughnessFactor", m_warnings));

  if (pbr.baseColorTexture.index >= 0) {
    const std::int32_t k = texture_map(pbr.baseColorTexture, pp + "/baseColorTexture", MapSlot::base_color);
    if (k >= 0) {
      m_scene.texture_maps[std::size_t(k)].factor = m.albedo;
      m.maps[std::size_t(MapSlot::base_color)] = k;
    }
  }
  if (pbr.metallicRoughnessTexture.index >= 0) {
    const std::string tp = pp + "/metallicRoughnessTexture";
    // Roughness in the green channel, metallic in the blue, linear data.
    const std::int32_t r = texture_map(pbr.metallicRoughnessTexture, tp, MapSlot::roughness);
    if (r >= 0) {
      TextureMap& map = m_scene.texture_maps[std::size_t(r)];
      map.scalar_channel = 1;
      map.linear = true;
      map.factor = {m.roughness, m.roughness, m.roughness};
      m.maps[std::size_t(MapSlot::roughness)] = r;
      TextureMap metal = map;
      metal.slot = MapSlot::metallic;
      metal.scalar_channel = 2;
      metal.factor = {m.metallic, m.metallic, m.metallic};
      m_scene.texture_maps.push_back(std::move(metal));
      m.maps[std::size_t(MapSlot::metallic)] = std::int32_t(m_scene.texture_maps.size() - 1);
    }
  }

  // Emission: emissiveFactor x KHR_materials_emissive_strength, times the texture.
  if (g.emissiveFactor.size() != 3) fail(file, 0, p + "/emissiveFactor: must be 3 numbers");
  double strength = 1;
  Vec3f emission;
  for (int c = 0; c < 3; ++c)
    (&emission.x)[c] = float(checked_factor(file, g.emissiveFactor[std::size_t(c)], 0, 1, p + "/emissiveFactor", m_warnings));
  const auto ext = [&](const char* name) -> const tinygltf::Value* {
    const auto it = g.extensions.find(name);
    return it == g.extensions.end() ? nullptr : &it->second;
  };
  if (const tinygltf::Value* e = ext("KHR_materials_emissive_strength")) {
    const std::string ep = p + "/extensions/KHR_materials_emissive_strength";
    strength = extension_number(*e, "emissiveStrength", 1.0, file, ep);
    if (!(strength >= 0) || !std::isfinite(strength)) fail(file, 0, ep + "/emissiveStrength: must be a finite number >= 0");
  }
  m.emission = emission * float(strength);
  if (g.emissiveTexture.index >= 0 && m.emission.x + m.emission.y + m.emission.z > 0) {
    const std::int32_t k = texture_map(g.emissiveTexture, p + "/emissiveTexture", MapSlot::emission);
    if (k >= 0) {
      m_scene.texture_maps[std::size_t(k)].factor = m.emission;
      m.maps[std::size_t(MapSlot::emission)] = k;
    }
  }

  if (const tinygltf::Value* e = ext("KHR_materials_specular")) {
    const std::string ep = p + "/extensions/KHR_materials_specular";
    m.specular = 0.5f * float(checked_factor(file, extension_number(*e, "specularFactor", 1.0, file, ep), 0, 1,
                                             ep + "/specularFactor", m_warnings));
    if (e->Has("specularColorFactor"))
      m_warnings.once("specularColorFactor", ep + "/specularColorFactor",
                      "a coloured specular is not modelled: read as white");
    for (const char* t : {"specularTexture", "specularColorTexture"})
      if (e->Has(t)) m_warnings.once(t, ep + "/" + t, std::string(t) + " is not read: the factor is used");
  }
  if (const tinygltf::Value* e = ext("KHR_materials_ior")) {
    const std::string ep = p + "/extensions/KHR_materials_ior";
    const double ior = extension_number(*e, "ior", 1.5, file, ep);
    if (ior == 0) {
      m_warnings.once("ior 0", ep + "/ior", "0 (a specular-only surface) is not modelled: read as 1.5");
    } else {
      m.ior = float(checked_factor(file, ior, 1.0, 10.0, ep + "/ior", m_warnings));
    }
  }
  if (const tinygltf::Value* e = ext("KHR_materials_transmission")) {
    const std::string ep = p + "/extensions/KHR_materials_transmission";
    m.transmission = float(checked_factor(file, extension_number(*e, "transmissionFactor", 0.0, file, ep), 0, 1,
                                          ep + "/transmissionFactor", m_warnings));
    if (e->Has("transmissionTexture"))
      m_warnings.once("transmissionTexture", ep + "/transmissionTexture",
                      "transmissionTexture is not read: the factor is used");
  }
  for (const auto& [name, value] : g.extensions)
    if (!modelled_material_extensions().count(name))
      m_warnings.once("material extension " + name, p + "/extensions/" + name,
                      "extension " + name + " is not modelled: ignored");

  // Cut-outs: MASK compares alpha (factor x texel) with alphaCutoff.
  if (g.alphaMode == "MASK" || g.alphaMode == "BLEND") {
    double cutoff = g.alphaMode == "MASK" ? g.alphaCutoff : 0.5;
    if (g.alphaMode == "BLEND")
      m_warnings.once("BLEND", p + "/alphaMode",
                      "BLEND is read as MASK with a cutoff of 0.5: Kappa's cut-outs are binary");
    if (!std::isfinite(cutoff) || cutoff < 0) fail(file, 0, p + "/alphaCutoff: must be a finite number >= 0");
    const std::int32_t base_map = m.maps[std::size_t(MapSlot::base_color)];
    if (base_map >= 0) {
      TextureMap mask = m_scene.texture_maps[std::size_t(base_map)];
      mask.slot = MapSlot::opacity;
      mask.alpha_factor = float(base[3]);
      mask.alpha_cutoff = float(cutoff);
      mask.warn_without_alpha = false;
      mask.factor = {1, 1, 1};
      m_scene.texture_maps.push_back(std::move(mask));
      m.maps[std::size_t(MapSlot::opacity)] = std::int32_t(m_scene.texture_maps.size() - 1);
    } else {
      m.opacity = base[3] >= cutoff ? 1.0f : 0.0f;
    }
  } else if (g.alphaMode != "OPAQUE") {
    fail(file, 0, p + "/alphaMode: '" + g.alphaMode + "' is not OPAQUE, MASK or BLEND");
  }

  if (g.normalTexture.index >= 0)
    m_warnings.once("normalTexture", p + "/normalTexture",
                    "normal maps are not modelled: shading uses the mesh's normals");
  if (g.occlusionTexture.index >= 0)
    m_warnings.once("occlusionTexture", p + "/occlusionTexture",
                    "occlusion maps are ignored: the path tracer finds occlusion itself");
  // Double-sided: an emitter emits from both sides (as Cycles renders
  // Blender's import); every surface reflects on both sides either way.
  if (!g.doubleSided)
    m_warnings.once("doubleSided", p + "/doubleSided",
                    "false: back faces are not culled; Kappa's surfaces reflect on both sides, as Cycles renders them");
  else
    m.emits_both_sides = m.emissive();
  return m;
}

}  // namespace kappa
