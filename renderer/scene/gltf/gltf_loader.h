// A glTF 2.0 file (.gltf or .glb) into the format-neutral scene: the default
// scene's node hierarchy walked (matrix or TRS, without recursion: a chain of
// a million nodes is only a long loop), each mesh instance's triangle
// primitives copied in world space (strips and fans converted; points and
// lines warned and skipped), its materials (gltf_material.h), perspective
// cameras and KHR_lights_punctual lights. Refusals name the file and the
// JSON pointer of the bad element.
#pragma once

#include <filesystem>

#include "core/error.h"
#include "renderer/scene/scene.h"

namespace kappa {

/// Appends the file's triangles, materials, texture maps, cameras and
/// lights to `scene`, and its summary to Scene::gltf_files.
void load_gltf(const std::filesystem::path& file, Scene& scene, Warnings& warnings);

}  // namespace kappa
