// Reading a glTF 2.0 file (.gltf with its external or data-URI buffers, or a
// .glb) into tinygltf's model, after the checks tinygltf does not make: the
// GLB container's header and chunks, the JSON's nesting depth (tinygltf
// recurses on it), duplicate keys, data URIs that are not base64, and URIs
// that leave the file's folder or name no readable file. Refusals name the
// file and the JSON pointer of the bad element (InputError, exit 2).
#pragma once

#include "renderer/scene/gltf/tiny_gltf_config.h"

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/error.h"

namespace kappa {

struct GltfFile {
  std::filesystem::path file;
  tinygltf::Model model;
  /// Files the model named and that were read or will be (buffers, images).
  std::vector<std::filesystem::path> external_files;
  /// Per image: its bytes when the file holds it (a buffer view or a data
  /// URI), else null (the image is `model.images[i].uri`, beside the file).
  std::vector<std::shared_ptr<const std::vector<unsigned char>>> embedded_images;
};

/// Deepest JSON nesting accepted (tinygltf's parser recurses on it; real
/// files nest under 10 levels).
inline constexpr int kMaxGltfJsonDepth = 64;

/// Reads and parses `file` (.gltf or .glb by its content's magic).
GltfFile read_gltf(const std::filesystem::path& file, Warnings& warnings);

/// "/meshes/2/primitives/0": a JSON pointer from its parts.
std::string json_pointer(std::initializer_list<std::string> parts);

/// The percent-decoded form of a URI reference ("a%20b.png" -> "a b.png").
std::string percent_decoded(const std::string& uri);

}  // namespace kappa
